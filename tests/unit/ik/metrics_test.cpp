// Quality metrics: invalid input first, then each figure on data whose answer is known.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "ik/metrics.h"
#include "ik_test_support.h"

namespace motionstyle {
namespace {

// 21 canonical joints standing still at distinct places (x = joint index), 10 frames, Y-up.
Eigen::MatrixXd standingCanonical(int frames = 10) {
  Eigen::MatrixXd positions(frames, 63);
  for (int f = 0; f < frames; ++f)
    for (int c = 0; c < kCanonicalJointCount; ++c) positions.block<1, 3>(f, 3 * c) << c, 5.0, 0.0;
  return positions;
}

TEST(Metrics, RejectsInvalidInput) {
  const Eigen::MatrixXd positions = standingCanonical();
  MetricsInput input{positions, identityCanonicalJoints()};
  input.contacts = Eigen::MatrixXi::Zero(9, 4);
  EXPECT_THROW(computeMetrics(input), std::invalid_argument);
  input.contacts = Eigen::MatrixXi::Constant(10, 4, 2);
  EXPECT_THROW(computeMetrics(input), std::invalid_argument);
  input.contacts = Eigen::MatrixXi();
  input.targets = Eigen::MatrixXd::Zero(10, 60);
  EXPECT_THROW(computeMetrics(input), std::invalid_argument);
  input.targets = Eigen::MatrixXd();
  input.canonical_joints[3] = 21;
  EXPECT_THROW(computeMetrics(input), std::invalid_argument);
  input.canonical_joints = identityCanonicalJoints();
  input.bones = {{1, 30, 1.0}};
  EXPECT_THROW(computeMetrics(input), std::invalid_argument);
  input.bones.clear();
  input.fps = 0.0;
  EXPECT_THROW(computeMetrics(input), std::invalid_argument);
  input.fps = 60.0;
  input.cm_per_unit = -1.0;
  EXPECT_THROW(computeMetrics(input), std::invalid_argument);
  const Eigen::MatrixXd narrow = positions.leftCols(62);
  EXPECT_THROW(computeMetrics(MetricsInput{narrow, identityCanonicalJoints()}), std::invalid_argument);
}

TEST(Metrics, FootSkateIsTheHorizontalSpeedDuringContact) {
  Eigen::MatrixXd positions = standingCanonical();
  // The left toe slides 0.5 units per frame along x and bobs vertically (ignored); 2 cm per unit, 30 fps.
  const int toe = index(CanonicalJoint::LeftToe);
  for (int f = 0; f < 10; ++f) {
    positions(f, 3 * toe) += 0.5 * f;
    positions(f, 3 * toe + 1) += (f % 2) * 3.0;
  }
  MetricsInput input{positions, identityCanonicalJoints()};
  input.cm_per_unit = 2.0;
  input.fps = 30.0;
  input.contacts = Eigen::MatrixXi::Zero(10, 4);
  input.contacts.col(1).setOnes();  // left toe, sliding at 0.5 * 2 * 30 = 30 cm/s
  input.contacts.col(2).setOnes();  // right heel, still
  const ClipMetrics m = computeMetrics(input);
  EXPECT_EQ(m.contact_steps, 18);
  EXPECT_NEAR(m.foot_skate_cm_s, 15.0, 1e-9);
  EXPECT_NEAR(m.skate_track_cm_s[4], 15.0, 1e-9);
  EXPECT_EQ(m.skate_track_cm_s[9], 0.0);
}

// A foot with heel and toe in contact skates at the slower of the two: a heel turning up about its
// still toe (a foot rolling off) is no slide, a whole foot sliding is, once per foot.
TEST(Metrics, AFootSkatesAtItsStillestJointInContact) {
  Eigen::MatrixXd positions = standingCanonical();
  const int heel = index(CanonicalJoint::LeftAnkle), toe = index(CanonicalJoint::LeftToe);
  for (int f = 0; f < 10; ++f) {
    positions(f, 3 * heel) += 0.5 * f;  // the heel moves along the floor plane's x ...
    positions(f, 3 * heel + 1) += 1.0 * f;  // ... as it rises: a roll about the toe
  }
  MetricsInput input{positions, identityCanonicalJoints()};
  input.cm_per_unit = 2.0;
  input.fps = 30.0;
  input.contacts = Eigen::MatrixXi::Zero(10, 4);
  input.contacts.leftCols(2).setOnes();  // left heel and toe
  const ClipMetrics rolling = computeMetrics(input);
  EXPECT_EQ(rolling.contact_steps, 9);  // one per foot and step
  EXPECT_NEAR(rolling.foot_skate_cm_s, 0.0, 1e-9);

  for (int f = 0; f < 10; ++f) positions(f, 3 * toe) += 0.25 * f;  // the toe slides too, at 15 cm/s
  const ClipMetrics sliding = computeMetrics(input);
  EXPECT_NEAR(sliding.foot_skate_cm_s, 15.0, 1e-9);
  input.contacts.col(0).setZero();  // the toe alone in contact: its own speed
  EXPECT_NEAR(computeMetrics(input).foot_skate_cm_s, 15.0, 1e-9);
  input.contacts.col(0).setOnes();
  input.contacts.col(1).setZero();  // the heel alone: its own, 30 cm/s
  EXPECT_NEAR(computeMetrics(input).foot_skate_cm_s, 30.0, 1e-9);
}

TEST(Metrics, FloorPenetrationCountsOnlyFeetBelowTheFloor) {
  Eigen::MatrixXd positions = standingCanonical();
  positions(3, 3 * index(CanonicalJoint::RightAnkle) + 1) = 1.0;   // 1 unit below a floor at 2
  positions(6, 3 * index(CanonicalJoint::LeftToe) + 1) = 1.5;      // 0.5 below
  positions(6, 3 * index(CanonicalJoint::LeftWrist) + 1) = -10.0;  // not a foot joint
  MetricsInput input{positions, identityCanonicalJoints()};
  input.floor_height = 2.0;
  input.cm_per_unit = 10.0;
  const ClipMetrics m = computeMetrics(input);
  EXPECT_EQ(m.penetrating_samples, 2);
  EXPECT_NEAR(m.penetration_max_cm, 10.0, 1e-9);
  EXPECT_NEAR(m.penetration_mean_cm, 7.5, 1e-9);
}

TEST(Metrics, BoneErrorOfAnFkClipIsZeroAndOfAStretchedOneIsKnown) {
  const Motion clip = test::makeHumanoidClip(20, 30.0);
  const Eigen::MatrixXd world = worldPositions(clip);
  MetricsInput input{world, test::humanoidMapping(clip.skeleton).joints, skeletonBones(clip.skeleton)};
  EXPECT_LT(computeMetrics(input).bone_error_max_cm, 1e-9);

  const JointMapping mapping = test::humanoidMapping(clip.skeleton);
  Eigen::MatrixXd canonical = test::canonicalPositions(world, mapping);
  const std::vector<BoneReference> bones = canonicalBones(world, mapping);
  ASSERT_EQ(bones.size(), 20u);
  // Move the left hand end 2 units further along its bone at frame 5: that bone is 2 units too long.
  const int end = index(CanonicalJoint::LeftHandEnd), wrist = index(CanonicalJoint::LeftWrist);
  const Eigen::Vector3d bone = (canonical.block<1, 3>(5, 3 * end) - canonical.block<1, 3>(5, 3 * wrist)).transpose();
  canonical.block<1, 3>(5, 3 * end) += 2.0 * bone.normalized().transpose();
  // Bones through joints outside the canonical set (the clavicle between chest and upper arm) bend a
  // little; the hand bone is rigid, so it alone shows exactly the 2 units.
  std::vector<BoneReference> hand_bone;
  for (const BoneReference& reference : bones)
    if (reference.joint == end) hand_bone.push_back(reference);
  ASSERT_EQ(hand_bone.size(), 1u);
  EXPECT_EQ(hand_bone[0].parent, wrist);
  EXPECT_NEAR(hand_bone[0].length, 10.0, 1e-9);
  MetricsInput canonical_input{canonical, identityCanonicalJoints(), hand_bone};
  const ClipMetrics m = computeMetrics(canonical_input);
  EXPECT_NEAR(m.bone_error_max_cm, 2.0, 1e-9);
  EXPECT_NEAR(m.bone_error_track_cm[5], 2.0, 1e-9);
  EXPECT_LT(m.bone_error_track_cm[4], 1e-9);
}

TEST(Metrics, ResidualAndJerkHaveKnownValues) {
  Eigen::MatrixXd positions = standingCanonical(8);
  // All joints move along z as t^3 (units, t in frames): third difference 6 units/frame^3.
  for (int f = 0; f < 8; ++f)
    for (int c = 0; c < kCanonicalJointCount; ++c) positions(f, 3 * c + 2) = static_cast<double>(f * f * f);
  MetricsInput input{positions, identityCanonicalJoints()};
  input.fps = 10.0;
  input.cm_per_unit = 2.0;
  const ClipMetrics m = computeMetrics(input);
  EXPECT_NEAR(m.jerk_mean_cm_s3, 6.0 * 2.0 * 1000.0, 1e-6);
  EXPECT_FALSE(m.has_residual);

  Eigen::MatrixXd still = standingCanonical(8);
  MetricsInput residual_input{still, identityCanonicalJoints()};
  residual_input.targets = still;
  residual_input.targets.col(0).array() += 0.3;  // hips x off by 0.3 units in every frame
  residual_input.cm_per_unit = 2.0;
  const ClipMetrics r = computeMetrics(residual_input);
  EXPECT_TRUE(r.has_residual);
  EXPECT_NEAR(r.residual_max_cm, 0.6, 1e-12);
  EXPECT_NEAR(r.residual_mean_cm, 0.6 / 21.0, 1e-12);
  EXPECT_EQ(r.residual_max_frame, 0);  // the first of equal worsts
  EXPECT_EQ(r.residual_max_joint, index(CanonicalJoint::Hips));

  // Where the worst is: the left toe 2 units off at frame 5, the hips' 0.3 everywhere else.
  residual_input.targets(5, 3 * index(CanonicalJoint::LeftToe) + 1) -= 2.0;
  const ClipMetrics w = computeMetrics(residual_input);
  EXPECT_NEAR(w.residual_max_cm, 4.0, 1e-12);
  EXPECT_EQ(w.residual_max_frame, 5);
  EXPECT_EQ(w.residual_max_joint, index(CanonicalJoint::LeftToe));
  const nlohmann::json json = nlohmann::json::parse(metricsToJson(w));
  EXPECT_EQ(json["position_residual_max_frame"], 5);
  EXPECT_EQ(json["position_residual_max_joint"], "LeftToe");
}

TEST(Metrics, JsonHoldsTheFigures) {
  const Eigen::MatrixXd positions = standingCanonical();
  MetricsInput input{positions, identityCanonicalJoints()};
  input.targets = positions;
  const ClipMetrics m = computeMetrics(input);
  const nlohmann::json json = nlohmann::json::parse(metricsToJson(m, true));
  EXPECT_EQ(json["format"], "motionstyle-metrics");
  EXPECT_EQ(json["frames"], 10);
  EXPECT_EQ(json["position_residual_mean_cm"], 0.0);
  EXPECT_EQ(json["skate_track_cm_s"].size(), 10u);
  EXPECT_FALSE(nlohmann::json::parse(metricsToJson(m, false)).contains("skate_track_cm_s"));
}

}  // namespace
}  // namespace motionstyle
