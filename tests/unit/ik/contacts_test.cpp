// Contact detection: invalid input first, then the properties (stance found, invariant to the unit and
// the up axis, no flicker, overrides).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "features/foot_contacts.h"
#include "ik/contacts.h"
#include "ik_test_support.h"

namespace motionstyle {
namespace {

constexpr double kBodyHeight = 170.0;  // cm

// A synthetic gait: 4 joints (left ankle, left toe, right ankle, right toe) walking along +Z, Y-up, cm.
// Each foot is planted for the first 60 % of its 1-second cycle (ankle 7 cm, toe 2 cm high) and swings
// 70 cm forward, 15 cm high, for the rest. The right foot is half a cycle behind.
struct Gait {
  Eigen::MatrixXd positions;
  Eigen::MatrixXi stance;  // ground truth, frames x 4
};

Gait makeGait(double fps, double seconds) {
  const int frames = static_cast<int>(seconds * fps);
  Gait gait{Eigen::MatrixXd::Zero(frames, 12), Eigen::MatrixXi::Zero(frames, 4)};
  for (int f = 0; f < frames; ++f) {
    for (int foot = 0; foot < 2; ++foot) {
      const double t = f / fps + 0.5 * foot;
      const double cycle = std::floor(t), phase = t - cycle;
      const bool planted = phase < 0.6;
      const double swing = planted ? 0.0 : (phase - 0.6) / 0.4;
      const double progress = 0.5 - 0.5 * std::cos(M_PI * swing);  // eased swing
      const double z = 70.0 * (cycle + progress);
      const double lift = planted ? 0.0 : 15.0 * std::sin(M_PI * swing);
      const double x = foot == 0 ? 10.0 : -10.0;
      gait.positions.block<1, 3>(f, 6 * foot) << x, 7.0 + lift, z;
      gait.positions.block<1, 3>(f, 6 * foot + 3) << x, 2.0 + lift, z + 12.0;
      gait.stance(f, 2 * foot) = gait.stance(f, 2 * foot + 1) = planted ? 1 : 0;
    }
  }
  return gait;
}

const std::array<int, kContactCount> kFeet = {0, 1, 2, 3};

TEST(Contacts, RejectsInvalidInput) {
  const Gait gait = makeGait(60.0, 2.0);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  EXPECT_THROW(detectContacts(gait.positions, {0, 1, 2, 4}, up, 0.0, 60.0, kBodyHeight), std::invalid_argument);
  EXPECT_THROW(detectContacts(gait.positions, kFeet, Eigen::Vector3d(0, 0.5, 0), 0.0, 60.0, kBodyHeight),
               std::invalid_argument);
  EXPECT_THROW(detectContacts(gait.positions, kFeet, up, 0.0, 0.0, kBodyHeight), std::invalid_argument);
  EXPECT_THROW(detectContacts(gait.positions, kFeet, up, 0.0, 60.0, -1.0), std::invalid_argument);
  EXPECT_THROW(detectContacts(gait.positions.leftCols(11), kFeet, up, 0.0, 60.0, kBodyHeight), std::invalid_argument);
  Eigen::MatrixXd bad = gait.positions;
  bad(3, 4) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(detectContacts(bad, kFeet, up, 0.0, 60.0, kBodyHeight), std::invalid_argument);
  ContactDetectionOptions options;
  options.release_factor = 0.5;
  EXPECT_THROW(detectContacts(gait.positions, kFeet, up, 0.0, 60.0, kBodyHeight, options), std::invalid_argument);
}

TEST(Contacts, OverridesRejectBadShapesAndValues) {
  const ContactLabels labels = ContactLabels::Zero(5, 4);
  EXPECT_THROW(applyContactOverrides(labels, Eigen::MatrixXi::Constant(4, 4, -1)), std::invalid_argument);
  Eigen::MatrixXi overrides = Eigen::MatrixXi::Constant(5, 4, -1);
  overrides(2, 2) = 2;
  EXPECT_THROW(applyContactOverrides(labels, overrides), std::invalid_argument);
}

TEST(Contacts, FindsTheStancePhases) {
  const Gait gait = makeGait(60.0, 4.0);
  const ContactLabels labels = detectContacts(gait.positions, kFeet, Eigen::Vector3d::UnitY(), 0.0, 60.0, kBodyHeight);
  const double agreement = (labels.array() == gait.stance.array()).cast<double>().mean();
  EXPECT_GT(agreement, 0.92);
  // Mid-stance and mid-swing frames are never wrong.
  for (int f = 0; f < labels.rows(); ++f) {
    for (int foot = 0; foot < 2; ++foot) {
      const double phase = std::fmod(f / 60.0 + 0.5 * foot, 1.0);
      if (std::abs(phase - 0.3) < 0.2) {
        EXPECT_EQ(labels(f, 2 * foot), 1) << "frame " << f;
      }
      if (std::abs(phase - 0.8) < 0.1) {
        EXPECT_EQ(labels(f, 2 * foot), 0) << "frame " << f;
      }
    }
  }
}

TEST(Contacts, AreTheSameInAnyUnitAndUpAxis) {
  const Gait gait = makeGait(60.0, 4.0);
  const ContactLabels reference =
      detectContacts(gait.positions, kFeet, Eigen::Vector3d::UnitY(), 0.0, 60.0, kBodyHeight);
  // Inches, Z-up (file y -> z, z -> -y), floor raised by 10 inches.
  const double inch = 2.54;
  Eigen::MatrixXd converted(gait.positions.rows(), gait.positions.cols());
  for (int j = 0; j < 4; ++j) {
    converted.col(3 * j) = gait.positions.col(3 * j) / inch;
    converted.col(3 * j + 1) = -gait.positions.col(3 * j + 2) / inch;
    converted.col(3 * j + 2) = gait.positions.col(3 * j + 1) / inch + Eigen::VectorXd::Constant(converted.rows(), 10.0);
  }
  const ContactLabels converted_labels =
      detectContacts(converted, kFeet, Eigen::Vector3d::UnitZ(), 10.0, 60.0, kBodyHeight / inch);
  EXPECT_EQ(converted_labels, reference);
}

TEST(Contacts, ThresholdsScaleWithTheCharacter) {
  // A foot creeping at 20 cm/s is planted for a 170 cm character's default threshold (0.15 body
  // heights/s = 25.5 cm/s) but not for a 100 cm one (15 cm/s).
  Eigen::MatrixXd positions = Eigen::MatrixXd::Zero(60, 12);
  for (int f = 0; f < 60; ++f)
    for (int j = 0; j < 4; ++j) positions.block<1, 3>(f, 3 * j) << 0.0, 2.0, 20.0 * f / 60.0;
  const ContactLabels tall = detectContacts(positions, kFeet, Eigen::Vector3d::UnitY(), 0.0, 60.0, 170.0);
  const ContactLabels small = detectContacts(positions, kFeet, Eigen::Vector3d::UnitY(), 0.0, 60.0, 100.0);
  EXPECT_EQ(tall.sum(), 240);
  EXPECT_EQ(small.sum(), 0);
}

TEST(Contacts, HysteresisAndMinimumLengthRemoveFlicker) {
  Gait gait = makeGait(60.0, 4.0);
  // A one-frame 10 cm hop of the left toe in mid-stance (frame 18) must not split its contact.
  gait.positions(18, 4) += 10.0;
  const ContactLabels labels = detectContacts(gait.positions, kFeet, Eigen::Vector3d::UnitY(), 0.0, 60.0, kBodyHeight);
  for (int f = 10; f < 28; ++f) EXPECT_EQ(labels(f, 1), 1) << "frame " << f;
  const std::vector<ContactSegment> segments = contactSegments(labels, 1);
  for (const ContactSegment& segment : segments)
    if (segment.first > 0 && segment.last + 1 < labels.rows()) {
      EXPECT_GE(segment.last - segment.first + 1, 3);
    }
}

TEST(Contacts, OverridesForceLabelsOnAndOff) {
  ContactLabels automatic = ContactLabels::Zero(6, 4);
  automatic.col(0).setOnes();
  Eigen::MatrixXi overrides = Eigen::MatrixXi::Constant(6, 4, -1);
  overrides(2, 0) = 0;
  overrides(4, 3) = 1;
  const ContactLabels result = applyContactOverrides(automatic, overrides);
  EXPECT_EQ(result(2, 0), 0);
  EXPECT_EQ(result(1, 0), 1);
  EXPECT_EQ(result(4, 3), 1);
  EXPECT_EQ(result.sum(), 6);
}

TEST(Contacts, SegmentsAreInclusiveRuns) {
  ContactLabels labels = ContactLabels::Zero(8, 4);
  labels.col(2).segment(1, 3).setOnes();
  labels(7, 2) = 1;
  const std::vector<ContactSegment> segments = contactSegments(labels, 2);
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[0].first, 1);
  EXPECT_EQ(segments[0].last, 3);
  EXPECT_EQ(segments[1].first, 7);
  EXPECT_EQ(segments[1].last, 7);
}

TEST(Contacts, BodyHeightAndFloorOfAHandBuiltRig) {
  const Motion clip = test::makeHumanoidClip(30, 30.0);
  EXPECT_NEAR(restPoseBodyHeight(clip.skeleton, Eigen::Vector3d::UnitY()), 162.0, 1e-9);
  const Gait gait = makeGait(60.0, 2.0);
  EXPECT_NEAR(estimateFloorHeight(gait.positions, kFeet, Eigen::Vector3d::UnitY()), 2.0, 1e-9);
}

// A static root above the hips (Bandai's joint_Root, a reference node) whose child's offset holds
// where the clip starts: the body height is the body's, wherever the clip starts. Before, it spanned
// the root too (Bandai: 100 cm for a clip starting at the origin, 458 for one starting 450 cm ahead).
TEST(Contacts, BodyHeightIsTheBodysWhereverAStaticRootPlacesIt) {
  const Skeleton body = test::makeHumanoid(true);
  for (const Eigen::Vector3d& start : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(-17, 93, 453), Eigen::Vector3d(1, 94, -452)}) {
    Skeleton placed;
    Joint root;
    root.name = "Reference";
    root.channels = body.joints[0].channels;
    placed.joints.push_back(root);
    for (Joint joint : body.joints) {
      joint.parent += 1;
      if (joint.parent == 0) joint.offset = start;
      placed.joints.push_back(joint);
    }
    EXPECT_NEAR(restPoseBodyHeight(placed, Eigen::Vector3d::UnitY()), 162.0, 1e-9) << start.transpose();
  }
}

}  // namespace
}  // namespace motionstyle
