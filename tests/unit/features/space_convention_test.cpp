#include <gtest/gtest.h>

#include <functional>

#include "bvh/bvh_reader.h"
#include "common/errors.h"
#include "features/representation.h"
#include "features/space_convention.h"
#include "mapping/joint_mapping.h"
#include "motion/kinematics.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

struct LoadedClip {
  Motion motion;
  JointMapping mapping;
  Eigen::MatrixXd world;      // every joint
  Eigen::MatrixXd canonical;  // the 21 canonical joints (what detectSpaceConvention reads)
};

LoadedClip load(const std::string& name) {
  LoadedClip clip{readBvh(test::fixture(name)), {}, {}, {}};
  clip.mapping = mapJoints(clip.motion.skeleton, name);
  clip.world = worldPositions(clip.motion);
  clip.canonical = canonicalJointPositions(clip.motion, clip.mapping);
  return clip;
}

TEST(SpaceConvention, RejectsPositionsThatAreNotTheCanonicalJoints) {
  const LoadedClip clip = load("cmu_131_01.bvh");
  EXPECT_THROW(detectSpaceConvention(clip.motion.skeleton, clip.canonical.leftCols(6), clip.mapping), std::invalid_argument);
  EXPECT_THROW(detectSpaceConvention(clip.motion.skeleton, clip.world, clip.mapping), std::invalid_argument);
  EXPECT_THROW(detectSpaceConvention(clip.motion.skeleton, clip.canonical.topRows(0), clip.mapping), std::invalid_argument);
}

TEST(SpaceConvention, RejectsUnknownUnit) {
  const LoadedClip clip = load("cmu_131_01.bvh");
  EXPECT_THROW(detectSpaceConvention(clip.motion.skeleton, clip.canonical, clip.mapping, std::string("furlong")),
               std::invalid_argument);
}

// The clip with every OFFSET replaced by `offset(joint index)`: a rest pose of no height.
Motion withOffsets(const Motion& motion, const std::function<Eigen::Vector3d(int)>& offset) {
  Motion flat = motion;
  for (int j = 0; j < flat.skeleton.jointCount(); ++j) flat.skeleton.joints[static_cast<size_t>(j)].offset = offset(j);
  return flat;
}

void expectUnmeasurable(const Motion& motion, const JointMapping& mapping) {
  try {
    requireMeasurableRestPose(motion, mapping);
    ADD_FAILURE() << "accepted a rest pose on one line";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), motion.source);
    EXPECT_NE(error.detail().find("one line"), std::string::npos) << error.detail();
  }
  // extractFeatures (info, stylize, training) says the same, with or without a given unit.
  EXPECT_THROW(extractFeatures(motion, mapping, {}), InputError);
  FeatureOptions in_cm;
  in_cm.unit = "cm";
  EXPECT_THROW(extractFeatures(motion, mapping, in_cm), InputError);
}

TEST(SpaceConvention, ARestPoseOnOneLineOrPointIsAnInputErrorNamingTheClip) {
  LoadedClip clip = load("zombie.bvh");
  clip.motion.source = "zombie.bvh";
  expectUnmeasurable(withOffsets(clip.motion, [](int) { return Eigen::Vector3d::Zero(); }), clip.mapping);
  expectUnmeasurable(withOffsets(clip.motion, [](int j) { return Eigen::Vector3d(1.0 + j % 7, 0, 0); }), clip.mapping);
  expectUnmeasurable(withOffsets(clip.motion, [](int j) { return Eigen::Vector3d(0, 0, 1.0 + j % 3); }), clip.mapping);
  EXPECT_NO_THROW(requireMeasurableRestPose(clip.motion, clip.mapping));
}

TEST(SpaceConvention, KnownUnitNamesListsEveryUnit) {
  EXPECT_EQ(knownUnitNames(), "cm, m, mm, inch, ft, dm, cmu");
}

TEST(SpaceConvention, CmuIsYUpInCmuUnits) {
  const LoadedClip clip = load("cmu_131_01.bvh");
  const SpaceConvention convention = detectSpaceConvention(clip.motion.skeleton, clip.canonical, clip.mapping);
  EXPECT_EQ(convention.up_axis, "+Y");
  EXPECT_EQ(convention.unit, "cmu");
  EXPECT_TRUE(convention.unit_guessed);
  EXPECT_TRUE(convention.axes.isIdentity());
}

TEST(SpaceConvention, ZombieIsZUpAndTurnsToYUp) {
  const LoadedClip clip = load("zombie.bvh");
  const SpaceConvention convention = detectSpaceConvention(clip.motion.skeleton, clip.canonical, clip.mapping);
  EXPECT_EQ(convention.up_axis, "+Z");
  EXPECT_NEAR(convention.axes.determinant(), 1.0, 1e-12);
  // The head ends up above the feet in canonical space.
  const int head = clip.mapping[CanonicalJoint::Head];
  const int toe = clip.mapping[CanonicalJoint::LeftToe];
  const Eigen::Vector3d head_up = convention.toCanonical(clip.world.row(0).segment<3>(3 * head).transpose());
  const Eigen::Vector3d toe_up = convention.toCanonical(clip.world.row(0).segment<3>(3 * toe).transpose());
  EXPECT_GT(head_up.y() - toe_up.y(), 50.0);
}

TEST(SpaceConvention, GivenUnitIsUsedAndNotGuessed) {
  const LoadedClip clip = load("cmu_131_01.bvh");
  const SpaceConvention convention = detectSpaceConvention(clip.motion.skeleton, clip.canonical, clip.mapping, std::string("m"));
  EXPECT_EQ(convention.unit, "m");
  EXPECT_DOUBLE_EQ(convention.cm_per_unit, 100.0);
  EXPECT_FALSE(convention.unit_guessed);
}

TEST(SpaceConvention, UnitGuessFollowsScale) {
  // The same rig in centimetres and in metres: the guess must tell them apart.
  LoadedClip clip = load("cmu_131_01.bvh");
  const double cmu_cm = *centimetresPerUnit("cmu");
  for (const auto& [unit, cm_per_unit] : {std::pair<std::string, double>{"cm", 1.0}, {"m", 100.0}, {"mm", 0.1}}) {
    Skeleton scaled = clip.motion.skeleton;
    for (Joint& joint : scaled.joints) joint.offset *= cmu_cm / cm_per_unit;
    const SpaceConvention convention =
        detectSpaceConvention(scaled, clip.canonical * (cmu_cm / cm_per_unit), clip.mapping);
    EXPECT_EQ(convention.unit, unit);
    EXPECT_NEAR(skeletalHeight(scaled, clip.mapping) * convention.cm_per_unit,
                skeletalHeight(clip.motion.skeleton, clip.mapping) * cmu_cm, 1e-9);
  }
}

TEST(SpaceConvention, ToFileInvertsToCanonical) {
  SpaceConvention convention;
  convention.cm_per_unit = 2.54;
  convention.axes << 1, 0, 0, 0, 0, 1, 0, -1, 0;
  const Eigen::Vector3d p(1.5, -2.0, 7.25);
  EXPECT_TRUE(convention.toFile(convention.toCanonical(p)).isApprox(p, 1e-12));
  EXPECT_TRUE(convention.fileUp().isApprox(Eigen::Vector3d::UnitZ(), 1e-12));
}

}  // namespace
}  // namespace motionstyle
