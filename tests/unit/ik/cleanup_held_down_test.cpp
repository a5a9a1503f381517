// The clean-up's warning of a heel or toe that its locked contact holds under its target (a style that
// lifts the foot while the contact track holds it down): named with its frames where it happens, and
// nowhere else (ik/cleanup.h, CleanupOptions::held_down_warning_cm).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "ik/cleanup.h"
#include "ik_test_support.h"

namespace motionstyle {
namespace {

constexpr const char* kLeftHeelHeld = "held down by its contact: left heel";

class CleanupHeldDown : public ::testing::Test {
 protected:
  static constexpr int kFrames = 90;
  Motion clip = test::makeHumanoidClip(kFrames, 60.0);
  JointMapping mapping = test::humanoidMapping(clip.skeleton);
  Eigen::MatrixXd targets = test::canonicalPositions(worldPositions(clip), mapping);

  // The left foot planted where frame 20 has it through frames 20-70 (heel and toe labelled), its heel
  // raised `lift` cm over frames 40-50 while the toe stays down: a heel the style lifts mid-stance.
  Eigen::MatrixXd heelLifted(double lift) const {
    Eigen::MatrixXd lifted = targets;
    for (int f = 0; f < kFrames; ++f)
      for (CanonicalJoint joint : {CanonicalJoint::LeftAnkle, CanonicalJoint::LeftToe}) {
        lifted.block<1, 3>(f, 3 * index(joint)) = targets.block<1, 3>(std::min(f, 20), 3 * index(joint));
        if (joint == CanonicalJoint::LeftAnkle && f >= 40 && f <= 50) lifted(f, 3 * index(joint) + 1) += lift;
      }
    return lifted;
  }
  Eigen::MatrixXi leftFootPlanted() const {
    Eigen::MatrixXi contacts = Eigen::MatrixXi::Zero(kFrames, kContactCount);
    contacts.block(20, 0, 51, 2).setOnes();
    return contacts;
  }
  std::vector<CleanupWarning> warnings(const Eigen::MatrixXd& t, const Eigen::MatrixXi& contacts,
                                       const CleanupOptions& options = {}) const {
    CleanupReport report;
    cleanupMotion(CleanupInput{clip, mapping, t, contacts, Eigen::Vector3d::UnitY(), -50.0, 1.0}, options, &report);
    return report.warnings;
  }
  static std::vector<CleanupWarning> leftHeelHeld(const std::vector<CleanupWarning>& all) {
    std::vector<CleanupWarning> held;
    for (const CleanupWarning& w : all)
      if (w.text.rfind(kLeftHeelHeld, 0) == 0) held.push_back(w);
    return held;
  }
};

TEST_F(CleanupHeldDown, AStillFootOnItsContactIsNotWarnedOf) {
  EXPECT_TRUE(leftHeelHeld(warnings(heelLifted(0.0), leftFootPlanted())).empty());
}

TEST_F(CleanupHeldDown, AHeelTheStyleLiftsWhileItsContactHoldsItIsNamedWithItsFrames) {
  const std::vector<CleanupWarning> held = leftHeelHeld(warnings(heelLifted(12.0), leftFootPlanted()));
  ASSERT_EQ(held.size(), 1u);
  EXPECT_GE(held[0].first_frame, 40);
  EXPECT_LE(held[0].last_frame, 50);
  EXPECT_LT(held[0].first_frame, held[0].last_frame);
  EXPECT_NE(held[0].text.find("end the contact there to follow the style"), std::string::npos) << held[0].text;
  // The figure is how far under its target the heel was held: more than the threshold, at most the lift.
  const double cm = std::stod(held[0].text.substr(held[0].text.find("lift by ") + 8));
  EXPECT_GT(cm, CleanupOptions{}.held_down_warning_cm);
  EXPECT_LE(cm, 12.0 + 1e-9);
}

// The warning says what to do (end the contact), the residuals it causes only where: it comes before
// them, so that the few warnings a panel shows include it.
TEST_F(CleanupHeldDown, ComesBeforeTheLargeResidualsTheHeldFootCauses) {
  const std::vector<CleanupWarning> all = warnings(heelLifted(12.0), leftFootPlanted());
  const auto held = std::find_if(all.begin(), all.end(),
                                 [](const CleanupWarning& w) { return w.text.rfind(kLeftHeelHeld, 0) == 0; });
  const auto residual = std::find_if(all.begin(), all.end(), [](const CleanupWarning& w) {
    return w.text.rfind("large residual: LeftAnkle", 0) == 0;
  });
  ASSERT_NE(held, all.end());
  ASSERT_NE(residual, all.end()) << "the held heel is 12 cm off its target: a large residual too";
  EXPECT_LT(held - all.begin(), residual - all.begin());
}

// The warning carries its fix as data (CleanupWarning::contact, what a front end offers as an action):
// the contact it names, which ended over the frames it names ends the warning; no other warning has one.
TEST_F(CleanupHeldDown, TheWarningsOwnFixEndsIt) {
  const std::vector<CleanupWarning> all = warnings(heelLifted(12.0), leftFootPlanted());
  const std::vector<CleanupWarning> held = leftHeelHeld(all);
  ASSERT_EQ(held.size(), 1u);
  EXPECT_EQ(held[0].contact, static_cast<int>(ContactLabel::LeftHeel));
  for (const CleanupWarning& w : all) {
    if (w.text.rfind("held down by its contact", 0) != 0) {
      EXPECT_EQ(w.contact, -1) << w.text;
    }
  }
  Eigen::MatrixXi fixed = leftFootPlanted();
  fixed.block(held[0].first_frame, held[0].contact, held[0].last_frame - held[0].first_frame + 1, 1).setZero();
  EXPECT_TRUE(leftHeelHeld(warnings(heelLifted(12.0), fixed)).empty());
}

TEST_F(CleanupHeldDown, NoWarningWhereTheContactIsEndedOrNothingIsLocked) {
  Eigen::MatrixXi ended = leftFootPlanted();
  ended.block(38, 0, 15, 1).setZero();  // the heel's contact ended over the lift (frames 38-52)
  EXPECT_TRUE(leftHeelHeld(warnings(heelLifted(12.0), ended)).empty());
  CleanupOptions unlocked;
  unlocked.lock_contacts = false;
  EXPECT_TRUE(leftHeelHeld(warnings(heelLifted(12.0), leftFootPlanted(), unlocked)).empty());
}

TEST_F(CleanupHeldDown, ALiftUnderTheThresholdIsNotWarnedOf) {
  CleanupOptions options;
  options.held_down_warning_cm = 20.0;
  EXPECT_TRUE(leftHeelHeld(warnings(heelLifted(12.0), leftFootPlanted(), options)).empty());
}

}  // namespace
}  // namespace motionstyle
