// Clean-up properties on a hand-built humanoid (cm, Y-up): exact bones, little change to clean input,
// locked contacts, the floor, unmapped joints untouched, unreachable targets, bounded time, Z-up.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "features/foot_contacts.h"
#include "ik/cleanup.h"
#include "ik/cleanup_locks.h"
#include "ik/metrics.h"
#include "ik_test_support.h"
#include "motion/rotation.h"

namespace motionstyle {
namespace {

class CleanupHumanoid : public ::testing::Test {
 protected:
  static constexpr int kFrames = 90;
  Motion clip = test::makeHumanoidClip(kFrames, 60.0);
  JointMapping mapping = test::humanoidMapping(clip.skeleton);
  Eigen::MatrixXd world = worldPositions(clip);
  Eigen::MatrixXd targets = test::canonicalPositions(world, mapping);
  Eigen::MatrixXi no_contacts = Eigen::MatrixXi::Zero(kFrames, kContactCount);

  CleanupInput input(const Eigen::MatrixXd& t, const Eigen::MatrixXi& c, double floor = -50.0) const {
    return CleanupInput{clip, mapping, t, c, Eigen::Vector3d::UnitY(), floor, 1.0};
  }
  // The targets with the left wrist 30 cm further from the shoulder over frames 10-20: out of reach.
  Eigen::MatrixXd leftWristPulledAway() const {
    Eigen::MatrixXd stretched = targets;
    const int wrist = index(CanonicalJoint::LeftWrist), shoulder = index(CanonicalJoint::LeftUpperArm);
    for (int f = 10; f <= 20; ++f) {
      const Eigen::Vector3d direction =
          (stretched.block<1, 3>(f, 3 * wrist) - stretched.block<1, 3>(f, 3 * shoulder)).transpose().normalized();
      stretched.block<1, 3>(f, 3 * wrist) += 30.0 * direction.transpose();
    }
    return stretched;
  }
  static double meanDistanceCm(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    double sum = 0.0;
    for (Eigen::Index f = 0; f < a.rows(); ++f)
      for (Eigen::Index j = 0; j < a.cols() / 3; ++j) sum += (a.block<1, 3>(f, 3 * j) - b.block<1, 3>(f, 3 * j)).norm();
    return sum / static_cast<double>(a.rows() * (a.cols() / 3));
  }
};

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

// The left foot's targets held where the content's toe is lowest (planted), then raised straight up
// 1 cm a frame from frame `lift_from` on, and `bob` cm up over frames 36-40 (a network's wobble inside
// the stance).
Eigen::MatrixXd footRaisedFrom(const Eigen::MatrixXd& targets, int lift_from, double bob) {
  Eigen::Index planted = 0;
  targets.col(3 * index(CanonicalJoint::LeftToe) + 1).minCoeff(&planted);
  Eigen::MatrixXd raised = targets;
  for (int f = 0; f < static_cast<int>(targets.rows()); ++f)
    for (CanonicalJoint joint : {CanonicalJoint::LeftAnkle, CanonicalJoint::LeftToe}) {
      raised.block<1, 3>(f, 3 * index(joint)) = targets.block<1, 3>(planted, 3 * index(joint));
      raised(f, 3 * index(joint) + 1) += std::max(0, f - lift_from) + (f >= 36 && f <= 40 ? bob : 0.0);
    }
  return raised;
}

// `positions` with the joint at column `moving` turned `rise` cm up about the joint at column `pivot`
// on every frame, the distance between them kept (a foot tipped onto its toe, or its toe lifted). NaN
// where the two already stand less than `rise` from vertical.
Eigen::MatrixXd turnedUp(Eigen::MatrixXd positions, int pivot, int moving, double rise) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  for (Eigen::Index f = 0; f < positions.rows(); ++f) {
    const Eigen::Vector3d at = positions.block<1, 3>(f, pivot).transpose();
    const Eigen::Vector3d bone = positions.block<1, 3>(f, moving).transpose() - at;
    const Eigen::Vector3d across = (bone - up.dot(bone) * up).normalized();
    const double height = up.dot(bone) + rise;
    positions.block<1, 3>(f, moving) = (at + across * std::sqrt(bone.squaredNorm() - height * height) + up * height).transpose();
  }
  return positions;
}

// A toe the style lifts off before the content's contact ends, its heel already free (heel contact
// 20-30, toe 20-60, the foot raised from frame 48): the toe rises with its targets (within the 1 cm
// tolerance; held down it was 14 cm under them at frame 60) and stays still over the floor. With the
// heel locked too, the two rise together by the smaller lift (the whole foot lifted off: the toe was
// held 11 cm under it), but a toe rising while its heel stays down stays down: the foot's length ties
// the two. A 3 cm wobble inside the stance is not followed (the foot stays on the floor). With no pull
// toward the targets (position_weight 0) the lone lock still holds the toe in place (its lift read
// 0 / 0 there).
TEST_F(CleanupHumanoid, AToeTheStyleLiftsOffEarlyRisesWithItsTargetsAndStaysStill) {
  const Eigen::MatrixXd raised = footRaisedFrom(targets, 48, 3.0);
  const int toe = mapping[CanonicalJoint::LeftToe];
  const int toe_column = 3 * index(CanonicalJoint::LeftToe);
  Eigen::MatrixXi toe_alone = no_contacts;
  toe_alone.block(20, 0, 11, 1).setOnes();  // left heel 20-30
  toe_alone.block(20, 1, 41, 1).setOnes();  // left toe 20-60
  // How far the cleaned toe has moved over the floor since frame 45, in the stance.
  const auto slidSince45 = [&](const Eigen::MatrixXd& cleaned, int f) {
    return std::hypot(cleaned(f, 3 * toe) - cleaned(45, 3 * toe), cleaned(f, 3 * toe + 2) - cleaned(45, 3 * toe + 2));
  };
  const Eigen::MatrixXd alone = worldPositions(cleanupMotion(input(raised, toe_alone, 0.0), {}, nullptr));
  const double locked_height = alone(45, 3 * toe + 1);
  for (int f = 52; f <= 60; ++f) {
    EXPECT_NEAR(alone(f, 3 * toe + 1), raised(f, toe_column + 1), 1.3) << "frame " << f;
    EXPECT_LT(slidSince45(alone, f), 0.2) << "the toe slid at frame " << f;
  }
  for (int f = 36; f <= 40; ++f) EXPECT_NEAR(alone(f, 3 * toe + 1), locked_height, 0.3) << "frame " << f;

  Eigen::MatrixXi both = no_contacts;
  both.block(20, 0, 41, 2).setOnes();  // heel and toe 20-60
  const Eigen::MatrixXd together = worldPositions(cleanupMotion(input(raised, both, 0.0), {}, nullptr));
  for (int f = 52; f <= 60; ++f) {
    EXPECT_NEAR(together(f, 3 * toe + 1), raised(f, toe_column + 1), 1.3) << "frame " << f;
    EXPECT_LT(slidSince45(together, f), 0.2) << "the foot slid at frame " << f;
  }
  Eigen::MatrixXd toe_only = raised;  // the heel's targets held down (with the wobble), the toe's rising
  const int heel_height = 3 * index(CanonicalJoint::LeftAnkle) + 1;
  toe_only.col(heel_height) = footRaisedFrom(targets, kFrames, 3.0).col(heel_height);
  const Eigen::MatrixXd tied = worldPositions(cleanupMotion(input(toe_only, both, 0.0), {}, nullptr));
  EXPECT_NEAR(tied(58, 3 * toe + 1), tied(45, 3 * toe + 1), 1.0);

  // Without the pull toward the targets (a valid weight of 0) the lone toe is still held in place.
  CleanupOptions locks_only;
  locks_only.position_weight = 0.0;
  const Eigen::MatrixXd held = worldPositions(cleanupMotion(input(raised, toe_alone, 0.0), locks_only, nullptr));
  for (int f = 52; f <= 60; ++f)
    EXPECT_LT(slidSince45(held, f), 0.2) << "frame " << f;
}

// A heel the style lifts off before the content's contact ends while its toe stays down (heel and toe
// contacts 20-60; from frame 48 the heel's targets rise straight up, 1 cm a frame): its lock rises past
// the toe's (the smaller-lift rule held it on the floor with its toe) by the lift less the two 1 cm
// tolerances, or as far as the foot's length lets it, turning about the toe's lock (their distance
// kept, so toward it along the floor), while the toe's lock stays where it was; the cleaned heel
// comes up and the toe holds still. A toe lifted while its heel stays down does not roll
// (AToeTheStyleLiftsOffEarly..., above).
TEST_F(CleanupHumanoid, AHeelTheStyleLiftsOffEarlyRollsUpOnItsToe) {
  const int heel_column = 3 * index(CanonicalJoint::LeftAnkle);
  Eigen::MatrixXd lifting = footRaisedFrom(targets, kFrames, 0.0);  // the foot held still ...
  for (int f = 49; f < kFrames; ++f) lifting(f, heel_column + 1) += f - 48.0;  // ... its heel lifted
  Eigen::MatrixXi both = no_contacts;
  both.block(20, 0, 41, 2).setOnes();
  const CleanupInput lifted = input(lifting, both, 0.0);

  const Eigen::MatrixXd feet_world = worldPositions(clip, contactJoints(mapping));
  const ik_detail::ContactLocks locks =
      ik_detail::contactLocks(lifted, {}, ik_detail::contentFootHeights(lifted, feet_world), feet_world);
  const auto lockAt = [&](int f, int label) { return locks.positions[static_cast<size_t>(f)][static_cast<size_t>(label)]; };
  const auto across = [](const Eigen::Vector3d& v) { return std::hypot(v.x(), v.z()); };
  const Eigen::Vector3d foot = lockAt(45, 0) - lockAt(45, 1);  // heel over toe, as the stance holds it
  const double highest = foot.norm() - foot.y();               // the heel's rise to stand over its toe
  ASSERT_GT(highest, 1.0);
  for (int f = 51; f <= 60; ++f) {
    EXPECT_NEAR(lockAt(f, 0).y() - lockAt(45, 0).y(), std::min(f - 48.0 - 2.0, highest), 0.01) << "frame " << f;
    EXPECT_NEAR((lockAt(f, 0) - lockAt(f, 1)).norm(), foot.norm(), 0.01) << "the foot's length, frame " << f;
    EXPECT_LT(across(lockAt(f, 0) - lockAt(f, 1)), across(foot) - 0.2) << "toward the toe, frame " << f;
    EXPECT_LT((lockAt(f, 1) - lockAt(45, 1)).norm(), 1e-9) << "the toe's lock stays, frame " << f;
  }

  const Eigen::MatrixXd cleaned = worldPositions(cleanupMotion(lifted, {}, nullptr));
  const int heel = mapping[CanonicalJoint::LeftAnkle], toe = mapping[CanonicalJoint::LeftToe];
  for (int f = 54; f <= 60; ++f) {
    EXPECT_GT(cleaned(f, 3 * heel + 1) - cleaned(45, 3 * heel + 1), 0.8 * highest) << "the heel comes up, frame " << f;
    EXPECT_LT(std::hypot(cleaned(f, 3 * toe) - cleaned(45, 3 * toe), cleaned(f, 3 * toe + 2) - cleaned(45, 3 * toe + 2)), 0.3)
        << "the toe slid at frame " << f;
    EXPECT_NEAR(cleaned(f, 3 * toe + 1), cleaned(45, 3 * toe + 1), 0.5) << "frame " << f;
  }
}

// The left foot held still `heel_up` and `toe_up` cm above where it rests through a heel and toe
// contact (frames 20-40): both joints stay within 2 cm of those heights.
class CleanupFootHeldUp : public CleanupHumanoid {
 protected:
  void expectHeldUp(double heel_up, double toe_up) {
    Eigen::MatrixXd held = footRaisedFrom(targets, kFrames, 0.0);  // the foot held still, not lifted
    const int heel_column = 3 * index(CanonicalJoint::LeftAnkle), toe_column = 3 * index(CanonicalJoint::LeftToe);
    held.col(heel_column + 1).array() += heel_up;
    held.col(toe_column + 1).array() += toe_up;
    expectLockedOnTargets(held);
  }
  // A heel contact over frames heel_from-40 and a toe contact over 20-40: the cleaned heel and toe
  // stay at `held`'s heights through them. Returns the cleaned clip's world positions.
  Eigen::MatrixXd expectLockedOnTargets(const Eigen::MatrixXd& held, int heel_from = 20) {
    const int heel_column = 3 * index(CanonicalJoint::LeftAnkle), toe_column = 3 * index(CanonicalJoint::LeftToe);
    Eigen::MatrixXi contacts = no_contacts;
    contacts.block(heel_from, 0, 41 - heel_from, 1).setOnes();
    contacts.block(20, 1, 21, 1).setOnes();
    const Eigen::MatrixXd cleaned = worldPositions(cleanupMotion(input(held, contacts, 0.0), {}, nullptr));
    const int heel = mapping[CanonicalJoint::LeftAnkle], toe = mapping[CanonicalJoint::LeftToe];
    for (int f = 22; f <= 38; ++f) {
      EXPECT_NEAR(cleaned(f, 3 * heel + 1), held(f, heel_column + 1), 2.0) << "frame " << f;
      EXPECT_NEAR(cleaned(f, 3 * toe + 1), held(f, toe_column + 1), 2.0) << "frame " << f;
    }
    return cleaned;
  }
};

// A foot the style holds up through a contact whose content foot is never planted (it moves there, as
// a run's quick stance can: no height of its own to compare with): the targets hold the left heel and
// toe still, 10 cm above where the foot rests, over a heel and toe contact. The locks take the
// targets' height, as where the content plants the foot (lockHeight); at the clip's rest height they
// pulled the foot 10 cm down (Bandai's run 012 with masculine: its heel 9.7 cm from the targets, and
// the toe's lock, placed the foot's length from it, turned the foot up; docs/decisions.md).
TEST_F(CleanupFootHeldUp, AFootTheStyleHoldsUpWhereTheContentNeverPlantsItStaysUp) { expectHeldUp(10.0, 10.0); }

// The same foot held still 4.5 cm up, under the 5 cm at which a lock takes its targets' height: the
// locks move most of the way up, as lockHeight's blend moves them over a content's planted height
// (against the rest height here, where there is none). They stayed at the rest height, 4.5 cm under
// their targets (Bandai's walk-turn-left_active_037 with sad: a heel contact found on the output alone
// at the clip's start, the knee 9.8 cm from its target; docs/decisions.md).
TEST_F(CleanupFootHeldUp, AFootTheStyleHoldsALittleUpWhereTheContentNeverPlantsItIsLockedPartlyUp) {
  expectHeldUp(4.5, 4.5);
}

// An uneven floor: the content's body dips 5 cm over four frames where its left heel moves lowest
// (never planted: the foot keeps moving) and the targets hold the left foot 3 cm under the content's
// there, through the floor it stood on. A contact over the dip is locked where the content's own foot
// goes lowest, not at the clip's rest height above it (CMU 07_01 with youthful: a toe found planted on
// the output at the first step, the content's 3.6 cm under its rest height, was locked 7.1 cm over its
// targets; docs/decisions.md).
TEST_F(CleanupHumanoid, AContactWhereTheContentsFootGoesUnderItsRestHeightIsLockedThere) {
  const int heel = mapping[CanonicalJoint::LeftAnkle];
  Eigen::Index low = 0;
  world.col(3 * heel + 1).segment(10, kFrames - 20).minCoeff(&low);
  const int first = static_cast<int>(low) + 10 - 1;
  Motion dipped = clip;
  for (int f = first; f < first + 4; ++f) dipped.values(f, 1) -= 5.0;  // the root's Y position channel
  const Eigen::MatrixXd content = worldPositions(dipped);
  Eigen::MatrixXd pushed = test::canonicalPositions(content, mapping);
  const int heel_column = 3 * index(CanonicalJoint::LeftAnkle), toe_column = 3 * index(CanonicalJoint::LeftToe);
  for (int f = first; f < first + 4; ++f)
    for (int column : {heel_column, toe_column}) pushed(f, column + 1) -= 3.0;
  Eigen::MatrixXi contacts = no_contacts;
  contacts.block(first, 0, 4, 2).setOnes();
  CleanupReport report;
  const Eigen::MatrixXd cleaned =
      worldPositions(cleanupMotion(CleanupInput{dipped, mapping, pushed, contacts, Eigen::Vector3d::UnitY(), 0.0, 1.0},
                                   {}, &report));
  const double lowest = content.col(3 * heel + 1).segment(first, 4).minCoeff();
  ASSERT_LT(lowest, report.contact_rest_heights[0] - 2.0) << "the dip does not take the heel under its rest height";
  for (int f = first + 1; f <= first + 2; ++f) EXPECT_NEAR(cleaned(f, 3 * heel + 1), lowest, 1.0) << "frame " << f;
}

// The style holds the whole foot up, the heel 7 cm and the toe 4 cm (only the heel over the 5 cm at
// which a lock takes its targets' height): both locks rise, neither is pulled to the other's height.
TEST_F(CleanupFootHeldUp, AFootTheStyleHoldsUpWholeIsHeldUpWhole) { expectHeldUp(7.0, 4.0); }

// The style holds the toe 6 cm up (its lock at the targets' height) and the heel where the content
// plants it, still above the toe: the toe's lock, placed the foot's length from the heel's, stays
// below the heel as its targets are. It was put above it, the foot turned up (Bandai's
// walk_active_001 with youthful: the toe 14 cm over its targets; docs/decisions.md).
TEST_F(CleanupFootHeldUp, AToeTheStyleRaisesBelowItsHeelStaysBelowIt) {
  const int heel_column = 3 * index(CanonicalJoint::LeftAnkle), toe_column = 3 * index(CanonicalJoint::LeftToe);
  const Eigen::MatrixXd held = turnedUp(footRaisedFrom(targets, kFrames, 0.0), heel_column, toe_column, 6.0);
  ASSERT_TRUE(held.allFinite());
  ASSERT_LT(held(30, toe_column + 1), held(30, heel_column + 1) - 2.0) << "the raised toe is still under its heel";
  expectLockedOnTargets(held);
}

// A forefoot stance the style partly raises: the toe 1 cm over where the foot rests (the lock stays at
// the content's height) and the heel, turned up about it (the foot's length kept), 2.4 cm over (its
// lock rises 0.6 cm, lockHeight's blend). The locks' heights then leave the foot steeper than the
// targets': slid along the floor to the foot's length from the toe, the heel went toward it,
// over it where the heights differ by the foot's length (Bandai's run_exhausted_031 with masculine:
// 9.0 cm from its targets; its toe landed a frame before the heel, as here). Pivoted about the toe,
// its place over the floor kept, it stays with them.
TEST_F(CleanupFootHeldUp, AHeelTheStylePartlyRaisesPivotsOnItsToe) {
  const int heel_column = 3 * index(CanonicalJoint::LeftAnkle), toe_column = 3 * index(CanonicalJoint::LeftToe);
  Eigen::MatrixXd held = footRaisedFrom(targets, kFrames, 0.0);  // the foot held still, 1 cm up
  held.col(heel_column + 1).array() += 1.0;
  held.col(toe_column + 1).array() += 1.0;
  held = turnedUp(held, toe_column, heel_column, 1.4);
  ASSERT_TRUE(held.allFinite()) << "the humanoid's foot is too steep to turn up 1.4 cm more";
  const Eigen::MatrixXd cleaned = expectLockedOnTargets(held, 21);  // the toe lands first
  const int heel = mapping[CanonicalJoint::LeftAnkle];
  for (int f = 23; f <= 38; ++f)
    EXPECT_LT((cleaned.block<1, 3>(f, 3 * heel) - held.block<1, 3>(f, heel_column)).norm(), 1.5) << "frame " << f;
}

// A landing found on the output two frames before the content's stance: the heel is locked over frames
// 20-22, 4 cm behind where it then stands, and again over 24-40; the toe over 20-40, on its targets.
// The brief heel lock, starting with the toe's, must not anchor it: the toe stays within 0.6 cm of its
// targets and the brief lock is set the foot's length from it. Anchored, the toe was 2.4 cm off here
// (Bandai's walk_proud_002 with feminine: 5 cm behind its targets, 8.3 cm at worst; docs/decisions.md).
TEST_F(CleanupFootHeldUp, ABriefHeelLockDoesNotMoveTheToesLongerOne) {
  const int heel_column = 3 * index(CanonicalJoint::LeftAnkle), toe_column = 3 * index(CanonicalJoint::LeftToe);
  Eigen::MatrixXd held = footRaisedFrom(targets, kFrames, 0.0);  // the foot held still
  const Eigen::Vector3d back = (held.block<1, 3>(30, heel_column) - held.block<1, 3>(30, toe_column)).transpose()
                                   .cwiseProduct(Eigen::Vector3d(1.0, 0.0, 1.0)).normalized();
  for (int f = 20; f <= 22; ++f) held.block<1, 3>(f, heel_column) += 4.0 * back.transpose();
  Eigen::MatrixXi contacts = no_contacts;
  contacts.block(20, 0, 3, 1).setOnes();
  contacts.block(24, 0, 17, 1).setOnes();
  contacts.block(20, 1, 21, 1).setOnes();
  const Eigen::MatrixXd cleaned = worldPositions(cleanupMotion(input(held, contacts, 0.0), {}, nullptr));
  const int toe = mapping[CanonicalJoint::LeftToe];
  for (int f = 24; f <= 38; ++f)
    EXPECT_LT((cleaned.block<1, 3>(f, 3 * toe) - held.block<1, 3>(f, toe_column)).norm(), 1.2) << "frame " << f;
}

// A toe the style holds up through its stance (8 cm over where the foot rests, the lock at the
// targets' height) and puts down to the floor over the stance's last four frames, its heel already
// free: the lock falls with its targets (within the 1 cm tolerance; held up it was 8 cm over them) and
// stays still over the floor (cleanup_locks.cpp, raiseDepartingLocks).
TEST_F(CleanupHumanoid, AToeTheStyleHoldsUpAndPutsDownFallsWithItsTargets) {
  Eigen::MatrixXd held = footRaisedFrom(targets, kFrames, 0.0);  // the foot held still
  const int heel_column = 3 * index(CanonicalJoint::LeftAnkle), toe_column = 3 * index(CanonicalJoint::LeftToe);
  held.col(heel_column + 1).array() += 8.0;
  held.col(toe_column + 1).array() += 8.0;
  for (int f = 37; f <= 40; ++f) held(f, toe_column + 1) -= 2.0 * (f - 36);  // down to where it rests
  Eigen::MatrixXi contacts = no_contacts;
  contacts.block(20, 0, 15, 1).setOnes();  // left heel 20-34
  contacts.block(20, 1, 21, 1).setOnes();  // left toe 20-40
  const Eigen::MatrixXd cleaned = worldPositions(cleanupMotion(input(held, contacts, 0.0), {}, nullptr));
  const int toe = mapping[CanonicalJoint::LeftToe];
  EXPECT_NEAR(cleaned(30, 3 * toe + 1), held(30, toe_column + 1), 1.0);  // held up through the stance
  for (int f = 39; f <= 40; ++f) {
    EXPECT_NEAR(cleaned(f, 3 * toe + 1), held(f, toe_column + 1), 1.3) << "frame " << f;
    EXPECT_LT(std::hypot(cleaned(f, 3 * toe) - cleaned(30, 3 * toe), cleaned(f, 3 * toe + 2) - cleaned(30, 3 * toe + 2)), 0.3)
        << "the toe slid at frame " << f;
  }
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
