#include <gtest/gtest.h>

#include <numbers>

#include "bvh/bvh_reader.h"
#include "common/errors.h"
#include "features/representation.h"
#include "motion/kinematics.h"
#include "motion/resample.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

// Largest distance between matching joints of two frames x 63 position matrices.
double maxJointError(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  double worst = 0.0;
  for (Eigen::Index f = 0; f < a.rows(); ++f)
    for (int c = 0; c < kCanonicalJointCount; ++c)
      worst = std::max(worst, (a.row(f).segment<3>(3 * c) - b.row(f).segment<3>(3 * c)).norm());
  return worst;
}

TEST(Representation, RejectsClipTooShort) {
  Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton);
  motion.values.conservativeResize(1, Eigen::NoChange);
  EXPECT_THROW(extractFeatures(motion, mapping), InputError);
}

TEST(Representation, RejectsFeaturesOfWrongShape) {
  EXPECT_THROW(referenceWorldPositions(Eigen::MatrixXd::Zero(65, 10), FeatureAnchor{}), std::invalid_argument);
  EXPECT_THROW(canonicalBoneLengths(Eigen::MatrixXd::Zero(3, 10)), std::invalid_argument);
}

// The acceptance: BVH -> 66 features -> global positions matches forward kinematics of the
// canonical joints over a whole real clip, root drift included, within 1% of body height, through the
// retargeting to the reference proportions and back, and without it.
void expectRoundTrip(const std::string& name) {
  const Motion motion = readBvh(test::fixture(name));
  const JointMapping mapping = mapJoints(motion.skeleton, name);
  const Motion at60 = resampleMotion(motion, 60.0);
  const Eigen::MatrixXd expected = canonicalJointPositions(at60, mapping);
  const double body_height = skeletalHeight(motion.skeleton, mapping);

  const MotionFeatures features = extractFeatures(motion, mapping);
  ASSERT_EQ(features.values.rows(), kFeatureCount);
  ASSERT_EQ(features.frameCount(), at60.frameCount());
  for (int c = 1; c < kCanonicalJointCount; ++c)  // the fixtures have every bone, hands included
    EXPECT_GT(features.anchor.proportions.bone_length[static_cast<std::size_t>(c)], 1.0) << name << " bone " << c;
  EXPECT_LT(maxJointError(expected, canonicalWorldPositions(features.values, features.anchor)), 0.01 * body_height)
      << name;

  FeatureOptions own_proportions;
  own_proportions.retarget_proportions = false;
  const MotionFeatures unretargeted = extractFeatures(motion, mapping, own_proportions);
  EXPECT_LT(maxJointError(expected, canonicalWorldPositions(unretargeted.values, unretargeted.anchor)), 0.01 * body_height)
      << name;
  // The hips travel: the test would be weak on a clip standing still.
  const int hips = 3 * index(CanonicalJoint::Hips);
  EXPECT_GT((expected.row(expected.rows() - 1).segment<3>(hips) - expected.row(0).segment<3>(hips)).norm(),
            0.5 * body_height)
      << name;
}

TEST(Representation, RoundTripCmuWalk) { expectRoundTrip("cmu_131_01.bvh"); }
TEST(Representation, RoundTripZombieZUp) { expectRoundTrip("zombie.bvh"); }

TEST(Representation, CanonicalJointPositionsAreTheMappedColumnsOfForwardKinematics) {
  const Motion motion = readBvh(test::fixture("zombie.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton);
  const Eigen::MatrixXd canonical = canonicalJointPositions(motion, mapping);
  const Eigen::MatrixXd all = worldPositions(motion);
  ASSERT_EQ(canonical.rows(), all.rows());
  ASSERT_EQ(canonical.cols(), 3 * kCanonicalJointCount);
  for (int c = 0; c < kCanonicalJointCount; ++c)
    EXPECT_LT((canonical.middleCols<3>(3 * c) - all.middleCols<3>(3 * mapping.joints[static_cast<size_t>(c)])).cwiseAbs().maxCoeff(),
              1e-10)
        << "canonical joint " << c;
}

// extractFeatures resamples local transforms (resampleLocalPoses); going through resampleMotion's Euler
// angles first must give the same features and anchor, to rounding: 30 -> 60 fps (zombie, the
// midpoint path) and 120 -> 60 fps (CMU, decimation).
TEST(Representation, ResamplingInsideEqualsResamplingTheMotionFirst) {
  for (const std::string name : {"zombie.bvh", "cmu_131_01.bvh"}) {
    const Motion motion = readBvh(test::fixture(name));
    const JointMapping mapping = mapJoints(motion.skeleton, name);
    const MotionFeatures inside = extractFeatures(motion, mapping);
    const MotionFeatures first = extractFeatures(resampleMotion(motion, kDefaultFeatureFps), mapping);
    ASSERT_EQ(inside.frameCount(), first.frameCount()) << name;
    EXPECT_LT((inside.values - first.values).cwiseAbs().maxCoeff(), 1e-9) << name;
    EXPECT_EQ(inside.contacts, first.contacts) << name;
    EXPECT_NEAR(inside.anchor.scale, first.anchor.scale, 1e-12) << name;
    EXPECT_NEAR(inside.anchor.floor_height, first.anchor.floor_height, 1e-9) << name;
    EXPECT_NEAR(inside.anchor.start_heading, first.anchor.start_heading, 1e-12) << name;
    EXPECT_LT((inside.anchor.start_root - first.anchor.start_root).cwiseAbs().maxCoeff(), 1e-9) << name;
    EXPECT_EQ(inside.anchor.convention.up_axis, first.anchor.convention.up_axis) << name;
  }
}

TEST(Representation, FeaturesAreInvariantToWhereTheClipIsOnTheFloor) {
  // Turning the whole clip about the up axis and moving it on the floor changes only the anchor.
  Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton);
  const MotionFeatures original = extractFeatures(motion, mapping);

  const double angle = 0.7;
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()));
  LocalPoses poses = localPoses(motion);
  for (int f = 0; f < poses.frames; ++f) {
    poses.rotation(f, 0) = turn * poses.rotation(f, 0);
    poses.translation(f, 0) = turn * poses.translation(f, 0) + Eigen::Vector3d(30.0, 0.0, -12.0);
  }
  setLocalPoses(poses, motion);
  const MotionFeatures moved = extractFeatures(motion, mapping);
  EXPECT_LT((moved.values - original.values).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_NEAR(std::remainder(moved.anchor.start_heading - original.anchor.start_heading - angle, 2 * std::numbers::pi),
              0.0, 1e-6);
}

// A clip derived from another (a cleaned result) is measured in that clip's frame: raised 5 units, it
// reads that much higher, where measured on its own its floor and stance are found again.
TEST(Representation, ADerivedClipIsMeasuredInTheFrameOfTheClipItCameFrom) {
  Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton);
  const MotionFeatures original = extractFeatures(motion, mapping);
  FeatureOptions derived;
  derived.derived_from = original.anchor;
  EXPECT_LT((extractFeatures(motion, mapping, derived).values - original.values).cwiseAbs().maxCoeff(), 1e-9);

  LocalPoses poses = localPoses(motion);
  const Eigen::Vector3d up = original.anchor.convention.fileUp();
  for (int f = 0; f < poses.frames; ++f) poses.translation(f, 0) += 5.0 * up;
  setLocalPoses(poses, motion);
  const MotionFeatures remeasured = extractFeatures(motion, mapping);
  EXPECT_LT((remeasured.values - original.values).cwiseAbs().maxCoeff(), 1e-6);
  const MotionFeatures in_frame = extractFeatures(motion, mapping, derived);
  EXPECT_EQ(in_frame.anchor.floor_height, original.anchor.floor_height);
  EXPECT_EQ(in_frame.anchor.retarget_height_shift, original.anchor.retarget_height_shift);
  // In reference cm, then scaled with the hips' height to the reference legs (proportions.h).
  const double raised_cm = 5.0 * original.anchor.convention.cm_per_unit * original.anchor.scale *
                           referenceProportions().legLength() / original.anchor.proportions.legLength();
  for (int row = 0; row < kFeatureCount; ++row) {
    const bool height = row < 3 * kCanonicalJointCount && row % 3 == 1;
    const Eigen::ArrayXd change = in_frame.values.row(row).array() - original.values.row(row).array();
    EXPECT_LT((change - (height ? raised_cm : 0.0)).abs().maxCoeff(), 1e-6) << "row " << row;
  }
}

TEST(Representation, FeaturesAreAtTheReferenceScaleWhateverTheCharacterSize) {
  Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton);
  FeatureOptions options;
  options.unit = "cmu";
  const MotionFeatures original = extractFeatures(motion, mapping, options);
  // A character 1.5 times larger (every length scaled) gives the same features.
  for (Joint& joint : motion.skeleton.joints) joint.offset *= 1.5;
  LocalPoses poses = localPoses(motion);
  for (int f = 0; f < poses.frames; ++f) poses.translation(f, 0) *= 1.5;
  setLocalPoses(poses, motion);
  const MotionFeatures larger = extractFeatures(motion, mapping, options);
  EXPECT_NEAR(larger.anchor.scale * 1.5, original.anchor.scale, 1e-12);
  EXPECT_LT((larger.values - original.values).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(Representation, FacingIsPlusZAndHipsAreAboveTheRoot) {
  const Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const MotionFeatures features = extractFeatures(motion, mapJoints(motion.skeleton));
  // In the root frame the left hip is on +X and the hips are roughly above the root.
  const Eigen::RowVectorXd left_hip_x = features.values.row(3 * index(CanonicalJoint::LeftHip));
  const Eigen::RowVectorXd right_hip_x = features.values.row(3 * index(CanonicalJoint::RightHip));
  EXPECT_GT((left_hip_x - right_hip_x).minCoeff(), 0.0);
  EXPECT_LT(features.values.row(3 * index(CanonicalJoint::Hips)).cwiseAbs().maxCoeff(), 20.0);
  // Walking forward: mean forward velocity is positive, sideways is small in comparison.
  EXPECT_GT(features.values.row(kForwardVelocity).mean(), 0.2);
  EXPECT_LT(std::abs(features.values.row(kSidewaysVelocity).mean()), 0.5 * features.values.row(kForwardVelocity).mean());
}

TEST(Representation, BoneLengthsAreThoseOfTheReferenceCharacter) {
  const Motion motion = readBvh(test::fixture("zombie.bvh"));
  const MotionFeatures features = extractFeatures(motion, mapJoints(motion.skeleton));
  const Eigen::VectorXd lengths = canonicalBoneLengths(features.values);
  using C = CanonicalJoint;
  const double legs = 0.5 * (lengths[index(C::LeftKnee)] + lengths[index(C::LeftAnkle)] + lengths[index(C::RightKnee)] +
                             lengths[index(C::RightAnkle)]);
  const double trunk = lengths[index(C::Spine)] + lengths[index(C::Chest)] + lengths[index(C::Neck)] + lengths[index(C::Head)];
  // Straight lines between joints: never longer than the rest-pose measure, close to it for a walk.
  EXPECT_NEAR(legs + trunk, kReferenceSkeletalHeightCm, 0.03 * kReferenceSkeletalHeightCm);
}

}  // namespace
}  // namespace motionstyle
