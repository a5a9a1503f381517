// Properties of the data side: labels from file names, file discovery, windows and padding, pairing,
// hold-out split and the positions-only output clip.
#include <gtest/gtest.h>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "features/feature_layout.h"
#include "mapping/canonical_joints.h"
#include "motion/kinematics.h"
#include "style/clip_labels.h"
#include "style/position_clip.h"
#include "style/style_pairing.h"
#include "style/training_windows.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

using style::ClipLabels;
using style::parseClipLabels;

TEST(ClipLabels, BandaiNamesGiveContentAndStyle) {
  EXPECT_EQ(parseClipLabels("x/dataset-2_walk-turn-left_elderly_012.bvh"), (ClipLabels{"walk-turn-left", "elderly"}));
  EXPECT_EQ(parseClipLabels("dataset-1_walk_old_001.bvh"), (ClipLabels{"walk", "old"}));
  EXPECT_EQ(parseClipLabels("dataset-1_walk_not-confident_003.bvh"), (ClipLabels{"walk", "not-confident"}));
  EXPECT_EQ(parseClipLabels("DATASET-1_Run_Angry_001.BVH"), (ClipLabels{"run", "angry"}));
}

TEST(ClipLabels, OtherNamesGiveTheFirstAlphabeticWord) {
  EXPECT_EQ(parseClipLabels("walk_fast.bvh"), (ClipLabels{"walk", ""}));
  EXPECT_EQ(parseClipLabels("cmu_131_01.bvh"), (ClipLabels{"cmu", ""}));
  EXPECT_EQ(parseClipLabels("07-Zombie-Run2.bvh"), (ClipLabels{"zombie", ""}));
  EXPECT_EQ(parseClipLabels("131_01.bvh"), (ClipLabels{"", ""}));
  // Not quite Bandai (no take number): generic rule.
  EXPECT_EQ(parseClipLabels("dataset-1_walk_old.bvh"), (ClipLabels{"dataset", ""}));
}

TEST(FindBvhFiles, FoldersAreSearchedRecursivelyAndSorted) {
  test::TempDir dir;
  for (const char* name : {"b/z.bvh", "a.BVH", "b/a/y.bvh", "c.txt"}) test::writeText(dir / name, "x");
  const auto files = style::findBvhFiles({dir.path(), dir / "a.BVH"});
  ASSERT_EQ(files.size(), 4u);
  EXPECT_EQ(files[0], dir / "a.BVH");
  EXPECT_EQ(files[1], dir / "b/a/y.bvh");
  EXPECT_EQ(files[2], dir / "b/z.bvh");
  EXPECT_EQ(files[3], dir / "a.BVH");  // a file named explicitly keeps its place
}

TEST(FindBvhFiles, ASkippedFolderBelowAnInputIsNotSearched) {
  test::TempDir dir;
  for (const char* name : {"shots/a.bvh", "shots/out/a.bvh", "shots/out/deep/b.bvh", "shots/outtakes/c.bvh"})
    test::writeText(dir / name, "x");
  // Reached through "..": compared once resolved.
  const auto files = style::findBvhFiles({dir / "shots"}, {dir / "shots/outtakes/../out"});
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0], dir / "shots/a.bvh");
  EXPECT_EQ(files[1], dir / "shots/outtakes/c.bvh");  // a name that merely starts like it is searched
  // The input folder itself is never skipped: its clips are what was asked for.
  EXPECT_EQ(style::findBvhFiles({dir / "shots/out"}, {dir / "shots/out"}).size(), 2u);
}

TEST(Windows, SpansFollowThe2016Rule) {
  const style::WindowOptions options;  // 240 / 120
  using Span = style::WindowSpan;
  EXPECT_EQ(style::windowSpans(100, options), (std::vector<Span>{{0, 100}}));
  EXPECT_EQ(style::windowSpans(10, options), (std::vector<Span>{{0, 10}}));
  EXPECT_EQ(style::windowSpans(240, options), (std::vector<Span>{{0, 240}, {120, 120}}));
  EXPECT_EQ(style::windowSpans(360, options), (std::vector<Span>{{0, 240}, {120, 240}, {240, 120}}));
  // 1000 frames: starts below 1000 - 30 = 970: 0, 120, ..., 960.
  const auto spans = style::windowSpans(1000, options);
  ASSERT_EQ(spans.size(), 9u);
  EXPECT_EQ(spans.back(), (Span{960, 40}));
  // A start must lie below frames - window/8: 270 frames -> starts 0, 120 (240 is not below 240);
  // 271 frames -> a third window of 31 frames, padded.
  EXPECT_EQ(style::windowSpans(270, options).size(), 2u);
  EXPECT_EQ(style::windowSpans(271, options).size(), 3u);
}

TEST(Windows, ShortSlicesArePaddedWithFirstAndLastFramesAtZeroVelocity) {
  Eigen::MatrixXd values(kFeatureCount, 5);
  for (int f = 0; f < 5; ++f) values.col(f).setConstant(f + 1.0);
  const Eigen::MatrixXd window = style::cutWindow(values, {1, 3}, 8, true);  // frames 1..3, 5 padded
  ASSERT_EQ(window.cols(), 8);
  // 3 before (half of 5, rounded up), 2 after.
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(window(0, i), 2.0);
    EXPECT_EQ(window.col(i).segment<3>(kSidewaysVelocity), Eigen::Vector3d::Zero());
  }
  for (int i = 3; i < 6; ++i) EXPECT_EQ(window.col(i), values.col(i - 2));
  for (int i = 6; i < 8; ++i) {
    EXPECT_EQ(window(62, i), 4.0);
    EXPECT_EQ(window.col(i).segment<3>(kSidewaysVelocity), Eigen::Vector3d::Zero());
  }
  // Contacts keep their values on padded frames.
  Eigen::MatrixXd contacts = Eigen::MatrixXd::Ones(kContactCount, 5);
  EXPECT_EQ(style::cutWindow(contacts, {1, 3}, 8, false), Eigen::MatrixXd::Ones(kContactCount, 8));
}

TEST(Windows, WindowSetCountsAndNormalisesTheClips) {
  const auto& clips = test::fixtureClips();
  const nn::LossNetworkModel model = test::tinyLossNetworkModel();
  const FeatureStatistics& statistics = model.normalisation;
  const style::WindowSet set = style::makeWindows(clips, statistics, {60, 30});
  std::size_t expected = 0;
  for (const auto& clip : clips) expected += style::windowSpans(clip.frameCount(), {60, 30}).size();
  ASSERT_EQ(static_cast<std::size_t>(set.count()), expected);
  EXPECT_EQ(set.values.cols(), set.count() * 60);
  EXPECT_EQ(set.contacts.cols(), set.count() * 60);
  EXPECT_EQ(set.bone_lengths.cols(), set.count());
  // Window 1 of clip 0 starts at frame 30: its first column is that frame, normalised.
  Eigen::MatrixXd frame = clips[0].features.values.col(30);
  statistics.normalize(frame);
  EXPECT_TRUE(set.values.col(60).cast<double>().isApprox(frame, 1e-5));
  EXPECT_EQ(set.clip_index.front(), 0);
  EXPECT_EQ(set.clip_index.back(), 1);
}

TEST(Pairing, StyleClipsPairByTheirOwnLabelExplicitLabelsAndTheDefault) {
  const std::vector<style::StyleSource> styles = {
      style::parseStyleSource("dataset-1_walk_old_001.bvh"),
      style::parseStyleSource("run=old_running.bvh"),
      style::parseStyleSource("dataset-1_dash_old_001.bvh"),
  };
  EXPECT_FALSE(styles[0].label.has_value());
  EXPECT_EQ(*styles[1].label, "run");
  EXPECT_EQ(styles[1].file, "old_running.bvh");
  // walk -> its own label, run -> explicit, dash -> own label, jump -> default (the first plain clip).
  EXPECT_EQ(style::pairStyles({"walk", "run", "dash", "jump", "walk"}, styles), (std::vector<int>{0, 1, 2, 0, 0}));
  // A path with '=' that is not a label stays a path.
  EXPECT_FALSE(style::parseStyleSource("/tmp/a=b/c.bvh").label.has_value());
  // An explicit label wins over a clip's file-name label.
  const std::vector<style::StyleSource> override_walk = {style::parseStyleSource("dataset-1_walk_old_001.bvh"),
                                                         style::parseStyleSource("walk=special.bvh")};
  EXPECT_EQ(style::pairStyles({"walk"}, override_walk), (std::vector<int>{1}));
}

TEST(Holdout, EveryNthFileIsHeldOut) {
  const std::vector<std::filesystem::path> files = {"a", "b", "c", "d", "e", "f", "g"};
  const style::HoldoutSplit split = style::splitHoldout(files, 3);
  EXPECT_EQ(split.held_out, (std::vector<std::filesystem::path>{"c", "f"}));
  EXPECT_EQ(split.training.size(), 5u);
  EXPECT_EQ(style::splitHoldout(files, 0).training.size(), 7u);
}

TEST(PositionClip, BvhRoundTripReproducesTheWorldPositions) {
  const auto& clip = test::fixtureClips()[1];
  const Eigen::MatrixXd world = canonicalWorldPositions(clip.features.values, clip.features.anchor);
  const Motion motion = style::canonicalPositionsMotion(world, 60.0, "out.bvh");
  test::TempDir dir;
  writeBvh(motion, dir / "out.bvh");
  const Motion back = readBvh(dir / "out.bvh");
  ASSERT_EQ(back.frameCount(), world.rows());
  const Eigen::MatrixXd positions = worldPositions(back);
  for (int c = 0; c < kCanonicalJointCount; ++c) {
    const int joint = back.skeleton.find(std::string(canonicalJointName(static_cast<CanonicalJoint>(c))));
    ASSERT_GE(joint, 0);
    EXPECT_LT((positions.middleCols<3>(3 * joint) - world.middleCols<3>(3 * c)).cwiseAbs().maxCoeff(), 1e-9);
  }
}

}  // namespace
}  // namespace motionstyle
