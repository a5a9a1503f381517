// Clean-up properties on a hand-built humanoid (cm, Y-up): exact bones, little change to clean input,
// locked contacts, the floor, unmapped joints untouched, unreachable targets, bounded time, Z-up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "cleanup_humanoid.h"
#include "features/foot_contacts.h"
#include "ik/cleanup.h"
#include "ik/metrics.h"
#include "ik_test_support.h"
#include "motion/rotation.h"

namespace motionstyle {
namespace {

using test::CleanupHumanoid;


TEST_F(CleanupHumanoid, CleanTargetsReturnTheContentClip) {
  CleanupReport report;
  const Motion result = cleanupMotion(input(targets, no_contacts), {}, &report);
  EXPECT_EQ(result.skeleton.jointCount(), clip.skeleton.jointCount());
  EXPECT_EQ(result.skeleton.channelCount(), clip.skeleton.channelCount());
  EXPECT_EQ(result.frame_time, clip.frame_time);
  EXPECT_EQ(result.frameCount(), kFrames);
  EXPECT_LT(meanDistanceCm(worldPositions(result), world), 1e-3);
  EXPECT_EQ(report.frames, kFrames);
  EXPECT_EQ(report.solves, kFrames);
  EXPECT_EQ(report.unknown_rotations, 18);  // hips, 3 per leg, spine, chest, neck, 4 per arm
  EXPECT_TRUE(report.warnings.empty());
  EXPECT_LT(report.max_position_residual_cm, 0.01);
}

TEST_F(CleanupHumanoid, BonesStayExactAndUnmappedJointsKeepTheirRotations) {
  const Eigen::MatrixXd damaged = test::damageTargets(targets, no_contacts, 60.0, 1.0, Eigen::Vector3d::UnitY(), {});
  const Motion result = cleanupMotion(input(damaged, no_contacts), {}, nullptr);
  const Eigen::MatrixXd result_world = worldPositions(result);
  const ClipMetrics m = computeMetrics(MetricsInput{result_world, mapping.joints, skeletonBones(clip.skeleton)});
  EXPECT_LT(m.bone_error_max_cm, 1e-9);
  const LocalPoses before = localPoses(clip), after = localPoses(result);
  for (const char* name : {"LeftThumb", "RightThumb", "Head", "LeftToeBase"}) {
    const int joint = clip.skeleton.find(name);
    for (int f = 0; f < kFrames; ++f)
      ASSERT_LT(rotationDistance(before.rotation(f, joint), after.rotation(f, joint)), 1e-9) << name << " frame " << f;
  }
  // The damage (2 cm smooth noise, 3 % bones) is partly absorbed: closer to the damaged targets than
  // the clean clip is, and within a few cm of both.
  const Eigen::MatrixXd result_canonical = test::canonicalPositions(result_world, mapping);
  EXPECT_LT(meanDistanceCm(result_canonical, damaged), meanDistanceCm(targets, damaged));
  EXPECT_LT(meanDistanceCm(result_canonical, targets), 3.0);
}

TEST_F(CleanupHumanoid, ContactsLockTheFootAtTheFloorPlusItsRestHeight) {
  // The left foot is labelled planted over frames 20-70 while the targets keep it moving.
  Eigen::MatrixXi contacts = no_contacts;
  contacts.block(20, 0, 51, 2).setOnes();
  CleanupReport report;
  const Motion result = cleanupMotion(input(targets, contacts, 0.0), {}, &report);
  const Eigen::MatrixXd result_world = worldPositions(result);
  MetricsInput metrics{result_world, mapping.joints};
  metrics.contacts = contacts;
  metrics.fps = 60.0;
  EXPECT_LT(computeMetrics(metrics).foot_skate_cm_s, 0.1);
  // The targets' own skate was much larger.
  const Eigen::MatrixXd canonical_targets = targets;
  MetricsInput target_metrics{canonical_targets, identityCanonicalJoints()};
  target_metrics.contacts = contacts;
  target_metrics.fps = 60.0;
  EXPECT_GT(computeMetrics(target_metrics).foot_skate_cm_s, 3.0);
  // The content never plants the foot, so the lock stands at the rest height, raised by lockHeight's
  // blend where even the targets' lowest over the contact is over it by more than 1 cm (here 1.9 cm:
  // 0.2 cm up; cleanup_locks.cpp).
  const int ankle = mapping[CanonicalJoint::LeftAnkle];
  const double rest = report.contact_rest_heights[0];
  const double lowest = targets.col(3 * index(CanonicalJoint::LeftAnkle) + 1).segment(20, 51).minCoeff();
  const double share = std::pow(std::max(0.0, (lowest - rest - 1.0) / 4.0), 2);
  ASSERT_LT(share, 0.1) << "the targets' lowest is " << lowest - rest << " cm over the rest height";
  // Where the targets lift the heel more than 2 cm (the lift's and the roll's 1 cm tolerances) before
  // they first put it down, it rolls up on its toe (AHeelTheStyleLiftsOffEarlyRollsUpOnItsToe); the
  // lock's height is checked on the other frames.
  int checked = 0;
  for (int f = 20; f <= 70; ++f) {
    if (targets(f, 3 * index(CanonicalJoint::LeftAnkle) + 1) > lowest + 2.0) continue;
    EXPECT_NEAR(result_world(f, 3 * ankle + 1), rest + 5.0 * share, 0.05) << "frame " << f;
    ++checked;
  }
  EXPECT_GE(checked, 20);
  EXPECT_EQ(report.contact_segments, 2);
}

// A foot the targets lift off quickly (3 m/s from the contact's last frame) is let go within the blend:
// 0.05 s after the contact it is back within 4 cm of its targets (at a 0.06 s blend it lagged 8-10 cm
// behind a style's quick lift-off, docs/decisions.md).
TEST_F(CleanupHumanoid, AFootLiftingOffQuicklyIsLetGoWithinTheBlend) {
  Eigen::MatrixXi contacts = no_contacts;
  contacts.block(20, 0, 31, 2).setOnes();  // left heel and toe, frames 20-50
  Eigen::MatrixXd lifted = targets;
  const int foot_joints[] = {index(CanonicalJoint::LeftAnkle), index(CanonicalJoint::LeftToe)};
  for (int f = 0; f < kFrames; ++f)
    for (int joint : foot_joints) {  // planted where frame 20 has it, then away at 300 cm/s
      lifted.block<1, 3>(f, 3 * joint) = targets.block<1, 3>(std::min(f, 20), 3 * joint);
      if (f > 50) lifted(f, 3 * joint + 2) += 5.0 * (f - 50);
    }
  const Motion result = cleanupMotion(input(lifted, contacts, -50.0), {}, nullptr);
  const Eigen::MatrixXd result_world = worldPositions(result);
  const int ankle = mapping[CanonicalJoint::LeftAnkle];
  const int after = 50 + static_cast<int>(std::ceil(0.05 * 60.0));
  const double residual = (result_world.block<1, 3>(after, 3 * ankle) -
                           lifted.block<1, 3>(after, 3 * index(CanonicalJoint::LeftAnkle))).norm();
  EXPECT_LT(residual, 4.0) << "the ankle " << residual << " cm behind its targets at frame " << after;
}

// The targets of the left foot through a stance (frames 20-70): still where frame 20 has it, then moving
// `speed` cm a frame along z over frames 56-70.
Eigen::MatrixXd footMovingLateInItsStance(const Eigen::MatrixXd& targets, double speed) {
  Eigen::MatrixXd moving = targets;
  for (int f = 0; f < static_cast<int>(targets.rows()); ++f)
    for (CanonicalJoint joint : {CanonicalJoint::LeftAnkle, CanonicalJoint::LeftToe}) {
      moving.block<1, 3>(f, 3 * index(joint)) = targets.block<1, 3>(std::min(f, 20), 3 * index(joint));
      moving(f, 3 * index(joint) + 2) += speed * std::clamp(f - 55, 0, 15);
    }
  return moving;
}

// Over frames 20-70: the ankle's largest distance on the floor from its targets, over the still part
// (20-55) and over the whole stance, and how far the locked ankle moved.
struct StanceFigures {
  double still_worst = 0.0, worst = 0.0, moved = 0.0;
};
StanceFigures stanceFigures(const Eigen::MatrixXd& result_world, const Eigen::MatrixXd& targets, int ankle) {
  StanceFigures s;
  const Eigen::Vector3d start = result_world.block<1, 3>(20, 3 * ankle).transpose();
  for (int f = 20; f <= 70; ++f) {
    const Eigen::Vector3d p = result_world.block<1, 3>(f, 3 * ankle).transpose();
    const Eigen::Vector3d t = targets.block<1, 3>(f, 3 * index(CanonicalJoint::LeftAnkle)).transpose();
    const double off = std::hypot(p.x() - t.x(), p.z() - t.z());
    s.worst = std::max(s.worst, off);
    if (f <= 55) s.still_worst = std::max(s.still_worst, off);
    s.moved = std::max(s.moved, std::hypot(p.x() - start.x(), p.z() - start.z()));
  }
  return s;
}

// A foot the targets hold still for most of a stance and then slide 8 cm (a network drifting a planted
// foot): the lock sits at the middle of the slide, so the foot is never more than half of it from its
// targets (locked at the still part, the median of the targets, it was 8 cm away at the stance's end).
TEST_F(CleanupHumanoid, AFootSlidThroughItsStanceIsLockedHalfWayAlongTheSlide) {
  Eigen::MatrixXi contacts = no_contacts;
  contacts.block(20, 0, 51, 2).setOnes();  // left heel and toe, frames 20-70
  const Eigen::MatrixXd sliding = footMovingLateInItsStance(targets, 8.0 / 15.0);
  const Motion result = cleanupMotion(input(sliding, contacts, -50.0), {}, nullptr);
  const StanceFigures s = stanceFigures(worldPositions(result), sliding, mapping[CanonicalJoint::LeftAnkle]);
  EXPECT_LT(s.worst, 4.5) << "the ankle held " << s.worst << " cm from its sliding targets";
  EXPECT_LT(s.moved, 0.2) << "the locked ankle moved " << s.moved << " cm through its stance";
}

// A stance that holds a step (a contact the user extended over a walking foot, 45 cm in 15 frames): the
// lock leaves the still part at most lock_shift_cm off its targets (half the step, 22 cm, at the
// minimax point alone).
TEST_F(CleanupHumanoid, AStepInsideAStanceMovesItsLockNoMoreThanTheBound) {
  Eigen::MatrixXi contacts = no_contacts;
  contacts.block(20, 0, 51, 2).setOnes();
  const Eigen::MatrixXd stepping = footMovingLateInItsStance(targets, 3.0);
  const Motion result = cleanupMotion(input(stepping, contacts, -50.0), {}, nullptr);
  const StanceFigures s = stanceFigures(worldPositions(result), stepping, mapping[CanonicalJoint::LeftAnkle]);
  EXPECT_LT(s.still_worst, CleanupOptions{}.lock_shift_cm + 0.3) << s.still_worst << " cm off through the still part";
  EXPECT_GT(s.still_worst, 0.5 * CleanupOptions{}.lock_shift_cm);  // moved toward the step, by the bound
  EXPECT_LT(s.moved, 0.2);
}

TEST_F(CleanupHumanoid, FeetStayAboveTheFloor) {
  Eigen::MatrixXd lowered = targets;
  for (int c = 0; c < kCanonicalJointCount; ++c) lowered.col(3 * c + 1).array() -= 12.0;  // toes ~10 cm under
  const Motion result = cleanupMotion(input(lowered, no_contacts, 0.0), {}, nullptr);
  const Eigen::MatrixXd result_world = worldPositions(result);
  const ClipMetrics m = computeMetrics(MetricsInput{result_world, mapping.joints});
  EXPECT_LT(m.penetration_max_cm, 0.1);
  // Without the floor term the toes would go under.
  CleanupOptions no_floor;
  no_floor.keep_above_floor = false;
  const Eigen::MatrixXd free_world = worldPositions(cleanupMotion(input(lowered, no_contacts, 0.0), no_floor, nullptr));
  EXPECT_GT(computeMetrics(MetricsInput{free_world, mapping.joints}).penetration_max_cm, 5.0);
}

TEST_F(CleanupHumanoid, UnreachableTargetsGiveAWarningAndABestEffortResult) {
  const Eigen::MatrixXd stretched = leftWristPulledAway();
  CleanupReport report;
  const Motion result = cleanupMotion(input(stretched, no_contacts), {}, &report);
  EXPECT_TRUE(result.values.allFinite());
  bool found = false;
  for (const std::string& warning : warningTexts(report))
    found = found || (warning.find("targets unreachable: left arm stretched by") != std::string::npos &&
                      warning.find("frames 10-20") != std::string::npos);
  EXPECT_TRUE(found);
  EXPECT_LT(report.seconds, 10.0);
  // Best effort: the arm points at the target, fully extended.
  const Eigen::MatrixXd result_world = worldPositions(result);
  const int f = 15;
  const Eigen::Vector3d base = result_world.block<1, 3>(f, 3 * mapping[CanonicalJoint::LeftUpperArm]).transpose();
  const Eigen::Vector3d hand = result_world.block<1, 3>(f, 3 * mapping[CanonicalJoint::LeftWrist]).transpose();
  EXPECT_GT((hand - base).norm(), 52.0);  // upper arm 28 + forearm 25 = 53 cm
}

// The user's clip may be at another rate than the solve (120 fps content is solved at 60 fps): a
// warning names the frames of the rate it is asked for, all those that overlap the run in time.
// A solve frame named at another rate: the first frame there that overlaps it, a ratio rounded just
// under 2 still doubling it (what the Result panel's worst residual and the warnings both use).
TEST(CleanupFrameAtRate, NamesTheFirstOverlappingFrame) {
  EXPECT_EQ(frameAtRate(67, 2.0), 134);
  EXPECT_EQ(frameAtRate(67, 2.0 - 1e-12), 134);
  EXPECT_EQ(frameAtRate(5, 0.5), 2);
  EXPECT_EQ(frameAtRate(0, 0.4), 0);
  EXPECT_EQ(frameAtRate(7, 1.0), 7);
}

TEST_F(CleanupHumanoid, WarningsNameTheFramesOfTheRateAskedFor) {
  const Eigen::MatrixXd stretched = leftWristPulledAway();
  const auto named = [&](double warning_fps) {
    CleanupOptions options;
    options.warning_fps = warning_fps;
    CleanupReport report;
    cleanupMotion(input(stretched, no_contacts), options, &report);
    for (const CleanupWarning& warning : report.warnings)
      if (warning.text.find("targets unreachable: left arm stretched by") != std::string::npos) return warning;
    return CleanupWarning{"no warning"};
  };
  // The text and the frames a front end shows (first, last) agree.
  const auto expectFrames = [&](double warning_fps, int first, int last) {
    const CleanupWarning warning = named(warning_fps);
    ASSERT_NE(warning.text.find(" at "), std::string::npos) << warning.text;
    EXPECT_EQ(warning.text.substr(warning.text.find(" at ") + 4),
              "frames " + std::to_string(first) + "-" + std::to_string(last));
    EXPECT_EQ(warning.first_frame, first);
    EXPECT_EQ(warning.last_frame, last);
  };
  expectFrames(0.0, 10, 20);               // the solve's own frames (60 fps)
  expectFrames(clip.fps(), 10, 20);
  expectFrames(2.0 * clip.fps(), 20, 41);  // 120 fps: each solve frame is two
  expectFrames(0.5 * clip.fps(), 5, 10);   // 30 fps: 10/2 .. ceil(21/2) - 1
}

TEST_F(CleanupHumanoid, ByDefaultEveryFrameIsSolvedHoweverLong) {
  EXPECT_FALSE(std::isfinite(CleanupOptions{}.max_total_seconds));  // a budget is the caller's choice
  CleanupReport report;
  cleanupMotion(input(targets, no_contacts), CleanupOptions{}, &report);
  EXPECT_EQ(report.frames_unsolved, 0);
}

TEST_F(CleanupHumanoid, TheTimeBudgetBoundsTheSolve) {
  CleanupOptions options;
  options.max_total_seconds = 1e-9;
  CleanupReport report;
  const Motion result = cleanupMotion(input(targets, no_contacts), options, &report);
  EXPECT_EQ(result.frameCount(), kFrames);
  EXPECT_TRUE(result.values.allFinite());
  EXPECT_GT(report.frames_unsolved, 0);
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_NE(report.warnings.back().text.find("time budget"), std::string::npos);
}

TEST_F(CleanupHumanoid, ZUpFileGivesTheSameClip) {
  // The same clip with every offset, root position and rotation turned so that +Y becomes +Z.
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(M_PI / 2.0, Eigen::Vector3d::UnitX()));
  Motion z_up = clip;
  for (Joint& joint : z_up.skeleton.joints) joint.offset = turn * joint.offset;
  LocalPoses poses = localPoses(clip);
  for (size_t i = 0; i < poses.rotations.size(); ++i) {
    poses.rotations[i] = turn * poses.rotations[i] * turn.conjugate();
    poses.translations[i] = turn * poses.translations[i];
  }
  setLocalPoses(poses, z_up);
  const Eigen::MatrixXd damaged = test::damageTargets(targets, no_contacts, 60.0, 1.0, Eigen::Vector3d::UnitY(), {});
  Eigen::MatrixXd z_targets = damaged;
  for (Eigen::Index f = 0; f < damaged.rows(); ++f)
    for (int c = 0; c < kCanonicalJointCount; ++c)
      z_targets.block<1, 3>(f, 3 * c) = (turn * Eigen::Vector3d(damaged.block<1, 3>(f, 3 * c).transpose())).transpose();

  const Eigen::MatrixXd y_result = worldPositions(cleanupMotion(input(damaged, no_contacts, 0.0), {}, nullptr));
  const Motion z_motion = cleanupMotion(
      CleanupInput{z_up, mapping, z_targets, no_contacts, Eigen::Vector3d::UnitZ(), 0.0, 1.0}, {}, nullptr);
  const Eigen::MatrixXd z_result = worldPositions(z_motion);
  double worst = 0.0;
  for (Eigen::Index f = 0; f < y_result.rows(); ++f)
    for (Eigen::Index j = 0; j < y_result.cols() / 3; ++j)
      worst = std::max(worst, (turn * Eigen::Vector3d(y_result.block<1, 3>(f, 3 * j).transpose()) -
                               z_result.block<1, 3>(f, 3 * j).transpose()).norm());
  EXPECT_LT(worst, 1e-3);
}

TEST(CleanupPositionChannels, EveryJointsPerFrameTranslationIsKept) {
  const Motion clip = test::makeHumanoidClip(40, 30.0, /*position_channels_everywhere=*/true);
  const JointMapping mapping = test::humanoidMapping(clip.skeleton);
  const Eigen::MatrixXd targets = test::canonicalPositions(worldPositions(clip), mapping);
  const Eigen::MatrixXi contacts = Eigen::MatrixXi::Zero(40, kContactCount);
  const Eigen::MatrixXd damaged = test::damageTargets(targets, contacts, 30.0, 1.0, Eigen::Vector3d::UnitY(), {});
  const Motion result =
      cleanupMotion(CleanupInput{clip, mapping, damaged, contacts, Eigen::Vector3d::UnitY(), -50.0, 1.0}, {}, nullptr);
  const LocalPoses before = localPoses(clip), after = localPoses(result);
  for (int f = 0; f < 40; ++f)
    for (int j = 1; j < clip.skeleton.jointCount(); ++j)
      ASSERT_LT((before.translation(f, j) - after.translation(f, j)).norm(), 1e-9);
}

TEST_F(CleanupHumanoid, WindowedSolveAgreesWithPerFrameSolve) {
  const Eigen::MatrixXd damaged = test::damageTargets(targets, no_contacts, 60.0, 1.0, Eigen::Vector3d::UnitY(), {});
  CleanupOptions windowed;
  windowed.solver = CleanupSolver::Ceres;
  windowed.window_frames = 6;
  windowed.window_overlap = 2;
  CleanupReport report;
  const Eigen::MatrixXd a = worldPositions(cleanupMotion(input(damaged, no_contacts), {}, nullptr));
  const Eigen::MatrixXd b = worldPositions(cleanupMotion(input(damaged, no_contacts), windowed, &report));
  EXPECT_LT(meanDistanceCm(a, b), 0.5);
  EXPECT_LT(report.solves, kFrames / 3);
  const ClipMetrics m = computeMetrics(MetricsInput{b, mapping.joints, skeletonBones(clip.skeleton)});
  EXPECT_LT(m.bone_error_max_cm, 1e-9);
}

}  // namespace
}  // namespace motionstyle
