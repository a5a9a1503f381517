// On a few licensed Bandai clips (label "data"): labels of the real file names, pairing of walk and run
// content with the walk and run clips of one style, and a very small loss network and style network
// trained for a couple of epochs, evaluated on a held-out clip.
#include <gtest/gtest.h>

#include "style/evaluation.h"
#include "style/stylizer.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

std::filesystem::path bandaiClip(const std::filesystem::path& root, const std::string& name) {
  return root / "dataset-2" / "data" / name;
}

TEST(StyleData, SmallNetworksTrainOnBandaiClipsAndEvaluate) {
  MOTIONSTYLE_REQUIRE_BANDAI(bandai);
  test::TempDir dir;
  const std::vector<std::filesystem::path> content_files = {
      bandaiClip(bandai, "dataset-2_walk_normal_001.bvh"), bandaiClip(bandai, "dataset-2_walk_normal_002.bvh"),
      bandaiClip(bandai, "dataset-2_run_normal_001.bvh"), bandaiClip(bandai, "dataset-2_run_normal_002.bvh"),
      bandaiClip(bandai, "dataset-2_walk_normal_003.bvh")};
  for (const auto& file : content_files) ASSERT_TRUE(std::filesystem::exists(file)) << file;

  // Loss network: 64 hidden units, the paper's width 25, 2 epochs; the 5th clip is held out.
  style::LossNetworkTrainingConfig loss_network_config;
  loss_network_config.settings = test::tinySettings(dir / "ae.net", 2);
  loss_network_config.settings.windows = {};  // 240 / 120
  loss_network_config.settings.holdout_every = 5;
  loss_network_config.data = content_files;
  loss_network_config.shape = {kFeatureCount, 64, 25};
  const auto loss_network = style::trainLossNetwork(loss_network_config);
  ASSERT_EQ(loss_network.status, style::TrainingStatus::Completed);
  ASSERT_EQ(loss_network.held_out_files.size(), 1u);
  EXPECT_LT(loss_network.history.back().total, loss_network.history.front().total);

  // Style network: walk content with the elderly walk, run content with the elderly run.
  style::StyleTrainingConfig config;
  config.settings = test::tinySettings(dir / "elderly.net", 2);
  config.settings.windows = {};
  config.settings.holdout_every = 5;
  config.settings.learning_rate = 1e-3;
  config.loss_network = dir / "ae.net";
  config.content = content_files;
  config.styles = {{std::nullopt, bandaiClip(bandai, "dataset-2_walk_elderly_001.bvh")},
                   {std::nullopt, bandaiClip(bandai, "dataset-2_run_elderly_001.bvh")}};
  config.shape = {kFeatureCount, 32, 25, true};
  const auto style_result = style::trainStyleNetwork(config);
  ASSERT_EQ(style_result.status, style::TrainingStatus::Completed);
  EXPECT_EQ(style_result.pairing, (std::vector<int>{0, 0, 1, 1}));
  EXPECT_LT(style_result.history.back().total, style_result.history.front().total);

  const auto held_out = style::loadMotionClip(loss_network.held_out_files[0]);
  EXPECT_EQ(held_out.labels, (style::ClipLabels{"walk", "normal"}));
  const auto style_clip = style::loadMotionClip(config.styles[0].file);
  const auto report = style::evaluateStyleNetwork(loss_network.model, style_result.model, {held_out}, {style_clip}, {0});
  ASSERT_EQ(report.clips.size(), 1u);
  EXPECT_TRUE(report.loss_network_matches_network);
  EXPECT_EQ(report.clips[0].frames, held_out.frameCount());
  EXPECT_TRUE(std::isfinite(report.clips[0].style_distance_after));
  RecordProperty("reconstruction_joint_error_cm", std::to_string(report.clips[0].reconstruction_joint_error_cm));
  RecordProperty("style_ratio", std::to_string(report.clips[0].style_distance_after / report.clips[0].style_distance_before));
}

}  // namespace
}  // namespace motionstyle
