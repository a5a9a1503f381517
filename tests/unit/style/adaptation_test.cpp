// Adapting the loss network to a user's clips (style/adaptation.h), retraining a style from the targets
// its network stores (training.h, style_pairing.h) and training on augmented clips: invalid input
// first, then properties.
#include <gtest/gtest.h>

#include "common/errors.h"
#include "style/adaptation.h"
#include "style/style_pairing.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

using test::TempDir;

style::AdaptationJob tinyJob(const TempDir& dir) {
  style::AdaptationJob job;
  job.loss_network = test::tinyLossNetworkModel();
  job.loss_network_name = "tiny.net";
  job.clips = {test::fixtureClips()[1]};  // the zombie
  job.settings.epochs = 6;
  job.settings.learning_rate = 3e-3;
  job.settings.output = dir / "adapted.net";
  return job;
}

TEST(AdaptationTest, RejectsBadSettingsAndMissingClips) {
  TempDir dir;
  style::AdaptationJob job = tinyJob(dir);
  job.clips.clear();
  EXPECT_THROW(job.validate(), std::invalid_argument);
  job = tinyJob(dir);
  job.settings.epochs = 0;
  EXPECT_THROW(job.validate(), std::invalid_argument);
  job = tinyJob(dir);
  job.settings.learning_rate = -1;
  EXPECT_THROW(job.validate(), std::invalid_argument);
  job = tinyJob(dir);
  job.settings.replay_ratio = NAN;
  EXPECT_THROW(job.validate(), std::invalid_argument);
  job = tinyJob(dir);
  job.settings.output.clear();
  EXPECT_THROW(job.validate(), std::invalid_argument);
  job = tinyJob(dir);
  job.clips[0].features.values(0, 0) = NAN;
  EXPECT_THROW(job.validate(), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "adapted.net"));
}

TEST(AdaptationTest, KeepsTheEncoderLearnsTheClipsAndRecordsThem) {
  TempDir dir;
  const style::AdaptationJob job = tinyJob(dir);
  const style::AdaptationResult result = job.run();
  ASSERT_EQ(result.status, style::TrainingStatus::Completed);
  EXPECT_EQ(result.model.network.encoder.weight.value, job.loss_network.network.encoder.weight.value);
  EXPECT_EQ(result.model.network.encoder.bias.value, job.loss_network.network.encoder.bias.value);
  EXPECT_NE(result.model.network.decoder.weight.value, job.loss_network.network.decoder.weight.value);
  ASSERT_EQ(result.clips.size(), 1u);
  EXPECT_LT(result.mean_after_cm, result.mean_before_cm);
  const nn::LossNetworkModel saved = style::loadCompatibleLossNetwork(dir / "adapted.net");
  std::map<std::string, std::string> properties(saved.metadata.properties.begin(), saved.metadata.properties.end());
  EXPECT_EQ(properties["adapted_from"], "tiny.net");
  EXPECT_EQ(properties["adapted_on"], "zombie.bvh");
  EXPECT_EQ(properties["adapted_clips"], "1");
  EXPECT_EQ(properties["adapted_frames"], std::to_string(test::fixtureClips()[1].frameCount()));
  EXPECT_EQ(properties["adapted_encoder"], "kept");
  EXPECT_FALSE(properties["adapted_date"].empty());

  // Replay clips are mixed in; with the encoder trained too, it changes.
  style::AdaptationJob both = tinyJob(dir);
  both.replay = {test::fixtureClips()[0]};
  both.settings.train_encoder = true;
  both.settings.output = dir / "both.net";
  const style::AdaptationResult trained = both.run();
  EXPECT_EQ(trained.replay_clips, 1);
  EXPECT_NE(trained.model.network.encoder.weight.value, job.loss_network.network.encoder.weight.value);
}

TEST(AdaptationTest, CancellationKeepsTheCheckpointAndWritesNothing) {
  TempDir dir;
  const style::AdaptationJob job = tinyJob(dir);
  const style::AdaptationResult result = job.run(test::cancelAtEndOfEpoch(2));
  EXPECT_EQ(result.status, style::TrainingStatus::Cancelled);
  EXPECT_FALSE(std::filesystem::exists(dir / "adapted.net"));
  EXPECT_FALSE(std::filesystem::exists(dir / "adapted.memory"));
  EXPECT_TRUE(std::filesystem::exists(dir / "adapted.net.checkpoint"));
}

TEST(StylePairingTest, StoredTargetsPairByLabelThenTheDefault) {
  EXPECT_EQ(style::pairTargets({"walk", "run", "jump"}, {"walk", "run", ""}, "n"), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(style::pairTargets({"", "walk"}, {"", "walk"}, "n"), (std::vector<int>{0, 1}));
  EXPECT_THROW(style::pairTargets({"walk", "jump"}, {"walk"}, "n"), InputError);
}

style::StyleTrainingConfig styleConfig(const TempDir& dir, const std::filesystem::path& loss_network, int epochs) {
  style::StyleTrainingConfig config;
  config.settings = test::tinySettings(dir / "style.net", epochs);
  config.settings.learning_rate = 1e-3;
  config.loss_network = loss_network;
  config.content_clips = test::fixtureClips();
  config.styles = {{std::nullopt, test::fixture("zombie.bvh")}};
  config.shape = test::tinyTransformationShape();
  config.weights.style = 1.0;
  return config;
}

TEST(StyleTargetsTest, ANetworkRetrainsFromItsStoredTargetsAgainstAnAdaptedLossNetwork) {
  TempDir dir;
  nn::saveLossNetwork(test::tinyLossNetworkModel(), dir / "ae.net");
  const auto original = style::trainStyleNetwork(styleConfig(dir, dir / "ae.net", 2));
  ASSERT_EQ(original.model.style_targets.size(), 2u);  // the clip's own label "zombie", and the default
  const nn::StyleModel saved = style::loadCompatibleStyleModel(dir / "style.net");
  ASSERT_EQ(saved.style_targets.size(), 2u);
  EXPECT_EQ(saved.style_targets[0].label, "zombie");
  EXPECT_EQ(saved.style_targets[1].label, "");

  // A loss network with another encoder cannot use those targets.
  nn::saveLossNetwork(test::tinyLossNetworkModel(11), dir / "other.net");
  style::StyleTrainingConfig wrong = styleConfig(dir, dir / "other.net", 1);
  wrong.styles.clear();
  wrong.settings.init = dir / "style.net";
  wrong.settings.output = dir / "wrong.net";
  EXPECT_THROW(style::trainStyleNetwork(wrong), InputError);

  // The adapted loss network keeps the encoder: the stored targets train the network on new content.
  style::AdaptationJob adapt = tinyJob(dir);
  adapt.settings.epochs = 2;
  ASSERT_EQ(adapt.run().status, style::TrainingStatus::Completed);
  style::StyleTrainingConfig retrain = styleConfig(dir, dir / "adapted.net", 2);
  retrain.styles.clear();
  retrain.settings.init = dir / "style.net";
  retrain.settings.output = dir / "retrained.net";
  const auto retrained = style::trainStyleNetwork(retrain);
  ASSERT_EQ(retrained.status, style::TrainingStatus::Completed);
  EXPECT_EQ(retrained.pairing, (std::vector<int>{1, 0}));  // "cmu" -> the default, "zombie" -> its own
  const nn::StyleModel loaded = style::loadCompatibleStyleModel(dir / "retrained.net");
  EXPECT_EQ(loaded.style_targets, saved.style_targets);
  EXPECT_EQ(loaded.metadata.style_clips, saved.metadata.style_clips);
  EXPECT_EQ(loaded.loss_network.decoder.weight.value, style::loadCompatibleLossNetwork(dir / "adapted.net").network.decoder.weight.value);
}

TEST(AugmentedTrainingTest, IsDeterministicAndResumable) {
  TempDir dir;
  style::DatasetOptions keep;
  keep.keep_motion = true;
  auto config = test::tinyLossNetworkConfig(dir / "ae.net", 3);
  config.clips = {style::loadMotionClip(test::fixture("cmu_131_01.bvh"), keep),
                  style::loadMotionClip(test::fixture("zombie.bvh"), keep)};
  config.settings.augmentation = style::defaultAugmentation();
  const auto first = style::trainLossNetwork(config);
  config.settings.output = dir / "split.net";
  ASSERT_EQ(style::trainLossNetwork(config, test::cancelAtEndOfEpoch(1)).status, style::TrainingStatus::Cancelled);
  config.settings.resume = true;
  const auto resumed = style::trainLossNetwork(config);
  EXPECT_EQ(test::weightsOf(first.model.network), test::weightsOf(resumed.model.network));
  // And it differs from training on the clips as they are.
  auto plain = test::tinyLossNetworkConfig(dir / "plain.net", 3);
  EXPECT_NE(test::weightsOf(style::trainLossNetwork(plain).model.network), test::weightsOf(first.model.network));
  std::map<std::string, std::string> properties(first.model.metadata.properties.begin(), first.model.metadata.properties.end());
  EXPECT_EQ(properties["augmentation"], style::describe(style::defaultAugmentation()));
}

}  // namespace
}  // namespace motionstyle
