// Augmentation (style/augmentation.h), path mode (style/path_mode.h), root paths
// (features/root_path.h) and familiarity (style/familiarity.h): invalid input first, then properties.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "features/root_path.h"
#include "mapping/joint_mapping.h"
#include "motion/kinematics.h"
#include "features/rig_canonicalisation.h"
#include "style/augmentation.h"
#include "style/familiarity.h"
#include "style/path_mode.h"
#include "style/stylizer.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

using style::AugmentationOptions;

struct SourceClip {
  Motion motion;
  JointMapping mapping;
  style::MotionClip clip;
};

SourceClip source(const std::string& name) {
  SourceClip s;
  s.motion = readBvh(test::fixture(name));
  s.mapping = mapJoints(s.motion.skeleton, name);
  s.clip = style::makeMotionClip(s.motion, s.mapping, test::fixture(name));
  return s;
}

Eigen::Vector3d meanBoneDirection(const Eigen::MatrixXd& features, CanonicalJoint joint) {
  const int c = index(joint), p = kCanonicalParent[static_cast<std::size_t>(c)];
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Eigen::Index f = 0; f < features.cols(); ++f)
    sum += (features.col(f).segment<3>(3 * c) - features.col(f).segment<3>(3 * p)).normalized();
  return sum.normalized();
}

TEST(AugmentationOptionsTest, RejectsOutOfRangeSettings) {
  const auto bad = [](auto change) {
    AugmentationOptions options;
    change(options);
    return options;
  };
  EXPECT_THROW(bad([](AugmentationOptions& o) { o.girdle_offset_degrees = -1; }).validate(), std::invalid_argument);
  EXPECT_THROW(bad([](AugmentationOptions& o) { o.offset_degrees = 91; }).validate(), std::invalid_argument);
  EXPECT_THROW(bad([](AugmentationOptions& o) { o.proportion_jitter = 0.5; }).validate(), std::invalid_argument);
  EXPECT_THROW(bad([](AugmentationOptions& o) { o.time_warp = 0.9; }).validate(), std::invalid_argument);
  EXPECT_THROW(bad([](AugmentationOptions& o) { o.time_warp = NAN; }).validate(), std::invalid_argument);
  EXPECT_THROW(bad([](AugmentationOptions& o) { o.mirror_probability = 1.5; }).validate(), std::invalid_argument);
  EXPECT_NO_THROW(style::defaultAugmentation().validate());
  EXPECT_FALSE(AugmentationOptions{}.enabled());
  EXPECT_TRUE(style::defaultAugmentation().enabled());
}

TEST(AugmentationTest, IdentityDrawLeavesTheFeaturesExactlyAsTheyWere) {
  const SourceClip s = source("zombie.bvh");
  std::mt19937 rng(3);
  const style::Augmentation identity = style::drawAugmentation(AugmentationOptions{}, rng);
  const style::MotionClip same = style::augmentedClip(s.motion, s.mapping, s.clip, identity, {});
  EXPECT_EQ(same.features.values, s.clip.features.values);
  EXPECT_EQ(same.features.contacts, s.clip.features.contacts);
}

// The representation is in the root frame and on the floor: a clip turned about the up axis and
// raised gives the same features, which is why the augmentation has no height or heading part.
TEST(AugmentationTest, HeightAndHeadingAreInvariant) {
  const SourceClip s = source("cmu_131_01.bvh");  // Y-up
  Motion moved = s.motion;
  // Raise by 7 units and turn the whole clip by 40 degrees about +Y (the root's position and rotation).
  LocalPoses poses = localPoses(moved);
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(40.0 * std::numbers::pi / 180.0, Eigen::Vector3d::UnitY()));
  for (int f = 0; f < poses.frames; ++f) {
    poses.translation(f, 0) = turn * poses.translation(f, 0) + Eigen::Vector3d(0, 7, 0);
    poses.rotation(f, 0) = turn * poses.rotation(f, 0);
  }
  setLocalPoses(poses, moved);
  const style::MotionClip turned = style::makeMotionClip(moved, s.mapping, test::fixture("cmu_131_01.bvh"));
  EXPECT_LT((turned.features.values - s.clip.features.values).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(AugmentationTest, MirroringTwiceIsTheIdentityAndSwapsSides) {
  const SourceClip s = source("cmu_131_01.bvh");
  style::MotionClip mirrored = s.clip;
  style::mirrorClip(mirrored);
  const auto left = 3 * index(CanonicalJoint::LeftAnkle), right = 3 * index(CanonicalJoint::RightAnkle);
  EXPECT_EQ(mirrored.features.values.row(left), -s.clip.features.values.row(right));
  EXPECT_EQ(mirrored.features.values.row(kSidewaysVelocity), -s.clip.features.values.row(kSidewaysVelocity));
  EXPECT_EQ(mirrored.features.values.row(kForwardVelocity), s.clip.features.values.row(kForwardVelocity));
  EXPECT_EQ(mirrored.features.contacts.row(0), s.clip.features.contacts.row(2));
  style::mirrorClip(mirrored);
  EXPECT_EQ(mirrored.features.values, s.clip.features.values);
  EXPECT_EQ(mirrored.features.contacts, s.clip.features.contacts);
  EXPECT_EQ(mirrored.bone_lengths, s.clip.bone_lengths);
}

TEST(AugmentationTest, TimeWarpChangesTheClipsLengthBySpeed) {
  const SourceClip s = source("zombie.bvh");
  style::Augmentation faster;
  faster.speed = 1.25;
  const style::MotionClip clip = style::augmentedClip(s.motion, s.mapping, s.clip, faster, {});
  EXPECT_NEAR(clip.frameCount(), s.clip.frameCount() / 1.25, 2.0);
  // Covered ground is the same; the speed is 1.25x.
  EXPECT_NEAR(summariseRootPath(clip.features.values).distance_cm,
              summariseRootPath(s.clip.features.values).distance_cm, 0.02 * summariseRootPath(s.clip.features.values).distance_cm);
}

// On clips as captured (the loss network's training data): content clips are canonicalised, which
// turns the girdle back to the reference placement (features/rig_canonicalisation.h).
TEST(AugmentationTest, GirdleRotationTurnsTheBoneByItsAngle) {
  SourceClip s = source("cmu_131_01.bvh");
  style::DatasetOptions as_captured;
  as_captured.features.canonical_rig = false;
  s.clip = style::makeMotionClip(s.motion, s.mapping, test::fixture("cmu_131_01.bvh"), as_captured);
  style::Augmentation turned;
  const double degrees = 25.0;
  // About the rig's forward axis of the hips' frame: the hip joint moves up or down.
  turned.offset_rotation[static_cast<std::size_t>(index(CanonicalJoint::LeftHip))] =
      Eigen::Quaterniond(Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, Eigen::Vector3d::UnitZ()));
  const style::MotionClip clip = style::augmentedClip(s.motion, s.mapping, s.clip, turned, as_captured);
  const Eigen::Vector3d before = meanBoneDirection(s.clip.features.values, CanonicalJoint::LeftHip);
  const Eigen::Vector3d after = meanBoneDirection(clip.features.values, CanonicalJoint::LeftHip);
  const double angle = std::acos(std::clamp(before.dot(after), -1.0, 1.0)) * 180.0 / std::numbers::pi;
  EXPECT_GT(angle, 0.5 * degrees);
  EXPECT_LT(angle, 1.5 * degrees);
  // The other side is untouched.
  EXPECT_GT(meanBoneDirection(s.clip.features.values, CanonicalJoint::RightHip)
                .dot(meanBoneDirection(clip.features.values, CanonicalJoint::RightHip)),
            0.999);
  // As content, both come out with the reference placement.
  const style::MotionClip content = style::augmentedClip(s.motion, s.mapping, s.clip, turned, {});
  const Eigen::Vector3d& reference = referenceGirdleDirections()[static_cast<std::size_t>(index(CanonicalJoint::LeftHip))];
  EXPECT_GT(meanBoneDirection(content.features.values, CanonicalJoint::LeftHip).dot(reference), 0.9999);
}

TEST(AugmentationTest, EpochsAreDeterministicAndDiffer) {
  style::DatasetOptions options;
  options.keep_motion = true;
  const std::vector<style::MotionClip> clips = {style::loadMotionClip(test::fixture("zombie.bvh"), options)};
  const AugmentationOptions augmentation = style::defaultAugmentation();
  const auto a = style::augmentedEpoch(clips, augmentation, 1, 3, options);
  const auto b = style::augmentedEpoch(clips, augmentation, 1, 3, options);
  const auto c = style::augmentedEpoch(clips, augmentation, 1, 4, options);
  EXPECT_EQ(a[0].features.values, b[0].features.values);
  EXPECT_NE(a[0].features.values.cols() == c[0].features.values.cols() ? (a[0].features.values - c[0].features.values).norm() : 1.0, 0.0);
  // Without a kept motion a clip passes through as it is.
  const std::vector<style::MotionClip> plain = {style::loadMotionClip(test::fixture("zombie.bvh"))};
  EXPECT_EQ(style::augmentedEpoch(plain, augmentation, 1, 3, {})[0].features.values, plain[0].features.values);
}

TEST(PathModeTest, ContentCopiesTheRootVelocitiesAndStyleKeepsTheOutputs) {
  Eigen::MatrixXd short_rows(65, 4);
  EXPECT_THROW(style::applyPathMode(short_rows, Eigen::MatrixXd::Zero(66, 4), style::PathMode::Content),
               std::invalid_argument);
  Eigen::MatrixXd wrong_length(66, 3);
  EXPECT_THROW(style::applyPathMode(wrong_length, Eigen::MatrixXd::Zero(66, 4), style::PathMode::Style), std::invalid_argument);
  const Eigen::MatrixXd content = Eigen::MatrixXd::Random(66, 10);
  const Eigen::MatrixXd output = Eigen::MatrixXd::Random(66, 10);
  Eigen::MatrixXd kept = output;
  style::applyPathMode(kept, content, style::PathMode::Content);
  EXPECT_EQ(kept.middleRows<3>(kSidewaysVelocity), content.middleRows<3>(kSidewaysVelocity));
  EXPECT_EQ(kept.topRows(63), output.topRows(63));
  Eigen::MatrixXd free = output;
  style::applyPathMode(free, content, style::PathMode::Style);
  EXPECT_EQ(free, output);
  EXPECT_EQ(style::parsePathMode("content"), style::PathMode::Content);
  EXPECT_EQ(style::parsePathMode("style"), style::PathMode::Style);
  EXPECT_FALSE(style::parsePathMode("Content"));
}

TEST(PathModeTest, TheStylizerKeepsTheContentsPathUnlessToldOtherwise) {
  const style::Stylizer stylizer(test::tinyStyleModel());
  const Eigen::MatrixXd& content = test::fixtureClips()[0].features.values;
  const Eigen::MatrixXd kept = stylizer.stylizeFeatures(content, {}, 1.0);
  EXPECT_EQ(kept.middleRows<3>(kSidewaysVelocity), content.middleRows<3>(kSidewaysVelocity));
  const Eigen::MatrixXd free = stylizer.stylizeFeatures(content, {}, 1.0, style::PathMode::Style);
  EXPECT_NE(free.middleRows<3>(kSidewaysVelocity), content.middleRows<3>(kSidewaysVelocity));
  EXPECT_EQ(free.topRows(63), kept.topRows(63));
}

TEST(RootPathTest, StraightAndTurningPaths) {
  EXPECT_THROW(summariseRootPath(Eigen::MatrixXd::Zero(65, 3)), std::invalid_argument);
  Eigen::MatrixXd straight = Eigen::MatrixXd::Zero(66, 10);
  straight.row(kForwardVelocity).setConstant(2.0);
  const RootPathSummary a = summariseRootPath(straight);
  EXPECT_DOUBLE_EQ(a.distance_cm, 20.0);
  EXPECT_NEAR(a.displacement.y(), 20.0, 1e-12);  // (x, z): forward is +Z
  Eigen::MatrixXd turning = straight;
  turning.row(kTurningVelocity).setConstant(std::numbers::pi / 10.0);  // half a turn over the clip
  const RootPathSummary b = summariseRootPath(turning);
  EXPECT_NEAR(b.heading_change, std::numbers::pi, 1e-12);
  EXPECT_LT(b.displacement.norm(), a.displacement.norm());
  const RootPathComparison same = compareRootPaths(a, a);
  EXPECT_DOUBLE_EQ(same.distance_ratio, 1.0);
  EXPECT_DOUBLE_EQ(same.end_error_fraction, 0.0);
  const RootPathComparison slower = compareRootPaths(a, summariseRootPath(straight * 0.5));
  EXPECT_NEAR(slower.distance_ratio, 0.5, 1e-12);
  EXPECT_NEAR(slower.end_error_fraction, 0.5, 1e-12);
}

TEST(FamiliarityTest, ReadsTheReconstructionErrorPerFrameAndPerClip) {
  EXPECT_EQ(style::familiarityLevel(0.0), style::FamiliarityLevel::Familiar);
  EXPECT_EQ(style::familiarityLevel(style::kFamiliarMaxCm), style::FamiliarityLevel::Familiar);
  EXPECT_EQ(style::familiarityLevel(style::kFamiliarMaxCm + 0.01), style::FamiliarityLevel::Unusual);
  EXPECT_EQ(style::familiarityLevel(style::kUnusualMaxCm + 0.01), style::FamiliarityLevel::Far);
  const nn::LossNetworkModel loss_network = test::tinyLossNetworkModel();
  EXPECT_THROW(style::measureFamiliarity(loss_network, Eigen::MatrixXd::Zero(65, 10)), std::invalid_argument);
  EXPECT_THROW(style::measureFamiliarity(loss_network, Eigen::MatrixXd::Zero(66, 0)), std::invalid_argument);
  const style::MotionClip& clip = test::fixtureClips()[1];
  const style::Familiarity f = style::measureFamiliarity(loss_network, clip.features.values);
  ASSERT_EQ(f.per_frame_cm.size(), static_cast<std::size_t>(clip.frameCount()));
  double sum = 0.0;
  for (double e : f.per_frame_cm) {
    EXPECT_GE(e, 0.0);
    sum += e;
  }
  EXPECT_NEAR(f.mean_cm, sum / clip.frameCount(), 1e-9);
  EXPECT_GE(f.worst_second_cm, f.mean_cm * 0.999);
  EXPECT_EQ(f.level, style::familiarityLevel(f.mean_cm));
  EXPECT_NE(style::familiaritySummary(f).find(style::familiarityName(f.level)), std::string::npos);
  // A clip far from anything the network saw (poses scaled up 3x) reads as less familiar.
  Eigen::MatrixXd strange = clip.features.values;
  strange.topRows(63) *= 3.0;
  EXPECT_GT(style::measureFamiliarity(loss_network, strange).mean_cm, f.mean_cm);
}

}  // namespace
}  // namespace motionstyle
