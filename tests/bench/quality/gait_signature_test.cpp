// gait_signature.h: invalid input first, then its figures on poses whose answer is known by
// construction, then the share's properties (none, whole, clamped, below resolution).
#include "gait_signature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "features/feature_layout.h"

namespace motionstyle::bench {
namespace {

void setJoint(Eigen::MatrixXd& f, CanonicalJoint j, Eigen::Index t, double x, double y, double z) {
  f.block<3, 1>(3 * index(j), t) = Eigen::Vector3d(x, y, z);
}

// A person standing straight (+X left, +Y up, facing +Z), legs and arms straight down; the wrists swing
// forward and back by `swing` cm over the frames (+swing, -swing, ...). `lean` tips the neck and head
// forward by that many cm.
Eigen::MatrixXd standing(int frames, double swing = 0.0, double lean = 0.0) {
  using J = CanonicalJoint;
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(kFeatureCount, frames);
  for (Eigen::Index t = 0; t < frames; ++t) {
    const double z = (t % 2 == 0 ? 1.0 : -1.0) * swing;
    setJoint(f, J::Hips, t, 0, 90, 0);
    for (const double side : {1.0, -1.0}) {
      const bool left = side > 0;
      setJoint(f, left ? J::LeftHip : J::RightHip, t, side * 8, 90, 0);
      setJoint(f, left ? J::LeftKnee : J::RightKnee, t, side * 8, 50, 0);
      setJoint(f, left ? J::LeftAnkle : J::RightAnkle, t, side * 8, 10, 0);
      setJoint(f, left ? J::LeftToe : J::RightToe, t, side * 8, 0, 12);
      setJoint(f, left ? J::LeftUpperArm : J::RightUpperArm, t, side * 18, 140, 0);
      setJoint(f, left ? J::LeftElbow : J::RightElbow, t, side * 18, 112, 0);
      setJoint(f, left ? J::LeftWrist : J::RightWrist, t, side * 18, 85, z);
      setJoint(f, left ? J::LeftHandEnd : J::RightHandEnd, t, side * 18, 80, z);
    }
    setJoint(f, J::Spine, t, 0, 110, 0);
    setJoint(f, J::Chest, t, 0, 130, 0);
    setJoint(f, J::Neck, t, 0, 150, lean);
    setJoint(f, J::Head, t, 0, 165, lean);
  }
  return f;
}

TEST(GaitSignature, RejectsFeaturesOfAnotherShape) {
  EXPECT_THROW(gaitSignature(Eigen::MatrixXd::Zero(kFeatureCount, 0)), std::invalid_argument);
  EXPECT_THROW(gaitSignature(Eigen::MatrixXd::Zero(kFeatureCount - 3, 10)), std::invalid_argument);
}

TEST(GaitSignature, ReadsAStandingPoseAsBuilt) {
  const GaitSignature g = gaitSignature(standing(10, 6.0, 60.0));
  EXPECT_DOUBLE_EQ(g[kHeadHeight], 165.0);
  EXPECT_DOUBLE_EQ(g[kHipsHeight], 90.0);
  EXPECT_NEAR(g[kTrunkLean], std::atan2(60.0, 60.0), 1e-12);  // the neck 60 cm up and 60 cm forward of the hips
  EXPECT_NEAR(g[kKneeAngle], std::numbers::pi, 1e-6);  // straight knees
  // The forearm 27 cm down and 6 cm forward or back.
  EXPECT_NEAR(g[kElbowAngle], std::numbers::pi - std::atan2(6.0, 27.0), 1e-12);
  EXPECT_DOUBLE_EQ(g[kHandHeight], -5.0);  // wrists 5 cm under the hips
  EXPECT_DOUBLE_EQ(g[kStanceWidth], 16.0);  // ankles 16 cm apart
  EXPECT_DOUBLE_EQ(g[kHandSpread], 18.0);  // wrists 18 cm out from the hips
  EXPECT_DOUBLE_EQ(g[kArmSwing], 6.0);  // +-6 cm forward swing
}

TEST(GaitSignature, ShareIsNoneForTheContentAndWholeForTheStyle) {
  const GaitSignature content = gaitSignature(standing(10, 2.0, 0.0));
  const GaitSignature style = gaitSignature(standing(10, 12.0, 30.0));
  EXPECT_DOUBLE_EQ(gaitSignatureShare(content, style, content), 0.0);
  EXPECT_DOUBLE_EQ(gaitSignatureShare(content, style, style), 1.0);
  // Halfway in both figures the style changes (swing and lean: both linear in what moved here, the lean
  // only nearly): about a half.
  const GaitSignature halfway = gaitSignature(standing(10, 7.0, 15.0));
  EXPECT_NEAR(gaitSignatureShare(content, style, halfway), 0.5, 0.05);
  // Away from the style: negative.
  EXPECT_LT(gaitSignatureShare(content, style, gaitSignature(standing(10, 0.0, -10.0))), 0.0);
}

TEST(GaitSignature, ShareIsClampedAndIgnoresDifferencesBelowResolution) {
  const GaitSignature content = gaitSignature(standing(10, 2.0));
  const GaitSignature style = gaitSignature(standing(10, 4.0));  // only the swing differs, by 2 cm
  EXPECT_DOUBLE_EQ(gaitSignatureShare(content, style, gaitSignature(standing(10, 40.0))), 2.0);
  EXPECT_DOUBLE_EQ(gaitSignatureShare(content, style, gaitSignature(standing(10, -40.0))), 2.0);  // |swing| again
  const GaitSignature barely = gaitSignature(standing(10, 2.3));  // 0.3 cm: below the swing's resolution
  EXPECT_DOUBLE_EQ(gaitSignatureShare(content, barely, style), 0.0);
}

}  // namespace
}  // namespace motionstyle::bench
