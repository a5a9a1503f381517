// The clean-up streamed in blocks (cleanupMotionInBlocks): a clip longer than two blocks arrives in
// order and whole, joins without a seam at the block boundaries, and windows that straddle a boundary
// solve as well as anywhere else. The metrics accumulator gives computeMetrics' figures exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "ik/cleanup.h"
#include "ik/metrics.h"
#include "ik_test_support.h"
#include "motion/kinematics.h"

namespace motionstyle {
namespace {

constexpr int kBlock = 128;                // small blocks: short clips cross several boundaries
constexpr int kFrames = 2 * kBlock + 40;  // two whole blocks and a partial one

class CleanupBlocks : public ::testing::Test {
 protected:
  Motion clip = test::makeHumanoidClip(kFrames, 60.0);
  JointMapping mapping = test::humanoidMapping(clip.skeleton);
  Eigen::MatrixXd world = worldPositions(clip);
  Eigen::MatrixXd targets = test::canonicalPositions(world, mapping);
  Eigen::MatrixXi no_contacts = Eigen::MatrixXi::Zero(kFrames, kContactCount);
  Eigen::MatrixXd damaged = test::damageTargets(targets, no_contacts, 60.0, 1.0, Eigen::Vector3d::UnitY(), {});

  CleanupInput input() const { return CleanupInput{clip, mapping, damaged, no_contacts, Eigen::Vector3d::UnitY(), -50.0, 1.0}; }
  static CleanupOptions inBlocks() {
    CleanupOptions options;
    options.block_frames = kBlock;
    return options;
  }

  // Largest frame-to-frame move of any joint over the frames f -> f + 1 for f in `frames`, cm.
  static double largestStep(const Eigen::MatrixXd& positions, const std::vector<int>& frames) {
    double largest = 0.0;
    for (int f : frames)
      for (Eigen::Index j = 0; j < positions.cols() / 3; ++j)
        largest = std::max(largest, (positions.block<1, 3>(f + 1, 3 * j) - positions.block<1, 3>(f, 3 * j)).norm());
    return largest;
  }
};

TEST_F(CleanupBlocks, BlocksArriveInOrderAndMakeUpTheWholeResult) {
  std::vector<int> firsts;
  MatrixRowMajor values(kFrames, clip.skeleton.channelCount());
  Eigen::MatrixXd block_world(kFrames, world.cols());
  CleanupReport report;
  cleanupMotionInBlocks(input(), inBlocks(), [&](const CleanedBlock& block) {
    ASSERT_EQ(block.first_frame, firsts.empty() ? 0 : firsts.back() + kBlock);
    ASSERT_LE(block.values.rows(), kBlock);
    ASSERT_EQ(block.world.rows(), block.values.rows());
    firsts.push_back(block.first_frame);
    values.middleRows(block.first_frame, block.values.rows()) = block.values;
    block_world.middleRows(block.first_frame, block.world.rows()) = block.world;
  }, &report);
  EXPECT_EQ(firsts, (std::vector<int>{0, kBlock, 2 * kBlock}));
  EXPECT_EQ(report.frames, kFrames);
  EXPECT_GE(report.solves, kFrames);  // every frame, plus the lead-ins of chunks after the first

  CleanupOptions one_block;
  one_block.block_frames = kFrames;
  const Motion whole = cleanupMotion(input(), one_block, nullptr);  // the block size changes nothing
  EXPECT_LT((whole.values - values).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((worldPositions(whole) - block_world).cwiseAbs().maxCoeff(), 1e-9);  // the world handed out is the result's
  Eigen::MatrixXd handed_out;
  const Motion with_world = cleanupMotion(input(), inBlocks(), nullptr, {}, &handed_out);  // as cleanUpStylizedClip asks
  EXPECT_EQ(with_world.values, values);
  EXPECT_EQ(handed_out, block_world);
}

TEST_F(CleanupBlocks, TheResultHasNoSeamAtBlockBoundaries) {
  const Motion result = cleanupMotion(input(), inBlocks(), nullptr);
  const Eigen::MatrixXd cleaned = worldPositions(result);
  std::vector<int> boundaries = {kBlock - 1, 2 * kBlock - 1};
  std::vector<int> elsewhere;
  for (int f = 1; f + 1 < kFrames; ++f)
    if (std::find(boundaries.begin(), boundaries.end(), f) == boundaries.end()) elsewhere.push_back(f);
  EXPECT_LE(largestStep(cleaned, boundaries), largestStep(cleaned, elsewhere));
  // Euler angles continue across the boundary too (no 360-degree branch jumps).
  for (int f : boundaries)
    EXPECT_LT((result.values.row(f + 1) - result.values.row(f)).cwiseAbs().maxCoeff(), 30.0) << "frame " << f;
}

TEST(CleanupBlocksWindowed, WindowsThatStraddleABoundarySolveAsWellAsElsewhere) {
  const int frames = kBlock + 40;
  const Motion clip = test::makeHumanoidClip(frames, 60.0);
  const JointMapping mapping = test::humanoidMapping(clip.skeleton);
  const Eigen::MatrixXi no_contacts = Eigen::MatrixXi::Zero(frames, kContactCount);
  const Eigen::MatrixXd damaged = test::damageTargets(test::canonicalPositions(worldPositions(clip), mapping), no_contacts,
                                                      60.0, 1.0, Eigen::Vector3d::UnitY(), {});
  const CleanupInput input{clip, mapping, damaged, no_contacts, Eigen::Vector3d::UnitY(), -50.0, 1.0};
  CleanupOptions windowed;
  windowed.block_frames = kBlock;
  windowed.solver = CleanupSolver::Ceres;
  windowed.window_frames = 3;
  windowed.window_overlap = 1;  // windows start at even frames: the one at 126 spans the boundary
  CleanupReport report;
  CleanupOptions per_frame_options;
  per_frame_options.block_frames = kBlock;
  const Eigen::MatrixXd per_frame = worldPositions(cleanupMotion(input, per_frame_options, nullptr));
  const Eigen::MatrixXd by_window = worldPositions(cleanupMotion(input, windowed, &report));
  EXPECT_EQ(report.frames_unsolved, 0);
  EXPECT_EQ(report.solves, frames / 2);  // starts 0, 2, ..., frames - 4, then the last window ends at the clip's end
  auto worstDistance = [&](int first, int last) {
    double worst = 0.0;
    for (int f = first; f <= last; ++f)
      for (Eigen::Index j = 0; j < per_frame.cols() / 3; ++j)
        worst = std::max(worst, (per_frame.block<1, 3>(f, 3 * j) - by_window.block<1, 3>(f, 3 * j)).norm());
    return worst;
  };
  EXPECT_LT(worstDistance(kBlock - 8, kBlock + 8), 1.0);
  EXPECT_LE(worstDistance(kBlock - 8, kBlock + 8), 2.0 * worstDistance(0, frames - 1));
}

// --- The metrics accumulator.

MetricsInput metricsOf(const Eigen::MatrixXd& positions, const JointMapping& mapping, const Skeleton& skeleton) {
  MetricsInput input(positions, mapping.joints, skeletonBones(skeleton));
  input.floor_height = 3.0;  // above the toes (2 cm): some samples penetrate
  return input;
}

TEST_F(CleanupBlocks, MetricsAccumulatorRefusesBlocksThatDoNotMatch) {
  const Eigen::MatrixXd head = world.topRows(10);
  MetricsInput first = metricsOf(head, mapping, clip.skeleton);
  first.contacts = no_contacts.topRows(10);
  MetricsAccumulator accumulator;
  accumulator.add(first);
  MetricsInput other_rate = first;
  other_rate.fps = 30.0;
  EXPECT_THROW(accumulator.add(other_rate), std::invalid_argument);
  MetricsInput no_labels = metricsOf(head, mapping, clip.skeleton);
  EXPECT_THROW(accumulator.add(no_labels), std::invalid_argument);
  MetricsInput bad = first;
  bad.contacts = no_contacts.topRows(9);
  EXPECT_THROW(accumulator.add(bad), std::invalid_argument);
}

TEST_F(CleanupBlocks, MetricsInBlocksEqualMetricsOfTheWhole) {
  const int frames = 200;
  const Eigen::MatrixXd positions = world.topRows(frames);
  Eigen::MatrixXi contacts = Eigen::MatrixXi::Zero(frames, kContactCount);
  for (int f = 0; f < frames; ++f)
    for (int label = 0; label < kContactCount; ++label) contacts(f, label) = ((f / 13 + label) % 3) == 0 ? 1 : 0;
  MetricsInput whole = metricsOf(positions, mapping, clip.skeleton);
  whole.contacts = contacts;
  whole.targets = damaged.topRows(frames);
  const ClipMetrics expected = computeMetrics(whole);
  ASSERT_GT(expected.contact_steps, 0);
  for (int block_frames : {1, 2, 7, 64, frames}) {
    MetricsAccumulator accumulator;
    for (int first = 0; first < frames; first += block_frames) {
      const int count = std::min(block_frames, frames - first);
      const Eigen::MatrixXd rows = positions.middleRows(first, count);
      MetricsInput block = metricsOf(rows, mapping, clip.skeleton);
      block.contacts = contacts.middleRows(first, count);
      block.targets = damaged.middleRows(first, count);
      accumulator.add(block);
    }
    const ClipMetrics got = accumulator.finish();
    SCOPED_TRACE("blocks of " + std::to_string(block_frames));
    EXPECT_EQ(got.frames, expected.frames);
    EXPECT_EQ(got.contact_steps, expected.contact_steps);
    EXPECT_EQ(got.foot_skate_cm_s, expected.foot_skate_cm_s);
    EXPECT_EQ(got.penetration_max_cm, expected.penetration_max_cm);
    EXPECT_EQ(got.penetration_mean_cm, expected.penetration_mean_cm);
    EXPECT_EQ(got.bone_error_mean_cm, expected.bone_error_mean_cm);
    EXPECT_EQ(got.bone_error_max_cm, expected.bone_error_max_cm);
    EXPECT_EQ(got.residual_mean_cm, expected.residual_mean_cm);
    EXPECT_EQ(got.residual_max_cm, expected.residual_max_cm);
    EXPECT_EQ(got.residual_max_frame, expected.residual_max_frame);
    EXPECT_EQ(got.residual_max_joint, expected.residual_max_joint);
    EXPECT_EQ(got.jerk_mean_cm_s3, expected.jerk_mean_cm_s3);
    EXPECT_EQ(got.skate_track_cm_s, expected.skate_track_cm_s);
    EXPECT_EQ(got.bone_error_track_cm, expected.bone_error_track_cm);
  }
}

}  // namespace
}  // namespace motionstyle
