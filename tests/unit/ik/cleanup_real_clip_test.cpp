// Acceptance on the real fixtures: CMU 131_01 (120 fps, Y-up, CMU unit) and zombie (30 fps, Z-up,
// inches). Damage = 2 cm smooth noise + 0.3 cm jitter per joint, 6 cm/s foot sliding during contact,
// +-3 % bone lengths (ik_test_support.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "bvh/bvh_reader.h"
#include "features/foot_contacts.h"
#include "features/signal_filters.h"
#include "ik/cleanup.h"
#include "ik/contacts.h"
#include "ik/metrics.h"
#include "ik_test_support.h"
#include "mapping/joint_mapping.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

struct Fixture {
  const char* file;
  Eigen::Vector3d up;
  double cm_per_unit;
};

void PrintTo(const Fixture& fixture, std::ostream* out) { *out << fixture.file; }

// The median height along `up` of joint j (world: frames x 3J) over a contact segment, file units.
double medianHeight(const Eigen::MatrixXd& world, int j, const ContactSegment& segment, const Eigen::Vector3d& up) {
  std::vector<double> heights;
  for (int f = segment.first; f <= segment.last; ++f) heights.push_back(up.dot(world.block<1, 3>(f, 3 * j).transpose()));
  return median(std::move(heights));
}

class CleanupRealClip : public ::testing::TestWithParam<Fixture> {
 protected:
  void SetUp() override {
    clip = readBvh(test::fixture(GetParam().file));
    mapping = mapJoints(clip.skeleton, clip.source);
    up = GetParam().up;
    cm = GetParam().cm_per_unit;
    world = worldPositions(clip);
    const std::array<int, kContactCount> feet = contactJoints(mapping);
    floor = estimateFloorHeight(world, feet, up);
    contacts = detectContacts(world, feet, up, floor, clip.fps(), restPoseBodyHeight(clip.skeleton, up));
    clean_targets = test::canonicalPositions(world, mapping);
  }

  Motion clean(const Eigen::MatrixXd& targets, CleanupReport& report) const {
    return cleanupMotion(CleanupInput{clip, mapping, targets, contacts, up, floor, cm}, {}, &report);
  }

  ClipMetrics metricsOf(const Eigen::MatrixXd& result_world, const Eigen::MatrixXd& targets) const {
    return test::cleanedClipMetrics(result_world, clip, mapping, contacts, targets, up, floor, cm);
  }

  Motion clip;
  JointMapping mapping;
  Eigen::Vector3d up;
  double cm = 1.0;
  double floor = 0.0;
  Eigen::MatrixXd world;
  Eigen::MatrixXi contacts;
  Eigen::MatrixXd clean_targets;
};

TEST_P(CleanupRealClip, DamagedTargetsComeOutClean) {
  ASSERT_GT(contacts.sum(), clip.frameCount() / 2) << "the fixture should have plenty of foot contact";
  const Eigen::MatrixXd damaged = test::damageTargets(clean_targets, contacts, clip.fps(), cm, up, {});
  MetricsInput damaged_input{damaged, identityCanonicalJoints(), canonicalBones(world, mapping)};
  damaged_input.contacts = contacts;
  damaged_input.up = up;
  damaged_input.floor_height = floor;
  damaged_input.cm_per_unit = cm;
  damaged_input.fps = clip.fps();
  const ClipMetrics target_metrics = computeMetrics(damaged_input);

  CleanupReport report;
  const Motion result = clean(damaged, report);
  const ClipMetrics m = metricsOf(worldPositions(result), damaged);
  std::printf("[ figures  ] %s: targets skate %.2f cm/s, bone error max %.2f cm | result skate %.3f cm/s, "
              "penetration max %.3f cm, residual mean %.2f max %.2f cm, bone error max %.1e cm, %.2f s, "
              "%d iterations over %d solves, %zu warnings\n",
              GetParam().file, target_metrics.foot_skate_cm_s, target_metrics.bone_error_max_cm, m.foot_skate_cm_s,
              m.penetration_max_cm, m.residual_mean_cm, m.residual_max_cm, m.bone_error_max_cm, report.seconds,
              report.total_iterations, report.solves, report.warnings.size());
  // The damage is real: the targets' feet move during contact (slide plus per-frame jitter) and their
  // bones are off by centimetres.
  EXPECT_GT(target_metrics.foot_skate_cm_s, 3.0);
  EXPECT_GT(target_metrics.bone_error_max_cm, 1.0);
  EXPECT_LE(m.foot_skate_cm_s, 0.5);
  EXPECT_LE(m.penetration_max_cm, 0.5);
  EXPECT_LE(m.residual_mean_cm, 2.0);
  EXPECT_LE(m.bone_error_max_cm, 1e-4);
  EXPECT_EQ(report.frames_unsolved, 0);
}

TEST_P(CleanupRealClip, CleanClipChangesLittle) {
  CleanupReport report;
  const Motion result = clean(clean_targets, report);
  const ClipMetrics m = metricsOf(worldPositions(result), clean_targets);
  std::printf("[ figures  ] %s clean: mean change %.3f cm, max %.2f cm, skate %.3f cm/s\n", GetParam().file,
              m.residual_mean_cm, m.residual_max_cm, m.foot_skate_cm_s);
  EXPECT_LE(m.residual_mean_cm, 1.0);  // targets = the clip itself: the residual is the change
  EXPECT_LE(m.foot_skate_cm_s, 0.5);
}

TEST_P(CleanupRealClip, OnASlopedFloorEachStepKeepsTheContentsHeight) {
  // The clip walked up a ramp that rises 8 cm over its length (the root's position channels, X Y Z in
  // both files, raised along `up`): captured floors are not flat. Cleaned toward itself, each contact
  // holds the ankle where the content's ankle is during that contact. A single height for the whole
  // clip puts the first and last steps about 4 cm off. With the left foot's targets 3 cm lower
  // throughout, a contact over the clip's rest height (the median over all its contacts) is locked
  // ((3 - 1) / 4)^2 = 1/4 of the way down to it, one under it where it is (cleanup_locks.cpp).
  Motion sloped = clip;
  const double rise = 8.0 / cm;
  for (int f = 0; f < sloped.frameCount(); ++f)
    for (int axis = 0; axis < 3; ++axis) sloped.values(f, axis) += rise * up[axis] * f / (sloped.frameCount() - 1);
  const Eigen::MatrixXd sloped_world = worldPositions(sloped);
  const std::array<int, kContactCount> feet = contactJoints(mapping);
  const double low_floor = estimateFloorHeight(sloped_world, feet, up);
  const Eigen::MatrixXi sloped_contacts =
      detectContacts(sloped_world, feet, up, low_floor, sloped.fps(), restPoseBodyHeight(sloped.skeleton, up));
  const int heel = static_cast<int>(ContactLabel::LeftHeel);
  const int ankle = feet[static_cast<size_t>(heel)];
  std::vector<double> planted;
  for (int f = 0; f < sloped_contacts.rows(); ++f)
    if (sloped_contacts(f, heel) != 0) planted.push_back(up.dot(sloped_world.block<1, 3>(f, 3 * ankle).transpose()));
  const double rest = median(std::move(planted));
  for (const double drop : {0.0, 3.0}) {
    Eigen::MatrixXd targets = test::canonicalPositions(sloped_world, mapping);
    for (const int c : {index(CanonicalJoint::LeftAnkle), index(CanonicalJoint::LeftToe)})
      for (int f = 0; f < targets.rows(); ++f) targets.block<1, 3>(f, 3 * c) -= (drop / cm) * up.transpose();
    const Eigen::MatrixXd result_world =
        worldPositions(cleanupMotion(CleanupInput{sloped, mapping, targets, sloped_contacts, up, low_floor, cm}, {}, nullptr));
    int segments = 0, lowered = 0;
    for (const ContactSegment& segment : contactSegments(sloped_contacts, heel)) {
      const double content_height = medianHeight(sloped_world, ankle, segment, up);
      const double locked = content_height + (drop > 0.0 ? 0.25 * std::min(0.0, rest - content_height) : 0.0);
      lowered += locked < content_height - 0.5 / cm;
      // A heel its own targets lift more than 2 cm as the step ends rolls up on its toe (cleanup_test.cpp,
      // AHeelTheStyleLiftsOffEarlyRollsUpOnItsToe): the lock's height is checked on the other frames.
      const int target_column = 3 * index(CanonicalJoint::LeftAnkle);
      double lowest = up.dot(targets.block<1, 3>(segment.first, target_column).transpose());
      for (int f = segment.first; f <= segment.last; ++f)
        lowest = std::min(lowest, up.dot(targets.block<1, 3>(f, target_column).transpose()));
      for (int f = segment.first; f <= segment.last; ++f) {
        if (up.dot(targets.block<1, 3>(f, target_column).transpose()) > lowest + 2.0 / cm) continue;
        ASSERT_NEAR(up.dot(result_world.block<1, 3>(f, 3 * ankle).transpose()) * cm, locked * cm, 0.5)
            << "drop " << drop << ", frame " << f << " of the contact " << segment.first << "-" << segment.last;
      }
      ++segments;
    }
    EXPECT_GE(segments, 2);
    if (drop > 0.0) {
      EXPECT_GE(lowered, 1);
    }
  }
}

TEST_P(CleanupRealClip, AFootTheTargetsHoldALittleUpIsLockedPartlyUp) {
  // The left foot's targets h cm over the clip's own through every frame: within the network's wobble
  // (h = 0.5) each heel contact holds the ankle on the content's height; at h = 3 the lock rises by
  // 5 ((3 - 1) / 4)^2 = 1.25 cm (cleanup_locks.cpp: a style's small lift followed continuously).
  const std::array<int, kContactCount> feet = contactJoints(mapping);
  const int heel = static_cast<int>(ContactLabel::LeftHeel);
  const int ankle = feet[static_cast<size_t>(heel)];
  for (const auto& [lift, locked_up] : {std::pair{0.5, 0.0}, std::pair{3.0, 1.25}}) {
    Eigen::MatrixXd raised = clean_targets;
    for (const int c : {index(CanonicalJoint::LeftAnkle), index(CanonicalJoint::LeftToe)})
      for (int f = 0; f < raised.rows(); ++f) raised.block<1, 3>(f, 3 * c) += (lift / cm) * up.transpose();
    CleanupReport report;
    const Eigen::MatrixXd result_world = worldPositions(clean(raised, report));
    int segments = 0;
    for (const ContactSegment& segment : contactSegments(contacts, heel)) {
      const double content_height = medianHeight(world, ankle, segment, up);
      const int middle = (segment.first + segment.last) / 2;
      EXPECT_NEAR((up.dot(result_world.block<1, 3>(middle, 3 * ankle).transpose()) - content_height) * cm, locked_up, 0.5)
          << "lift " << lift << ", frame " << middle << " of the contact " << segment.first << "-" << segment.last;
      ++segments;
    }
    EXPECT_GE(segments, 2);
  }
}

TEST_P(CleanupRealClip, StretchedLegWarnsAndStaysBounded) {
  Eigen::MatrixXd stretched = clean_targets;
  const int ankle = index(CanonicalJoint::RightAnkle), toe = index(CanonicalJoint::RightToe);
  const int first = clip.frameCount() / 4, last = first + clip.frameCount() / 10;
  for (int f = first; f <= last; ++f)
    for (int c : {ankle, toe}) stretched.block<1, 3>(f, 3 * c) -= (15.0 / cm) * up.transpose();  // 15 cm down
  CleanupReport report;
  const Motion result = clean(stretched, report);
  EXPECT_TRUE(result.values.allFinite());
  bool found = false;
  for (const std::string& warning : warningTexts(report))
    found = found || warning.find("targets unreachable: right leg stretched by") != std::string::npos;
  EXPECT_TRUE(found);
  EXPECT_LT(report.seconds, 30.0);
  EXPECT_EQ(report.frames_unsolved, 0);
}

// CMU 131_01 kneels (about 2.8-3.5 s in): the left ankle is planted 13 cm up, the foot on its instep.
// A style network stands the character up through it, its left foot on the floor under the knee. The
// lock must not hold that standing foot at the kneel's height: more than 5 cm from the target's height
// over the contact, the content's height says nothing of the floor, and the lock takes the rest height.
TEST(CleanupLockHeight, AKneelDoesNotHoldAStandingTargetFootAtItsHeight) {
  const Motion clip = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(clip.skeleton, clip.source);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  const double cm = 2.54 / 0.45;
  const Eigen::MatrixXd world = worldPositions(clip);
  const std::array<int, kContactCount> feet = contactJoints(mapping);
  const double floor = estimateFloorHeight(world, feet, up);
  const Eigen::MatrixXi contacts = detectContacts(world, feet, up, floor, clip.fps(), restPoseBodyHeight(clip.skeleton, up));
  const int heel = static_cast<int>(ContactLabel::LeftHeel);
  const int ankle = feet[static_cast<size_t>(heel)];
  const auto heightCm = [&](const Eigen::MatrixXd& positions, int column, int f) {
    return (up.dot(positions.block<1, 3>(f, 3 * column).transpose()) - floor) * cm;
  };
  std::optional<ContactSegment> kneel;
  double kneel_cm = 0.0;
  for (const ContactSegment& segment : contactSegments(contacts, heel)) {
    std::vector<double> heights;
    for (int f = segment.first; f <= segment.last; ++f) heights.push_back(heightCm(world, ankle, f));
    std::sort(heights.begin(), heights.end());
    if (heights[heights.size() / 2] >= 10.0) {
      kneel = segment;
      kneel_cm = heights[heights.size() / 2];
    }
  }
  ASSERT_TRUE(kneel.has_value()) << "the fixture's kneel (a left-heel contact 10 cm or more above the floor)";
  // The targets: the clip itself, but the left foot 8 cm lower over the kneel, as a standing foot.
  Eigen::MatrixXd targets = test::canonicalPositions(world, mapping);
  const int target_ankle = index(CanonicalJoint::LeftAnkle), target_toe = index(CanonicalJoint::LeftToe);
  for (int f = kneel->first; f <= kneel->last; ++f)
    for (int joint : {target_ankle, target_toe}) targets.block<1, 3>(f, 3 * joint) -= (8.0 / cm) * up.transpose();
  const Motion result = cleanupMotion(CleanupInput{clip, mapping, targets, contacts, up, floor, cm}, {}, nullptr);
  const Eigen::MatrixXd result_world = worldPositions(result);
  for (int f = kneel->first; f <= kneel->last; ++f) {
    const double cleaned = heightCm(result_world, ankle, f), target = heightCm(targets, target_ankle, f);
    ASSERT_LT(cleaned, kneel_cm - 5.0) << "frame " << f << ": the ankle held at the kneel's " << kneel_cm << " cm";
    ASSERT_NEAR(cleaned, target, 4.0) << "frame " << f << " of the kneel's contact " << kneel->first << "-" << kneel->last;
  }
}

// The other way round: a style that raises a planted heel (a run on the forefoot) through the content's
// heel contact, the foot pivoting on its toe. The lock keeps the heel still where the targets hold it
// rather than pulling it down to the content's height (it was pulled the 10 cm down, the targets'
// whole rise), and lies the foot's length from the toe's lock (the toe's place kept).
TEST(CleanupLockHeight, AHeelTheTargetsRaiseIsLockedRaised) {
  const Motion clip = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(clip.skeleton, clip.source);
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  const double cm = 2.54 / 0.45, rise_cm = 10.0;
  const Eigen::MatrixXd world = worldPositions(clip);
  const std::array<int, kContactCount> feet = contactJoints(mapping);
  const double floor = estimateFloorHeight(world, feet, up);
  const Eigen::MatrixXi contacts = detectContacts(world, feet, up, floor, clip.fps(), restPoseBodyHeight(clip.skeleton, up));
  const int heel = static_cast<int>(ContactLabel::LeftHeel), toe = static_cast<int>(ContactLabel::LeftToe);
  const int ankle = feet[static_cast<size_t>(heel)];
  const auto heightCm = [&](const Eigen::MatrixXd& positions, int column, int f) {
    return (up.dot(positions.block<1, 3>(f, 3 * column).transpose()) - floor) * cm;
  };
  // The longest heel contact on the floor (the ankle's median height under 10 cm) that the toe's overlaps.
  std::optional<ContactSegment> stance;
  for (const ContactSegment& segment : contactSegments(contacts, heel)) {
    std::vector<double> heights;
    bool toe_down = false;
    for (int f = segment.first; f <= segment.last; ++f) {
      heights.push_back(heightCm(world, ankle, f));
      toe_down = toe_down || contacts(f, toe) != 0;
    }
    std::sort(heights.begin(), heights.end());
    if (toe_down && heights[heights.size() / 2] < 10.0 && (!stance || segment.last - segment.first > stance->last - stance->first))
      stance = segment;
  }
  ASSERT_TRUE(stance.has_value() && stance->last - stance->first >= 10) << "a left heel contact of 10+ frames on the floor";
  // The targets: the clip, but over that contact the left ankle turned up about the toe until it is
  // rise_cm higher (the foot's length kept).
  Eigen::MatrixXd targets = test::canonicalPositions(world, mapping);
  const int target_ankle = index(CanonicalJoint::LeftAnkle), target_toe = index(CanonicalJoint::LeftToe);
  for (int f = stance->first; f <= stance->last; ++f) {
    const Eigen::Vector3d toe_at = targets.block<1, 3>(f, 3 * target_toe).transpose();
    const Eigen::Vector3d foot = targets.block<1, 3>(f, 3 * target_ankle).transpose() - toe_at;
    const Eigen::Vector3d back = (foot - up.dot(foot) * up).normalized();
    const double height = std::min(up.dot(foot) + rise_cm / cm, 0.95 * foot.norm());
    const Eigen::Vector3d raised = toe_at + back * std::sqrt(foot.squaredNorm() - height * height) + up * height;
    targets.block<1, 3>(f, 3 * target_ankle) = raised.transpose();
  }
  const Motion result = cleanupMotion(CleanupInput{clip, mapping, targets, contacts, up, floor, cm}, {}, nullptr);
  const Eigen::MatrixXd result_world = worldPositions(result);
  const Eigen::Vector3d first = result_world.block<1, 3>(stance->first, 3 * ankle).transpose();
  for (int f = stance->first; f <= stance->last; ++f) {
    const double cleaned = heightCm(result_world, ankle, f), target = heightCm(targets, target_ankle, f);
    EXPECT_NEAR(cleaned, target, 3.0) << "frame " << f << " of the heel's contact " << stance->first << "-" << stance->last
                                      << ": the content's ankle at " << heightCm(world, ankle, f) << " cm";
    Eigen::Vector3d moved = result_world.block<1, 3>(f, 3 * ankle).transpose() - first;
    moved -= up.dot(moved) * up;
    EXPECT_LT(moved.norm() * cm, 1.0) << "frame " << f << ": the raised heel slid";
  }
}

INSTANTIATE_TEST_SUITE_P(Fixtures, CleanupRealClip,
                         ::testing::Values(Fixture{"cmu_131_01.bvh", Eigen::Vector3d::UnitY(), 2.54 / 0.45},
                                           Fixture{"zombie.bvh", Eigen::Vector3d::UnitZ(), 2.54}),
                         [](const ::testing::TestParamInfo<Fixture>& param_info) {
                           const std::string file = param_info.param.file;
                           return file.substr(0, file.find('.'));
                         });

}  // namespace
}  // namespace motionstyle
