// Forward kinematics, the local-pose round trip and resampling on the committed real clips:
// tests/data/cmu_131_01.bvh (CMU walk, 120 fps, Y-up, ZYX joints) and tests/data/zombie.bvh
// (AnimatedDrawings, 30 fps, Z-up, XYZ and YXZ joints).

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "bvh/bvh_reader.h"
#include "motion/kinematics.h"
#include "motion/resample.h"
#include "motion/rotation.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

struct Clip {
  const char* file;
  int up_axis;  // 1 = Y, 2 = Z
  const char* head_end;
};

void PrintTo(const Clip& clip, std::ostream* out) { *out << clip.file; }

Eigen::Vector3d jointPosition(const Eigen::MatrixXd& world, int frame, int joint) {
  return world.block<1, 3>(frame, 3 * joint).transpose();
}

bool hasPositionChannels(const Joint& joint) {
  return std::any_of(joint.channels.begin(), joint.channels.end(), [](ChannelType c) { return !isRotation(c); });
}

bool isFootJoint(const std::string& name) {
  return name.find("Toe") != std::string::npos || name.find("Ankle") != std::string::npos ||
         name.find("Foot") != std::string::npos;
}

// Bones of joints without position channels keep |offset| in every frame (to 1e-9 relative).
void expectRigidBones(const Motion& motion, const Eigen::MatrixXd& world) {
  for (int j = 1; j < motion.skeleton.jointCount(); ++j) {
    const Joint& joint = motion.skeleton.joints[static_cast<size_t>(j)];
    if (hasPositionChannels(joint)) continue;
    const double length = joint.offset.norm();
    double worst = 0.0;
    for (int f = 0; f < motion.frameCount(); ++f)
      worst = std::max(worst, std::abs((jointPosition(world, f, j) - jointPosition(world, f, joint.parent)).norm() - length));
    EXPECT_LE(worst, 1e-9 * length) << joint.name;
  }
}

class RealClip : public ::testing::TestWithParam<Clip> {
 protected:
  void SetUp() override { motion_ = readBvh(test::fixture(GetParam().file)); }
  Motion motion_;
};

TEST_P(RealClip, BoneLengthsAreConstantAndEqualTheOffsets) {
  ASSERT_GT(motion_.frameCount(), 100);
  expectRigidBones(motion_, worldPositions(motion_));
}

TEST_P(RealClip, FeetAreTheLowestJointsAndTouchTheGround) {
  const int up = GetParam().up_axis;
  const Eigen::MatrixXd world = worldPositions(motion_);
  const int head_end = motion_.skeleton.find(GetParam().head_end);
  ASSERT_GE(head_end, 0);
  const double height = world.col(3 * head_end + up).maxCoeff();
  ASSERT_GT(height, 0.0);
  for (int f = 0; f < motion_.frameCount(); ++f) {
    int lowest = 0;
    for (int j = 1; j < motion_.skeleton.jointCount(); ++j)
      if (world(f, 3 * j + up) < world(f, 3 * lowest + up)) lowest = j;
    const std::string& name = motion_.skeleton.joints[static_cast<size_t>(lowest)].name;
    ASSERT_TRUE(isFootJoint(name)) << "frame " << f << ": lowest joint is " << name;
    // Walking on a floor at height 0: the lowest point stays within a few percent of the body height.
    ASSERT_GT(world(f, 3 * lowest + up), -0.05 * height) << "frame " << f;
    ASSERT_LT(world(f, 3 * lowest + up), 0.10 * height) << "frame " << f;
    ASSERT_GT(world(f, 3 * head_end + up), world(f, up)) << "frame " << f << ": head end below the hips";
  }
}

TEST_P(RealClip, LocalPoseRoundTripReproducesTheFileValues) {
  const LocalPoses poses = localPoses(motion_);
  Motion rebuilt = motion_;
  setLocalPoses(poses, rebuilt);
  const LocalPoses again = localPoses(rebuilt);
  for (size_t n = 0; n < poses.rotations.size(); ++n)
    ASSERT_LT(rotationDistance(again.rotations[n], poses.rotations[n]), 1e-12) << "pose " << n;
  // The angles themselves: the same up to whole turns (the file wraps at +-180 where continuity does
  // not), and the rebuilt channels never jump by half a turn or more between frames.
  const Eigen::MatrixXd difference = rebuilt.values - motion_.values;
  const Eigen::MatrixXd whole_turns = (difference / 360.0).array().round() * 360.0;
  EXPECT_LT((difference - whole_turns).cwiseAbs().maxCoeff(), 1e-8);
  const Eigen::MatrixXd steps = rebuilt.values.bottomRows(rebuilt.frameCount() - 1) - rebuilt.values.topRows(rebuilt.frameCount() - 1);
  EXPECT_LT(steps.cwiseAbs().maxCoeff(), 180.0);
}

TEST_P(RealClip, ResampledClipKeepsBonesAndAgreesAtSharedTimes) {
  const Eigen::MatrixXd source_world = worldPositions(motion_);
  const double scale = source_world.cwiseAbs().maxCoeff();
  for (const int factor : {2, 3}) {  // up to 2x and 3x the rate: every factor-th output frame is a source frame
    const Motion up = resampleMotion(motion_, motion_.fps() * factor);
    ASSERT_EQ(up.frameCount(), (motion_.frameCount() - 1) * factor + 1);
    const Eigen::MatrixXd world = worldPositions(up);
    expectRigidBones(up, world);
    for (int f = 0; f < motion_.frameCount(); ++f)
      ASSERT_LT((world.row(f * factor) - source_world.row(f)).cwiseAbs().maxCoeff(), 1e-12 * scale) << "frame " << f;
  }
  const Motion down = resampleMotion(motion_, motion_.fps() / 2.0);
  ASSERT_EQ(down.frameCount(), (motion_.frameCount() - 1) / 2 + 1);
  const Eigen::MatrixXd down_world = worldPositions(down);
  for (int k = 0; k < down.frameCount(); ++k) ASSERT_EQ(down_world.row(k), source_world.row(2 * k)) << "frame " << k;
}

INSTANTIATE_TEST_SUITE_P(Fixtures, RealClip,
                         ::testing::Values(Clip{"cmu_131_01.bvh", 1, "Head_End"}, Clip{"zombie.bvh", 2, "Head_End"}));

TEST(RealClipResample, CmuAt120To60KeepsEverySecondCapturedFrame) {
  // The file states ".0083333": whole-number decimation must still pick the captured frames.
  const Motion cmu = readBvh(test::fixture("cmu_131_01.bvh"));
  const Motion half = resampleMotion(cmu, 60.0);
  ASSERT_EQ(half.frameCount(), (cmu.frameCount() - 1) / 2 + 1);
  for (int k = 0; k < half.frameCount(); ++k) ASSERT_EQ(half.values.row(k), cmu.values.row(2 * k));
  EXPECT_DOUBLE_EQ(half.fps(), 60.0);
}

}  // namespace
}  // namespace motionstyle
