// Frame-rate conversion (resample.h): input checks, frame counts, exact decimation, the slerp path,
// shortest-path interpolation with continuous Euler angles, and agreement of world positions.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "motion/kinematics.h"
#include "motion/resample.h"
#include "motion/rotation.h"
#include "motion_test_helpers.h"

namespace motionstyle {
namespace {

using test::C;
using test::makeJoint;

Motion mixedAt(double fps, int frames, unsigned seed) {
  Motion m = test::randomMotion(test::mixedSkeleton(), frames, seed, 15.0);
  m.frame_time = 1.0 / fps;
  return m;
}

// ---- invalid input -------------------------------------------------------------------------------

TEST(ResampleInvalid, RejectsBadTargetRates) {
  const Motion m = mixedAt(30.0, 5, 1);
  for (double bad : {0.0, -60.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()})
    EXPECT_THROW(resampleMotion(m, bad), std::invalid_argument) << bad;
  EXPECT_THROW(resampleMotion(m, 30.0 * 101.0), std::invalid_argument);  // beyond 100x upsampling
  EXPECT_NO_THROW(resampleMotion(m, 30.0 * 100.0));
}

TEST(ResampleInvalid, AUsersRateBeyondAHundredTimesIsAnInputErrorNamingTheClip) {
  Motion slow = mixedAt(2.0, 5, 1);
  slow.source = "slow.bvh";
  try {
    requireResampleableTo(slow, 1000.0);
    ADD_FAILURE() << "accepted 500x upsampling";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "slow.bvh");
    EXPECT_NE(error.detail().find("more than 100 times the clip's 2 fps (at most 200)"), std::string::npos) << error.detail();
  }
  EXPECT_NO_THROW(requireResampleableTo(slow, 200.0));
  EXPECT_NO_THROW(resampleMotion(slow, 200.0));
}

TEST(ResampleInvalid, RejectsEmptyAndInvalidMotions) {
  Motion empty = mixedAt(30.0, 0, 1);
  EXPECT_THROW(resampleMotion(empty, 60.0), std::invalid_argument);
  Motion bad_columns = mixedAt(30.0, 3, 1);
  bad_columns.values.conservativeResize(3, bad_columns.values.cols() - 1);
  EXPECT_THROW(resampleMotion(bad_columns, 60.0), std::invalid_argument);
  Motion bad_time = mixedAt(30.0, 3, 1);
  bad_time.frame_time = -1.0;
  EXPECT_THROW(resampleMotion(bad_time, 60.0), std::invalid_argument);
  EXPECT_THROW(resampleRowsLinear(Eigen::MatrixXd(0, 3), 1.0 / 30.0, 60.0), std::invalid_argument);
  EXPECT_THROW(resampleRowsLinear(Eigen::MatrixXd::Zero(4, 3), 0.0, 60.0), std::invalid_argument);
  EXPECT_THROW(resampleSchedule(4, 1.0 / 30.0, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

TEST(ResampleInvalid, ResampleLocalPosesRejectsPosesOfAnotherShapeAndBadRates) {
  const LocalPoses poses = localPoses(mixedAt(30.0, 5, 1));
  LocalPoses short_rotations = poses;
  short_rotations.rotations.pop_back();
  EXPECT_THROW(resampleLocalPoses(short_rotations, 1.0 / 30.0, 60.0), std::invalid_argument);
  LocalPoses no_joints = poses;
  no_joints.joints = 0;
  EXPECT_THROW(resampleLocalPoses(no_joints, 1.0 / 30.0, 60.0), std::invalid_argument);
  LocalPoses negative = poses;
  negative.frames = -5;
  EXPECT_THROW(resampleLocalPoses(negative, 1.0 / 30.0, 60.0), std::invalid_argument);
  LocalPoses empty = poses;
  empty.frames = 0;
  empty.rotations.clear();
  empty.translations.clear();
  EXPECT_THROW(resampleLocalPoses(empty, 1.0 / 30.0, 60.0), std::invalid_argument);
  EXPECT_THROW(resampleLocalPoses(poses, 0.0, 60.0), std::invalid_argument);
  EXPECT_THROW(resampleLocalPoses(poses, 1.0 / 30.0, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(resampleLocalPoses(poses, 1.0 / 30.0, 30.0 * 101.0), std::invalid_argument);
}

// ---- timing --------------------------------------------------------------------------------------

TEST(ResampleTiming, FrameCountCoversTheSourceDurationWithoutExtrapolating) {
  EXPECT_EQ(resampleSchedule(11, 1.0 / 120.0, 60.0).size(), 6u);   // 10/120 s -> floor(5) + 1
  EXPECT_EQ(resampleSchedule(12, 1.0 / 120.0, 60.0).size(), 6u);   // 11/120 s -> floor(5.5) + 1
  EXPECT_EQ(resampleSchedule(10, 1.0 / 30.0, 60.0).size(), 19u);   // 9/30 s -> 18 + 1
  EXPECT_EQ(resampleSchedule(121, 1.0 / 120.0, 50.0).size(), 51u); // 1 s -> 50 + 1
  EXPECT_EQ(resampleSchedule(1, 1.0 / 30.0, 60.0).size(), 1u);
  for (double fps : {7.0, 24.0, 29.97, 50.0, 60.0, 90.0, 200.0}) {
    const std::vector<ResampleSample> schedule = resampleSchedule(97, 1.0 / 120.0, fps);
    const double duration = 96.0 / 120.0;
    EXPECT_EQ(schedule.size(), static_cast<size_t>(std::floor(duration * fps + 1e-6)) + 1) << fps;
    for (size_t k = 0; k < schedule.size(); ++k) {
      const double position = schedule[k].index + schedule[k].fraction;
      EXPECT_NEAR(position, static_cast<double>(k) / fps * 120.0, 1e-9) << fps << " frame " << k;
      EXPECT_LE(position, 96.0);
      EXPECT_GE(schedule[k].fraction, 0.0);
      EXPECT_LT(schedule[k].fraction, 1.0);
    }
  }
}

TEST(ResampleTiming, RoundedBvhFrameTimesStillDecimateExactly) {
  // CMU files state ".0083333" for 120 fps: 120 -> 60 still takes every second frame, untouched.
  const std::vector<ResampleSample> schedule = resampleSchedule(994, 0.0083333, 60.0);
  ASSERT_EQ(schedule.size(), 497u);
  for (size_t k = 0; k < schedule.size(); ++k) {
    EXPECT_EQ(schedule[k].index, static_cast<int>(2 * k));
    EXPECT_EQ(schedule[k].fraction, 0.0);
  }
  // Bandai files state "0.0333333" for 30 fps: 30 -> 60 still subdivides every source frame in two
  // and keeps the last frame.
  const std::vector<ResampleSample> doubled = resampleSchedule(128, 0.0333333, 60.0);
  ASSERT_EQ(doubled.size(), 255u);
  for (size_t k = 0; k < doubled.size(); ++k) {
    EXPECT_EQ(doubled[k].index, static_cast<int>(k / 2));
    EXPECT_EQ(doubled[k].fraction, k % 2 == 0 ? 0.0 : 0.5);
  }
  // Other ratios: a duration within rounding of a whole output frame keeps that frame (0.0083333 s
  // per frame -> 120 frames span 0.9999960 s, i.e. 49.9998 frames at 50 fps).
  EXPECT_EQ(resampleSchedule(121, 0.0083333, 50.0).size(), 51u);
  EXPECT_EQ(resampleSchedule(121, 0.0083333, 50.0).back().index, 120);
}

// ---- properties ----------------------------------------------------------------------------------

TEST(ResampleMotion, SameRateReturnsAnIdenticalCopy) {
  const Motion m = mixedAt(30.0, 17, 2);
  const Motion same = resampleMotion(m, 30.0);
  EXPECT_EQ(same.values, m.values);
  EXPECT_EQ(same.frame_time, m.frame_time);
  Motion rounded = m;
  rounded.frame_time = 0.0333333;
  EXPECT_EQ(resampleMotion(rounded, 30.0).values, m.values);
}

TEST(ResampleMotion, SameFrameRateIsWhereResamplingLeavesTheFramesAsTheyAre) {
  const Motion m = mixedAt(30.0, 17, 2);
  Motion off = m;
  off.frame_time = 1.0 / (30.0 * (1.0 + 5e-6));  // within the tolerance: a copy
  EXPECT_TRUE(sameFrameRate(off.fps(), 30.0));
  EXPECT_EQ(resampleMotion(off, 30.0).values, m.values);
  off.frame_time = 1.0 / (30.0 * (1.0 + 2e-5));  // beyond it: resampled, one frame fewer
  EXPECT_FALSE(sameFrameRate(off.fps(), 30.0));
  EXPECT_NE(resampleMotion(off, 30.0).frameCount(), m.frameCount());
  EXPECT_FALSE(sameFrameRate(60.0, 30.0));
}

TEST(ResampleMotion, HalvingTheRateKeepsEverySecondFrameExactly) {
  const Motion m = mixedAt(120.0, 41, 3);
  const Motion half = resampleMotion(m, 60.0);
  ASSERT_EQ(half.frameCount(), 21);
  EXPECT_DOUBLE_EQ(half.frame_time, 1.0 / 60.0);
  ASSERT_EQ(half.values.cols(), m.values.cols());
  for (int k = 0; k < half.frameCount(); ++k) EXPECT_EQ(half.values.row(k), m.values.row(2 * k)) << "frame " << k;
  EXPECT_EQ(half.skeleton.jointCount(), m.skeleton.jointCount());
  EXPECT_EQ(half.skeleton.channelOffsets(), m.skeleton.channelOffsets());
}

TEST(ResampleMotion, UpsampledFramesLieOnTheSlerpPathAndPositionsOnTheLine) {
  const Motion m = mixedAt(30.0, 25, 4);
  const Motion up = resampleMotion(m, 60.0);
  ASSERT_EQ(up.frameCount(), 49);
  const LocalPoses source = localPoses(m);
  const LocalPoses target = localPoses(up);
  for (int k = 0; k < up.frameCount(); ++k) {
    const int i = k / 2;
    for (int j = 0; j < source.joints; ++j) {
      const std::string joint = m.skeleton.joints[static_cast<size_t>(j)].name;
      if (joint == "H_TwoAxes") continue;  // a two-axis joint gets the projection of the slerp (checked below)
      if (k % 2 == 0) {
        ASSERT_LT(rotationDistance(target.rotation(k, j), source.rotation(i, j)), 1e-12) << joint << " frame " << k;
        ASSERT_LT((target.translation(k, j) - source.translation(i, j)).norm(), 1e-12);
        continue;
      }
      // Midway along the shortest great arc: half the angle to each neighbour, and those add up.
      const double whole = rotationDistance(source.rotation(i, j), source.rotation(i + 1, j));
      const double to_previous = rotationDistance(source.rotation(i, j), target.rotation(k, j));
      const double to_next = rotationDistance(target.rotation(k, j), source.rotation(i + 1, j));
      ASSERT_LT(whole, std::numbers::pi);
      ASSERT_NEAR(to_previous, 0.5 * whole, 1e-10) << joint << " frame " << k;
      ASSERT_NEAR(to_next, 0.5 * whole, 1e-10) << joint << " frame " << k;
      ASSERT_LT((target.translation(k, j) - 0.5 * (source.translation(i, j) + source.translation(i + 1, j))).norm(), 1e-12);
    }
  }
}

TEST(ResampleMotion, NonIntegerRatioSamplesAtTheRightFractionOfTheArc) {
  const Motion m = mixedAt(120.0, 61, 5);
  const Motion out = resampleMotion(m, 50.0);
  ASSERT_EQ(out.frameCount(), 26);  // 0.5 s -> 25 + 1
  const LocalPoses source = localPoses(m);
  const LocalPoses target = localPoses(out);
  const int joint = m.skeleton.find("E_ZXY");
  for (int k = 0; k < out.frameCount(); ++k) {
    const double position = k * 120.0 / 50.0;
    const int i = static_cast<int>(std::floor(position + 1e-9));
    const double w = position - i;
    if (w < 1e-9) {
      EXPECT_LT(rotationDistance(target.rotation(k, joint), source.rotation(i, joint)), 1e-12);
      continue;
    }
    const double whole = rotationDistance(source.rotation(i, joint), source.rotation(i + 1, joint));
    EXPECT_NEAR(rotationDistance(source.rotation(i, joint), target.rotation(k, joint)), w * whole, 1e-10);
    EXPECT_NEAR(rotationDistance(target.rotation(k, joint), source.rotation(i + 1, joint)), (1 - w) * whole, 1e-10);
  }
}

TEST(ResampleMotion, TwoAxisJointsGetTheProjectionOfTheSlerp) {
  const Motion m = mixedAt(30.0, 25, 4);
  const Motion up = resampleMotion(m, 60.0);
  const int joint = m.skeleton.find("H_TwoAxes");
  const LocalPoses source = localPoses(m);
  const LocalPoses target = localPoses(up);
  for (int k = 1; k < up.frameCount(); k += 2) {
    const Eigen::Quaterniond slerped = source.rotation(k / 2, joint).slerp(0.5, source.rotation(k / 2 + 1, joint));
    // Not exact (Rz * Rx products are not closed under slerp) but close for neighbouring frames.
    EXPECT_LT(rotationDistance(target.rotation(k, joint), slerped), 0.01) << "frame " << k;
  }
}

TEST(ResampleMotion, InterpolatesTheShortWayAndKeepsEulerAnglesContinuous) {
  Motion m;
  m.skeleton.joints.push_back(makeJoint("Root", -1, {0, 0, 0}, {C::Zrotation, C::Xrotation, C::Yrotation}));
  m.frame_time = 1.0 / 30.0;
  m.values.resize(2, 3);
  m.values << 170, 0, 0,
              -170, 0, 0;  // 20 degrees apart the short way, through 180
  const Motion up = resampleMotion(m, 120.0);
  ASSERT_EQ(up.frameCount(), 5);
  for (int k = 0; k < 5; ++k) {
    EXPECT_NEAR(up.values(k, 0), 170.0 + 5.0 * k, 1e-9) << "frame " << k;  // 170 175 180 185 190
    EXPECT_NEAR(up.values(k, 1), 0.0, 1e-9);
    EXPECT_NEAR(up.values(k, 2), 0.0, 1e-9);
  }
}

TEST(ResampleMotion, WorldPositionsAgreeAtSharedTimes) {
  for (const auto& [source_fps, target_fps, source_step, target_step] :
       {std::tuple{30.0, 60.0, 1, 2}, std::tuple{120.0, 50.0, 12, 5}, std::tuple{120.0, 60.0, 2, 1}}) {
    const Motion m = mixedAt(source_fps, 61, 6);
    const Motion out = resampleMotion(m, target_fps);
    const Eigen::MatrixXd source_world = worldPositions(m);
    const Eigen::MatrixXd target_world = worldPositions(out);
    int shared = 0;
    for (int k = 0; k * source_step < m.frameCount() && k * target_step < out.frameCount(); ++k, ++shared)
      EXPECT_LT((target_world.row(k * target_step) - source_world.row(k * source_step)).cwiseAbs().maxCoeff(), 1e-9)
          << source_fps << " -> " << target_fps << " shared frame " << k;
    EXPECT_GE(shared, 5);
  }
}

// resampleLocalPoses must be resampleMotion without the trip through Euler angles: same frames, same
// rotations (to rounding) and translations, for subdivision (its midpoint shortcut), a non-integer
// ratio (slerp), decimation (copies) and the same rate. Two-axis joints are left out: resampleMotion
// projects their slerp onto the two axes (TwoAxisJointsGetTheProjectionOfTheSlerp).
TEST(ResampleLocalPoses, EqualsTheLocalPosesOfTheResampledMotion) {
  for (const auto& [source_fps, target_fps] :
       {std::pair{30.0, 60.0}, std::pair{30.0, 120.0}, std::pair{120.0, 50.0}, std::pair{120.0, 60.0}, std::pair{30.0, 30.0}}) {
    const Motion m = mixedAt(source_fps, 37, 9);
    const LocalPoses direct = resampleLocalPoses(localPoses(m), m.frame_time, target_fps);
    const LocalPoses via_motion = localPoses(resampleMotion(m, target_fps));
    ASSERT_EQ(direct.frames, via_motion.frames) << source_fps << " -> " << target_fps;
    ASSERT_EQ(direct.joints, via_motion.joints);
    const int two_axes = m.skeleton.find("H_TwoAxes");
    double worst_rotation = 0.0, worst_translation = 0.0;
    for (int f = 0; f < direct.frames; ++f) {
      for (int j = 0; j < direct.joints; ++j) {
        if (j == two_axes) continue;
        worst_rotation = std::max(worst_rotation, rotationDistance(direct.rotation(f, j), via_motion.rotation(f, j)));
        worst_translation =
            std::max(worst_translation, (direct.translation(f, j) - via_motion.translation(f, j)).cwiseAbs().maxCoeff());
        ASSERT_NEAR(direct.rotation(f, j).norm(), 1.0, 1e-15);
      }
    }
    EXPECT_LT(worst_rotation, 1e-12) << source_fps << " -> " << target_fps;
    EXPECT_LT(worst_translation, 1e-12) << source_fps << " -> " << target_fps;
  }
}

TEST(ResampleLocalPoses, MidpointIsTheSlerpAtOneHalfAlsoBetweenOppositeSigns) {
  // Two frames of two joints; joint 1's second quaternion is stored negated (the same rotation), which
  // the midpoint must treat as the short way, as slerp does.
  LocalPoses poses;
  poses.frames = 2;
  poses.joints = 2;
  const Eigen::Quaterniond a = eulerToQuaternion(Eigen::Vector3d(10, 70, -30), EulerOrder::ZXY);
  const Eigen::Quaterniond b = eulerToQuaternion(Eigen::Vector3d(40, 20, 100), EulerOrder::ZXY);
  poses.rotations = {a, b, b, Eigen::Quaterniond(-a.coeffs())};
  poses.translations = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(4, 6, 8), Eigen::Vector3d(-1, 0, 1)};
  const LocalPoses up = resampleLocalPoses(poses, 1.0 / 30.0, 60.0);
  ASSERT_EQ(up.frames, 3);
  EXPECT_LT((up.rotation(1, 0).coeffs() - a.slerp(0.5, b).coeffs()).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT(rotationDistance(up.rotation(1, 1), b.slerp(0.5, a)), 1e-15);
  EXPECT_LT(rotationDistance(up.rotation(1, 1), up.rotation(1, 0)), 1e-15);  // b..a is a..b backwards
  EXPECT_EQ(up.translation(1, 0), Eigen::Vector3d(2, 3, 4));
  EXPECT_EQ(up.translation(1, 1), Eigen::Vector3d(0, 1, 2));
  EXPECT_EQ(up.rotation(0, 0).coeffs(), a.coeffs());  // fraction 0: copies
  EXPECT_EQ(up.rotation(2, 1).coeffs(), (-a.coeffs()).eval());
}

TEST(ResampleRowsLinear, ReproducesALinearSignalAtTheNewTimes) {
  // Rows are a + b t: linear interpolation must be exact at every output time.
  const int frames = 37;
  const double source_time = 1.0 / 120.0;
  Eigen::MatrixXd rows(frames, 2);
  for (int f = 0; f < frames; ++f) rows.row(f) << 3.0 + 2.0 * f * source_time, -1.0 - 7.5 * f * source_time;
  const Eigen::MatrixXd out = resampleRowsLinear(rows, source_time, 50.0);
  ASSERT_EQ(out.rows(), 16);  // 0.3 s -> 15 + 1
  for (int k = 0; k < out.rows(); ++k) {
    const double t = k / 50.0;
    EXPECT_NEAR(out(k, 0), 3.0 + 2.0 * t, 1e-12);
    EXPECT_NEAR(out(k, 1), -1.0 - 7.5 * t, 1e-12);
  }
  EXPECT_EQ(resampleRowsLinear(rows, source_time, 120.0), rows);
}

}  // namespace
TEST(ResampleRowsNearest, TakesTheNearestFrameInTimeAndRejectsAnEmptySource) {
  EXPECT_THROW(resampleRowsNearest(Eigen::MatrixXi(0, 4), 1.0 / 30.0, 60.0), std::invalid_argument);
  Eigen::MatrixXi labels(5, 2);
  labels << 0, 10, 1, 11, 2, 12, 3, 13, 4, 14;
  // 30 -> 60 fps: every source frame, and between two the later one (the midpoint rounds up).
  const Eigen::MatrixXi up = resampleRowsNearest(labels, 1.0 / 30.0, 60.0);
  ASSERT_EQ(up.rows(), 9);
  for (Eigen::Index k = 0; k < up.rows(); ++k) EXPECT_EQ(up(k, 0), (k + 1) / 2) << k;
  EXPECT_EQ(up.col(1), (up.col(0).array() + 10).matrix());
  // 30 -> 10 fps: every third frame exactly; 30 -> 12 fps: the nearest of the frames around each time.
  EXPECT_EQ(resampleRowsNearest(labels, 1.0 / 30.0, 10.0).col(0), (Eigen::VectorXi(2) << 0, 3).finished());
  EXPECT_EQ(resampleRowsNearest(labels, 1.0 / 30.0, 12.0).col(0), (Eigen::VectorXi(2) << 0, 3).finished());  // 2.5 -> 3
  EXPECT_EQ(resampleRowsNearest(labels, 1.0 / 30.0, 30.0), labels);
}

}  // namespace motionstyle
