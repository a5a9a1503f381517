// Forward kinematics (kinematics.h): hand-computed chains, position channels, an independent
// transform-product FK on every channel layout, and the localPoses <-> setLocalPoses round trip.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "motion/kinematics.h"
#include "motion/rotation.h"
#include "motion_test_helpers.h"

namespace motionstyle {
namespace {

using test::C;
using test::makeEndSite;
using test::makeJoint;

Eigen::Vector3d jointPosition(const Eigen::MatrixXd& world, int frame, int joint) {
  return world.block<1, 3>(frame, 3 * joint).transpose();
}

// Root (6 channels, Z Y X) -> Mid (Z X Y, offset 10 up) -> Tip (X Y Z, offset 5 up) -> End Site (2 along X).
Motion handChain() {
  Motion m;
  m.skeleton.joints.push_back(makeJoint("Root", -1, {0, 0, 0}, {C::Xposition, C::Yposition, C::Zposition, C::Zrotation, C::Yrotation, C::Xrotation}));
  m.skeleton.joints.push_back(makeJoint("Mid", 0, {0, 10, 0}, {C::Zrotation, C::Xrotation, C::Yrotation}));
  m.skeleton.joints.push_back(makeJoint("Tip", 1, {0, 5, 0}, {C::Xrotation, C::Yrotation, C::Zrotation}));
  m.skeleton.joints.push_back(makeEndSite("Tip_End", 2, {2, 0, 0}));
  m.values.resize(4, 12);
  //          Xp Yp Zp  Zr  Yr Xr | Mid Z  X  Y | Tip X  Y  Z
  m.values << 1, 2, 3,  0,  0, 0,       0, 0, 0,      0, 0, 0,
              1, 2, 3,  90, 0, 0,       0, 90, 0,     0, 90, 0,
              0, 0, 0,  0, 90, 0,       90, 0, 0,     0, 0, 0,
              0, 0, 0,  0,  0, 0,       90, 90, 0,    0, 0, 0;
  return m;
}

// Independent FK: Eigen affine products of AngleAxis rotations built straight from the channel values.
Eigen::MatrixXd referenceWorldPositions(const Motion& m) {
  const std::vector<int> offsets = m.skeleton.channelOffsets();
  Eigen::MatrixXd result(m.frameCount(), 3 * m.skeleton.jointCount());
  for (int f = 0; f < m.frameCount(); ++f) {
    std::vector<Eigen::Affine3d> world(m.skeleton.joints.size());
    for (size_t j = 0; j < m.skeleton.joints.size(); ++j) {
      const Joint& joint = m.skeleton.joints[j];
      Eigen::Vector3d translation = joint.offset;
      Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
      for (size_t c = 0; c < joint.channels.size(); ++c) {
        const double value = m.values(f, offsets[j] + static_cast<int>(c));
        const int axis = axisOf(joint.channels[c]);
        if (isRotation(joint.channels[c]))
          rotation = rotation * Eigen::AngleAxisd(value * std::numbers::pi / 180.0, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
        else
          translation[axis] = value;
      }
      Eigen::Affine3d local = Eigen::Translation3d(translation) * Eigen::Affine3d(rotation);
      world[j] = joint.parent < 0 ? local : world[static_cast<size_t>(joint.parent)] * local;
      result.block<1, 3>(f, 3 * static_cast<Eigen::Index>(j)) = world[j].translation().transpose();
    }
  }
  return result;
}

// ---- invalid input -------------------------------------------------------------------------------

TEST(KinematicsInvalid, LocalPosesValidatesTheMotion) {
  Motion m = handChain();
  m.values.conservativeResize(4, 11);
  EXPECT_THROW(localPoses(m), std::invalid_argument);
  m = handChain();
  m.frame_time = 0.0;
  EXPECT_THROW(localPoses(m), std::invalid_argument);
}

TEST(KinematicsInvalid, WorldQueriesRejectPosesOfAnotherShape) {
  const Motion m = handChain();
  LocalPoses poses = localPoses(m);
  LocalPoses wrong_joints = poses;
  wrong_joints.joints = 3;
  EXPECT_THROW(worldPositions(m.skeleton, wrong_joints), std::invalid_argument);
  EXPECT_THROW(worldRotations(m.skeleton, wrong_joints), std::invalid_argument);
  LocalPoses short_rotations = poses;
  short_rotations.rotations.pop_back();
  EXPECT_THROW(worldPositions(m.skeleton, short_rotations), std::invalid_argument);
  LocalPoses negative = poses;
  negative.frames = -1;
  EXPECT_THROW(worldPositions(m.skeleton, negative), std::invalid_argument);
  EXPECT_THROW(worldPositions(Skeleton{}, LocalPoses{}), std::invalid_argument);
  Skeleton misordered = m.skeleton;
  misordered.joints[1].parent = 2;
  EXPECT_THROW(worldPositions(misordered, poses), std::invalid_argument);
}

TEST(KinematicsInvalid, PartialWorldPositionsRejectUnknownJointsAndPosesOfAnotherShape) {
  const Motion m = handChain();
  const LocalPoses poses = localPoses(m);
  EXPECT_THROW(worldPositions(m.skeleton, poses, std::vector<int>{0, 4}), std::invalid_argument);
  EXPECT_THROW(worldPositions(m.skeleton, poses, std::vector<int>{-1}), std::invalid_argument);
  LocalPoses short_translations = poses;
  short_translations.translations.pop_back();
  EXPECT_THROW(worldPositions(m.skeleton, short_translations, std::vector<int>{3}), std::invalid_argument);
  Skeleton misordered = m.skeleton;
  misordered.joints[1].parent = 2;
  EXPECT_THROW(worldPositions(misordered, poses, std::vector<int>{3}), std::invalid_argument);
}

TEST(KinematicsInvalid, SetLocalPosesRejectsWhatTheChannelsCannotHoldAndLeavesTheMotionUnchanged) {
  const Motion original = test::randomMotion(test::mixedSkeleton(), 5, 3);
  const LocalPoses poses = localPoses(original);
  const int no_channels = original.skeleton.find("K_NoChannels");
  const int rotation_only = original.skeleton.find("A_XYZ");
  const int partial = original.skeleton.find("J_PartialPosition");

  LocalPoses rotated = poses;
  rotated.rotation(2, no_channels) = axisRotation(0, 1.0);
  Motion target = original;
  EXPECT_THROW(setLocalPoses(rotated, target), std::invalid_argument);
  EXPECT_EQ(target.values, original.values);

  LocalPoses moved = poses;
  moved.translation(4, rotation_only).x() += 0.01;
  EXPECT_THROW(setLocalPoses(moved, target), std::invalid_argument);

  LocalPoses partial_x = poses;
  partial_x.translation(1, partial).x() += 0.01;  // X has no channel there, Y has
  EXPECT_THROW(setLocalPoses(partial_x, target), std::invalid_argument);
  LocalPoses partial_y = poses;
  partial_y.translation(1, partial).y() += 0.01;
  EXPECT_NO_THROW(setLocalPoses(partial_y, target));

  LocalPoses not_finite = poses;
  not_finite.rotation(0, 1).x() = std::numeric_limits<double>::quiet_NaN();
  target = original;
  EXPECT_THROW(setLocalPoses(not_finite, target), std::invalid_argument);
  LocalPoses zero = poses;
  zero.rotation(0, 1) = Eigen::Quaterniond(0, 0, 0, 0);
  EXPECT_THROW(setLocalPoses(zero, target), std::invalid_argument);
  EXPECT_EQ(target.values, original.values);

  LocalPoses wrong_shape = poses;
  wrong_shape.translations.pop_back();
  EXPECT_THROW(setLocalPoses(wrong_shape, target), std::invalid_argument);
}

// ---- hand-computed answers -----------------------------------------------------------------------

TEST(ForwardKinematics, HandComputedThreeJointChain) {
  const Eigen::MatrixXd world = worldPositions(handChain());
  ASSERT_EQ(world.rows(), 4);
  ASSERT_EQ(world.cols(), 12);
  // Frame 0, rest pose translated by (1, 2, 3).
  EXPECT_TRUE(jointPosition(world, 0, 0).isApprox(Eigen::Vector3d(1, 2, 3), 1e-12));
  EXPECT_TRUE(jointPosition(world, 0, 1).isApprox(Eigen::Vector3d(1, 12, 3), 1e-12));
  EXPECT_TRUE(jointPosition(world, 0, 2).isApprox(Eigen::Vector3d(1, 17, 3), 1e-12));
  EXPECT_TRUE(jointPosition(world, 0, 3).isApprox(Eigen::Vector3d(3, 17, 3), 1e-12));
  // Frame 1: root Rz(90) turns Mid's offset (0,10,0) to (-10,0,0); Mid Rx(90) turns Tip's (0,5,0) to
  // (0,0,5), which Rz(90) keeps; Tip Ry(90) turns the End's (2,0,0) to (0,0,-2), Rx(90) to (0,2,0),
  // Rz(90) to (-2,0,0).
  EXPECT_LT((jointPosition(world, 1, 1) - Eigen::Vector3d(-9, 2, 3)).norm(), 1e-12);
  EXPECT_LT((jointPosition(world, 1, 2) - Eigen::Vector3d(-9, 2, 8)).norm(), 1e-12);
  EXPECT_LT((jointPosition(world, 1, 3) - Eigen::Vector3d(-11, 2, 8)).norm(), 1e-12);
  // Frame 2: root Ry(90) at the origin; Mid Rz(90) turns (0,5,0) to (-5,0,0), Ry(90) to (0,0,5);
  // the End's (2,0,0) -> Rz(90) (0,2,0) -> Ry(90) (0,2,0).
  EXPECT_LT((jointPosition(world, 2, 1) - Eigen::Vector3d(0, 10, 0)).norm(), 1e-12);
  EXPECT_LT((jointPosition(world, 2, 2) - Eigen::Vector3d(0, 10, 5)).norm(), 1e-12);
  EXPECT_LT((jointPosition(world, 2, 3) - Eigen::Vector3d(0, 12, 5)).norm(), 1e-12);
  // Frame 3: Mid "Z X Y" = (90, 90, 0) is Rz(90) * Rx(90): Rx first turns (0,5,0) to (0,0,5), which
  // Rz keeps; the End's (2,0,0) is kept by Rx and turned to (0,2,0) by Rz. (The reversed product
  // would give (-5,0,0) and (0,0,2).)
  EXPECT_LT((jointPosition(world, 3, 2) - Eigen::Vector3d(0, 10, 5)).norm(), 1e-12);
  EXPECT_LT((jointPosition(world, 3, 3) - Eigen::Vector3d(0, 12, 5)).norm(), 1e-12);
}

TEST(ForwardKinematics, PositionChannelsReplaceTheOffset) {
  Motion m;
  m.skeleton.joints.push_back(makeJoint("Root", -1, {0, 0, 0}, {C::Xposition, C::Yposition, C::Zposition, C::Zrotation, C::Xrotation, C::Yrotation}));
  m.skeleton.joints.push_back(makeJoint("Six", 0, {0, 10, 0}, {C::Xposition, C::Yposition, C::Zposition, C::Zrotation, C::Xrotation, C::Yrotation}));
  m.skeleton.joints.push_back(makeEndSite("Six_End", 1, {0, 1, 0}));
  m.values = MatrixRowMajor::Zero(1, 12);
  m.values(0, 6) = 4.0;   // Six: X position 4, Y and Z 0 (not the offset's 10)
  m.values(0, 9) = 90.0;  // Six: Zrotation 90 turns its End's (0,1,0) to (-1,0,0)
  const Eigen::MatrixXd world = worldPositions(m);
  EXPECT_LT((jointPosition(world, 0, 1) - Eigen::Vector3d(4, 0, 0)).norm(), 1e-12);
  EXPECT_LT((jointPosition(world, 0, 2) - Eigen::Vector3d(3, 0, 0)).norm(), 1e-12);
}

TEST(ForwardKinematics, PartialPositionChannelsKeepTheOffsetsOtherComponents) {
  Motion m;
  m.skeleton.joints.push_back(makeJoint("Root", -1, {0, 0, 0}, {C::Zrotation, C::Xrotation, C::Yrotation}));
  m.skeleton.joints.push_back(makeJoint("Slider", 0, {1, 10, 2}, {C::Yposition, C::Zrotation, C::Xrotation, C::Yrotation}));
  m.values = MatrixRowMajor::Zero(1, 7);
  m.values(0, 3) = 7.0;
  EXPECT_LT((jointPosition(worldPositions(m), 0, 1) - Eigen::Vector3d(1, 7, 2)).norm(), 1e-12);
}

// ---- properties ----------------------------------------------------------------------------------

TEST(ForwardKinematics, MatchesAnIndependentTransformProductOnEveryChannelLayout) {
  const Motion m = test::randomMotion(test::mixedSkeleton(), 40, 21, 40.0);
  const Eigen::MatrixXd world = worldPositions(m);
  const Eigen::MatrixXd expected = referenceWorldPositions(m);
  ASSERT_EQ(world.rows(), expected.rows());
  ASSERT_EQ(world.cols(), expected.cols());
  EXPECT_LT((world - expected).cwiseAbs().maxCoeff(), 1e-10);
}

TEST(ForwardKinematics, WorldRotationsAgreeWithWorldPositions) {
  const Motion m = test::randomMotion(test::mixedSkeleton(), 20, 22, 40.0);
  const LocalPoses poses = localPoses(m);
  const Eigen::MatrixXd world = worldPositions(m.skeleton, poses);
  const std::vector<Eigen::Quaterniond> rotations = worldRotations(m.skeleton, poses);
  ASSERT_EQ(rotations.size(), poses.rotations.size());
  for (int f = 0; f < poses.frames; ++f) {
    for (int j = 1; j < poses.joints; ++j) {
      const int p = m.skeleton.joints[static_cast<size_t>(j)].parent;
      const Eigen::Vector3d bone = jointPosition(world, f, j) - jointPosition(world, f, p);
      EXPECT_LT((bone - rotations[poses.at(f, p)] * poses.translation(f, j)).norm(), 1e-10);
      EXPECT_LT(rotationDistance(rotations[poses.at(f, j)], rotations[poses.at(f, p)] * poses.rotation(f, j)), 1e-12);
    }
  }
}

TEST(ForwardKinematics, PartialWorldPositionsMatchTheIndependentProductForAnySelection) {
  // 21 frames: two whole blocks of 8 and a partial one. Selections: every joint, leaves only (their
  // ancestors are visited but not returned), a joint twice, out of order, none.
  const Motion m = test::randomMotion(test::mixedSkeleton(), 21, 23, 40.0);
  const LocalPoses poses = localPoses(m);
  const Eigen::MatrixXd full = referenceWorldPositions(m);
  std::vector<int> every(static_cast<size_t>(m.skeleton.jointCount()));
  for (size_t j = 0; j < every.size(); ++j) every[j] = static_cast<int>(j);
  const int leaf = m.skeleton.find("C_YXZ_End"), other_leaf = m.skeleton.find("K_NoChannels_End");
  const int middle = m.skeleton.find("E_ZXY");
  for (const std::vector<int>& wanted : {every, std::vector<int>{leaf, other_leaf}, std::vector<int>{middle, 0, middle},
                                         std::vector<int>{other_leaf, leaf, middle}, std::vector<int>{}}) {
    const Eigen::MatrixXd partial = worldPositions(m.skeleton, poses, wanted);
    ASSERT_EQ(partial.rows(), full.rows());
    ASSERT_EQ(partial.cols(), 3 * static_cast<Eigen::Index>(wanted.size()));
    for (size_t n = 0; n < wanted.size(); ++n) {
      const auto column = 3 * static_cast<Eigen::Index>(n);
      EXPECT_LT((partial.middleCols<3>(column) - full.middleCols<3>(3 * wanted[n])).cwiseAbs().maxCoeff(), 1e-10)
          << "joint " << wanted[n];
    }
  }
}

TEST(ForwardKinematics, AFramesResultDoesNotDependOnWhereItSitsInTheClip) {
  // Kinematics works on blocks of frames with vector instructions: dropping the first few frames moves
  // every frame to another lane, which must not change a single bit (decimation relies on it).
  const Motion m = test::randomMotion(test::mixedSkeleton(), 29, 24, 40.0);
  const Eigen::MatrixXd world = worldPositions(m);
  for (int dropped = 1; dropped <= 9; ++dropped) {
    Motion later = m;
    later.values = m.values.bottomRows(m.frameCount() - dropped);
    const Eigen::MatrixXd later_world = worldPositions(later);
    for (int f = 0; f < later.frameCount(); ++f)
      ASSERT_EQ(later_world.row(f), world.row(f + dropped)) << dropped << " dropped, frame " << f;
  }
}

TEST(ForwardKinematics, PartialWorldPositionsOfZeroFramesAreEmpty) {
  Motion m = handChain();
  m.values.resize(0, 12);
  const Eigen::MatrixXd world = worldPositions(m.skeleton, localPoses(m), std::vector<int>{3, 1});
  EXPECT_EQ(world.rows(), 0);
  EXPECT_EQ(world.cols(), 6);
}

TEST(ForwardKinematics, ZeroFramesGiveAnEmptyResult) {
  Motion m = handChain();
  m.values.resize(0, 12);
  const Eigen::MatrixXd world = worldPositions(m);
  EXPECT_EQ(world.rows(), 0);
  EXPECT_EQ(world.cols(), 12);
}

TEST(LocalPoseRoundTrip, SetLocalPosesReproducesRotationsPositionsAndAngles) {
  const Motion original = test::randomMotion(test::mixedSkeleton(), 120, 31);
  const LocalPoses poses = localPoses(original);
  Motion rebuilt = original;
  setLocalPoses(poses, rebuilt);
  ASSERT_EQ(rebuilt.values.rows(), original.values.rows());
  const LocalPoses again = localPoses(rebuilt);
  for (size_t n = 0; n < poses.rotations.size(); ++n) {
    ASSERT_LT(rotationDistance(again.rotations[n], poses.rotations[n]), 1e-12) << "pose " << n;
    ASSERT_EQ(again.translations[n], poses.translations[n]) << "pose " << n;
  }
  // Angles too: the walk starts outside (-180, 180] and never jumps, so frame 0 seeded by the motion's
  // own first frame and continuity afterwards recover the file's angles rather than principal ones.
  EXPECT_LT((rebuilt.values - original.values).cwiseAbs().maxCoeff(), 1e-8);
}

TEST(LocalPoseRoundTrip, WithoutExistingValuesFrameZeroTakesThePrincipalSolution) {
  const Motion original = test::randomMotion(test::mixedSkeleton(), 30, 32);
  const LocalPoses poses = localPoses(original);
  Motion fresh;
  fresh.skeleton = original.skeleton;
  setLocalPoses(poses, fresh);
  ASSERT_EQ(fresh.frameCount(), 30);
  const LocalPoses again = localPoses(fresh);
  for (size_t n = 0; n < poses.rotations.size(); ++n)
    ASSERT_LT(rotationDistance(again.rotations[n], poses.rotations[n]), 1e-12) << "pose " << n;
  // Frame 0 of a three-axis joint lies in the principal ranges.
  const int joint = fresh.skeleton.find("A_XYZ");
  const int column = fresh.skeleton.channelOffsets()[static_cast<size_t>(joint)];
  EXPECT_LE(std::abs(fresh.values(0, column + 1)), 90.0);
  EXPECT_LE(std::abs(fresh.values(0, column)), 180.0);
  EXPECT_TRUE(worldPositions(fresh).isApprox(worldPositions(original), 1e-10));
}


// --- A clip walked in blocks of frames (long clips are never held whole).

TEST(BlockKinematics, RefusesRangesOutsideTheClipAndBadValuesInsideTheRange) {
  Motion motion = test::randomMotion(test::mixedSkeleton(), 20, 5);
  EXPECT_THROW(localPoses(motion, -1, 2), std::invalid_argument);
  EXPECT_THROW(localPoses(motion, 19, 2), std::invalid_argument);
  EXPECT_THROW(localPoses(motion, 0, -1), std::invalid_argument);
  motion.values(15, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NO_THROW(localPoses(motion, 0, 15));  // the bad frame lies outside the range
  EXPECT_THROW(localPoses(motion, 10, 6), std::invalid_argument);
}

TEST(BlockKinematics, ABlocksPosesAndPositionsAreThoseOfTheWholeClip) {
  const Motion motion = test::randomMotion(test::mixedSkeleton(), 3 * kMotionBlockFrames / 2, 6);
  const LocalPoses whole = localPoses(motion);
  const LocalPoses block = localPoses(motion, 700, 600);
  ASSERT_EQ(block.frames, 600);
  for (int f = 0; f < block.frames; ++f)
    for (int j = 0; j < block.joints; ++j) {
      ASSERT_EQ(block.rotation(f, j).coeffs(), whole.rotation(700 + f, j).coeffs());
      ASSERT_EQ(block.translation(f, j), whole.translation(700 + f, j));
    }
  const std::vector<int> wanted = {3, 0, 3};
  EXPECT_EQ(worldPositions(motion, wanted), worldPositions(motion.skeleton, whole, wanted));  // walked in blocks
}

TEST(BlockKinematics, ChannelValuesInBlocksSeededByThePreviousBlockEqualSetLocalPoses) {
  const Motion original = test::randomMotion(test::mixedSkeleton(), 40, 8);
  Motion whole = original;
  setLocalPoses(localPoses(original), whole);
  const MatrixRowMajor head = channelValues(original.skeleton, localPoses(original, 0, 25), original.values.row(0).data());
  const MatrixRowMajor tail = channelValues(original.skeleton, localPoses(original, 25, 15), head.row(24).data());
  EXPECT_EQ(head, whole.values.topRows(25));
  EXPECT_EQ(tail, whole.values.bottomRows(15));
}


TEST(BlockKinematics, WriteChannelValuesRefusesAJointOutsideTheSkeletonOrValuesOfAnotherShape) {
  const Motion motion = test::randomMotion(test::mixedSkeleton(), 10, 3);
  const LocalPoses poses = localPoses(motion);
  MatrixRowMajor values = motion.values;
  const std::vector<int> outside = {motion.skeleton.jointCount()};
  EXPECT_THROW(writeChannelValues(motion.skeleton, poses, outside, nullptr, values), std::invalid_argument);
  const std::vector<int> negative = {-1};
  EXPECT_THROW(writeChannelValues(motion.skeleton, poses, negative, nullptr, values), std::invalid_argument);
  MatrixRowMajor short_values = motion.values.topRows(9);
  const std::vector<int> first = {0};
  EXPECT_THROW(writeChannelValues(motion.skeleton, poses, first, nullptr, short_values), std::invalid_argument);
  EXPECT_EQ(values, motion.values);
}

TEST(BlockKinematics, WriteChannelValuesWritesTheListedJointsAsChannelValuesAndLeavesTheRest) {
  const Motion original = test::randomMotion(test::mixedSkeleton(), 30, 11);
  const Motion other = test::randomMotion(test::mixedSkeleton(), 30, 12);
  const LocalPoses poses = localPoses(other);
  const MatrixRowMajor expected = channelValues(other.skeleton, poses, original.values.row(0).data());
  std::vector<int> listed;
  for (int j = 0; j < original.skeleton.jointCount(); j += 2) listed.push_back(j);
  MatrixRowMajor values = original.values;
  writeChannelValues(original.skeleton, poses, listed, original.values.row(0).data(), values);
  std::vector<bool> written(static_cast<size_t>(original.skeleton.channelCount()), false);
  int column = 0;
  for (int j = 0; j < original.skeleton.jointCount(); ++j) {
    const int count = static_cast<int>(original.skeleton.joints[static_cast<size_t>(j)].channels.size());
    for (int c = 0; c < count; ++c) written[static_cast<size_t>(column + c)] = j % 2 == 0;
    column += count;
  }
  for (int c = 0; c < original.skeleton.channelCount(); ++c)
    EXPECT_EQ(values.col(c), written[static_cast<size_t>(c)] ? expected.col(c) : original.values.col(c)) << "channel " << c;
}

}  // namespace
}  // namespace motionstyle
