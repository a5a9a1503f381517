// Properties of the training API on the committed fixtures with tiny networks: the loss goes down,
// runs are deterministic, cancellation is prompt, resume reproduces uninterrupted training, divergence
// stops with an error and keeps the last good checkpoint.
#include <gtest/gtest.h>

#include <cmath>

#include <atomic>
#include <chrono>
#include <thread>

#include "common/errors.h"
#include "nn/adam.h"
#include "nn/init.h"
#include "style/training_state.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

// The bound is 1 s, checked in the optimised build. AddressSanitizer slows every step several
// times over, so the sanitizer pass (tests/run_all.sh) checks only that cancellation is prompt.
#if defined(__SANITIZE_ADDRESS__)
constexpr double kCancelBoundSeconds = 5.0;
#else
constexpr double kCancelBoundSeconds = 1.0;
#endif

using test::TempDir;

TEST(LearningRateSchedule, CosineWarmsUpThenDecaysToOnePercentAndConstantStays) {
  using style::LearningRateSchedule;
  using style::scheduledLearningRate;
  // 100 steps: the half cosine, scaled by a warm-up over the first 10 (a tenth of the run).
  const auto cosine = [](double step, double total) {
    return 1e-3 * (0.01 + 0.99 * 0.5 * (1.0 + std::cos(3.14159265358979323846 * step / (total - 1))));
  };
  EXPECT_DOUBLE_EQ(scheduledLearningRate(LearningRateSchedule::Cosine, 1e-3, 0, 100), 1e-4);
  EXPECT_NEAR(scheduledLearningRate(LearningRateSchedule::Cosine, 1e-3, 4, 100), 0.5 * cosine(4, 100), 1e-15);
  EXPECT_NEAR(scheduledLearningRate(LearningRateSchedule::Cosine, 1e-3, 9, 100), cosine(9, 100), 1e-15);
  EXPECT_DOUBLE_EQ(scheduledLearningRate(LearningRateSchedule::Cosine, 1e-3, 99, 100), 1e-5);
  EXPECT_NEAR(scheduledLearningRate(LearningRateSchedule::Cosine, 1e-3, 99, 199), 0.505e-3, 1e-12);  // halfway
  // Long runs warm up over kWarmupSteps.
  EXPECT_NEAR(scheduledLearningRate(LearningRateSchedule::Cosine, 1.0, style::kWarmupSteps / 2 - 1, 100000), 0.5, 1e-4);
  EXPECT_NEAR(scheduledLearningRate(LearningRateSchedule::Cosine, 1.0, style::kWarmupSteps, 100000), 1.0, 1e-4);
  double previous = 0.0;
  for (long step = 0; step < 5; ++step) {  // warm-up of 5 in a run of 50
    const double rate = scheduledLearningRate(LearningRateSchedule::Cosine, 1.0, step, 50);
    EXPECT_GT(rate, previous);
    previous = rate;
  }
  for (long step = 5; step < 50; ++step) {
    const double rate = scheduledLearningRate(LearningRateSchedule::Cosine, 1.0, step, 50);
    EXPECT_LT(rate, previous + 1e-15);
    previous = rate;
  }
  EXPECT_DOUBLE_EQ(scheduledLearningRate(LearningRateSchedule::Cosine, 2e-3, 0, 1), 2e-3);  // a one-step run
  for (long step : {0L, 10L, 99L})
    EXPECT_DOUBLE_EQ(scheduledLearningRate(LearningRateSchedule::Constant, 1e-3, step, 100), 1e-3);
}

TEST(TrainLossNetwork, LossDecreasesAndTheOutputLoads) {
  TempDir dir;
  std::vector<style::TrainingProgress> calls;
  style::TrainingCallbacks callbacks;
  callbacks.progress = [&](const style::TrainingProgress& p) { calls.push_back(p); };
  const auto result = style::trainLossNetwork(test::tinyLossNetworkConfig(dir / "ae.net", 4), callbacks);
  ASSERT_EQ(result.status, style::TrainingStatus::Completed);
  ASSERT_EQ(result.history.size(), 4u);
  EXPECT_LT(result.history.back().total, 0.8 * result.history.front().total);
  ASSERT_EQ(result.history.front().terms.size(), 2u);
  EXPECT_EQ(result.history.front().terms[0].name, "mse");

  const nn::LossNetworkModel loaded = style::loadCompatibleLossNetwork(dir / "ae.net");
  EXPECT_EQ(loaded.network.encoder.weight.value, result.model.network.encoder.weight.value);
  EXPECT_EQ(loaded.metadata.loss_history.epochs.size(), 4u);
  EXPECT_EQ(loaded.metadata.training.epochs, 4);

  // Progress: one call per step and one per epoch end, in order, with a finite ETA after the first step.
  int epoch_ends = 0, steps = 0;
  for (const auto& p : calls) {
    if (p.phase == style::TrainingProgress::Phase::EpochEnd) ++epoch_ends;
    if (p.phase == style::TrainingProgress::Phase::Training) {
      ++steps;
      EXPECT_GE(p.eta_seconds, 0.0);
      EXPECT_GE(p.step, 1);
      EXPECT_LE(p.step, p.steps_per_epoch);
    }
  }
  EXPECT_EQ(epoch_ends, 4);
  EXPECT_EQ(steps, 4 * calls.back().steps_per_epoch);
}

TEST(TrainLossNetwork, TheScheduleIsAppliedAndRecorded) {
  TempDir dir;
  style::LossNetworkTrainingConfig cosine = test::tinyLossNetworkConfig(dir / "cosine.net", 2);
  style::LossNetworkTrainingConfig constant = test::tinyLossNetworkConfig(dir / "constant.net", 2);
  constant.settings.schedule = style::LearningRateSchedule::Constant;
  const auto a = style::trainLossNetwork(cosine, {});
  const auto b = style::trainLossNetwork(constant, {});
  EXPECT_NE(a.model.network.encoder.weight.value, b.model.network.encoder.weight.value);
  auto property = [](const nn::NetworkMetadata& m, const std::string& key) {
    for (const auto& [k, v] : m.properties)
      if (k == key) return v;
    return std::string("(missing)");
  };
  EXPECT_EQ(property(style::loadCompatibleLossNetwork(dir / "cosine.net").metadata, "lr_schedule"), "cosine");
  EXPECT_EQ(property(style::loadCompatibleLossNetwork(dir / "constant.net").metadata, "lr_schedule"), "constant");
}

TEST(TrainLossNetwork, SameSeedGivesIdenticalWeightsAndAnotherSeedDoesNot) {
  TempDir dir;
  auto config = test::tinyLossNetworkConfig(dir / "a.net", 2);
  auto first = style::trainLossNetwork(config);
  config.settings.output = dir / "b.net";
  auto second = style::trainLossNetwork(config);
  EXPECT_EQ(test::weightsOf(first.model.network), test::weightsOf(second.model.network));
  config.settings.seed = 8;
  config.settings.output = dir / "c.net";
  auto third = style::trainLossNetwork(config);
  EXPECT_NE(test::weightsOf(first.model.network), test::weightsOf(third.model.network));
}

TEST(TrainLossNetwork, ResumeAfterAnEpochOrACancelledStepEqualsUninterruptedTraining) {
  TempDir dir;
  auto config = test::tinyLossNetworkConfig(dir / "straight.net", 3);
  const auto straight = style::trainLossNetwork(config);

  // Stopped at an epoch boundary (cancelled as epoch 1 ends: the run keeps its 3-epoch schedule),
  // resumed.
  config.settings.output = dir / "split.net";
  ASSERT_EQ(style::trainLossNetwork(config, test::cancelAtEndOfEpoch(1)).status, style::TrainingStatus::Cancelled);
  config.settings.resume = true;
  const auto resumed = style::trainLossNetwork(config);
  EXPECT_EQ(test::weightsOf(straight.model.network), test::weightsOf(resumed.model.network));
  EXPECT_EQ(resumed.history.size(), 3u);
  EXPECT_EQ(resumed.history[0].total, straight.history[0].total);

  // Cancelled in the middle of epoch 2 (deterministically, from the progress callback), then resumed.
  config.settings.output = dir / "cancelled.net";
  config.settings.resume = false;
  std::atomic<bool> cancel{false};
  style::TrainingCallbacks callbacks;
  callbacks.cancel = &cancel;
  callbacks.progress = [&](const style::TrainingProgress& p) {
    if (p.phase == style::TrainingProgress::Phase::Training && p.epoch == 2 && p.step == 2) cancel = true;
  };
  const auto cancelled = style::trainLossNetwork(config, callbacks);
  EXPECT_EQ(cancelled.status, style::TrainingStatus::Cancelled);
  EXPECT_EQ(cancelled.epochs_completed, 1);
  EXPECT_FALSE(std::filesystem::exists(dir / "cancelled.net"));
  config.settings.resume = true;
  const auto finished = style::trainLossNetwork(config);
  EXPECT_EQ(test::weightsOf(straight.model.network), test::weightsOf(finished.model.network));

  // The same from checkpoints written without fsync (the app's scratch checkpoints).
  config.settings.output = dir / "unsynced.net";
  config.settings.resume = false;
  config.settings.checkpoint_durability = FileDurability::Unsynced;
  ASSERT_EQ(style::trainLossNetwork(config, test::cancelAtEndOfEpoch(2)).status, style::TrainingStatus::Cancelled);
  config.settings.resume = true;
  const auto from_unsynced = style::trainLossNetwork(config);
  EXPECT_EQ(test::weightsOf(straight.model.network), test::weightsOf(from_unsynced.model.network));
}

// A completed run's checkpoint (network + state, megabytes) goes once the output is written, unless
// it is asked for; a cancelled run's stays, to resume from.
TEST(TrainLossNetwork, ACompletedRunRemovesItsCheckpointUnlessKept) {
  TempDir dir;
  auto config = test::tinyLossNetworkConfig(dir / "ae.net", 2);
  const std::filesystem::path checkpoint = config.settings.checkpointPath();
  ASSERT_EQ(style::trainLossNetwork(config, test::cancelAtEndOfEpoch(1)).status, style::TrainingStatus::Cancelled);
  EXPECT_TRUE(std::filesystem::exists(checkpoint));
  EXPECT_TRUE(std::filesystem::exists(style::statePath(checkpoint)));
  config.settings.resume = true;
  ASSERT_EQ(style::trainLossNetwork(config).status, style::TrainingStatus::Completed);
  EXPECT_TRUE(std::filesystem::exists(dir / "ae.net"));
  EXPECT_FALSE(std::filesystem::exists(checkpoint));
  EXPECT_FALSE(std::filesystem::exists(style::statePath(checkpoint)));

  config.settings.resume = false;
  config.settings.keep_checkpoint = true;
  ASSERT_EQ(style::trainLossNetwork(config).status, style::TrainingStatus::Completed);
  EXPECT_TRUE(std::filesystem::exists(checkpoint));
  EXPECT_TRUE(std::filesystem::exists(style::statePath(checkpoint)));
}

TEST(TrainLossNetwork, CancellationTakesEffectWithinOneSecond) {
  TempDir dir;
  // Full-size networks and windows (256 hidden units, width 25, 240 frames): the slowest steps there are.
  style::LossNetworkTrainingConfig config;
  config.settings = test::tinySettings(dir / "ae.net", 1000);
  config.settings.windows = {};
  config.settings.batch_size = 16;
  // The loop's latency, not the disk's: a cancel waits for a checkpoint write in flight, and a synced
  // one waits for the disk's journal, however busy (docs/decisions.md, "A cancel that waited for the disk").
  config.settings.checkpoint_durability = FileDurability::Unsynced;
  config.clips = test::fixtureClips();
  std::atomic<bool> cancel{false};
  std::atomic<int> steps{0};
  style::TrainingCallbacks callbacks;
  callbacks.cancel = &cancel;
  callbacks.progress = [&](const style::TrainingProgress& p) {
    if (p.phase == style::TrainingProgress::Phase::Training) ++steps;
  };
  std::chrono::steady_clock::time_point returned;
  style::LossNetworkTrainingResult result;
  std::thread worker([&] {
    result = style::trainLossNetwork(config, callbacks);
    returned = std::chrono::steady_clock::now();
  });
  while (steps.load() < 1) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(150));  // mid-step, most likely
  const auto requested = std::chrono::steady_clock::now();
  cancel = true;
  worker.join();
  const double latency = std::chrono::duration<double>(returned - requested).count();
  RecordProperty("cancel_latency_ms", std::to_string(static_cast<int>(latency * 1000)));
  EXPECT_EQ(result.status, style::TrainingStatus::Cancelled);
  EXPECT_LT(latency, kCancelBoundSeconds);
  EXPECT_FALSE(std::filesystem::exists(dir / "ae.net"));
}

TEST(TrainLossNetwork, DivergenceStopsWithAnErrorAndKeepsTheLastGoodCheckpoint) {
  TempDir dir;
  auto config = test::tinyLossNetworkConfig(dir / "ae.net", 1);
  config.settings.checkpoint = dir / "shared.checkpoint";
  ASSERT_EQ(style::trainLossNetwork(config).status, style::TrainingStatus::Completed);
  const std::string checkpoint = test::readBytes(config.settings.checkpointPath());
  config.settings.learning_rate = 1e35;  // the first step sends weights to ~1e35: the next loss is infinite
  config.settings.output = dir / "diverged.net";
  EXPECT_THROW(style::trainLossNetwork(config), TrainingDiverged);
  EXPECT_EQ(test::readBytes(config.settings.checkpointPath()), checkpoint);
  EXPECT_FALSE(std::filesystem::exists(dir / "diverged.net"));
}

TEST(TrainLossNetwork, HoldoutKeepsFilesOutOfTraining) {
  TempDir dir;
  auto config = test::tinyLossNetworkConfig(dir / "ae.net", 1);
  config.clips.clear();
  std::filesystem::create_directories(dir / "data");
  std::filesystem::copy_file(test::fixture("cmu_131_01.bvh"), dir / "data/a_walk.bvh");
  std::filesystem::copy_file(test::fixture("zombie.bvh"), dir / "data/b_zombie.bvh");
  config.data = {dir / "data"};
  config.settings.holdout_every = 2;
  const auto result = style::trainLossNetwork(config);
  ASSERT_EQ(result.training_files.size(), 1u);
  ASSERT_EQ(result.held_out_files.size(), 1u);
  EXPECT_EQ(result.held_out_files[0].filename(), "b_zombie.bvh");
}

style::StyleTrainingConfig tinyStyleConfig(const TempDir& dir, int epochs) {
  nn::saveLossNetwork(test::tinyLossNetworkModel(), dir / "ae.net");
  style::StyleTrainingConfig config;
  config.settings = test::tinySettings(dir / "style.net", epochs);
  config.settings.learning_rate = 1e-3;
  config.loss_network = dir / "ae.net";
  config.content_clips = test::fixtureClips();
  config.styles = {{std::nullopt, test::fixture("zombie.bvh")}};
  config.shape = test::tinyTransformationShape();
  config.weights.style = 1.0;  // the tiny untrained loss network has small Gram matrices
  return config;
}

TEST(TrainStyleNetwork, LossDecreasesAndTheFileRecordsTheStyle) {
  TempDir dir;
  std::vector<std::string> log;
  style::TrainingCallbacks callbacks;
  callbacks.log = [&](const std::string& line) { log.push_back(line); };
  const auto result = style::trainStyleNetwork(tinyStyleConfig(dir, 4), callbacks);
  ASSERT_EQ(result.status, style::TrainingStatus::Completed);
  EXPECT_LT(result.history.back().total, result.history.front().total);
  EXPECT_EQ(result.pairing, (std::vector<int>{0, 0}));  // "cmu" and "zombie" labels both use the default
  const nn::StyleModel loaded = style::loadCompatibleStyleModel(dir / "style.net");
  ASSERT_EQ(loaded.metadata.style_clips.size(), 1u);
  EXPECT_EQ(loaded.metadata.style_clips[0].name, "zombie.bvh");
  EXPECT_EQ(loaded.metadata.loss_history.terms.size(), 6u);  // total + 5 terms
  EXPECT_EQ(loaded.loss_network.encoder.weight.value, test::tinyLossNetworkModel().network.encoder.weight.value);
  bool pairing_logged = false;
  for (const auto& line : log) pairing_logged = pairing_logged || line.find("pairing: zombie") != std::string::npos;
  EXPECT_TRUE(pairing_logged);
}

// A fresh network on a small training set still takes kFreshStyleMinimumSteps steps over its run, its
// epochs passing over the windows again (one short clip gave one step an epoch: six Adam steps from
// random weights, a network that destroyed the motion); a warm start keeps one pass an epoch.
TEST(TrainStyleNetwork, AFreshNetworkOnLittleContentTakesTheMinimumSteps) {
  TempDir dir;
  auto config = tinyStyleConfig(dir, 4);
  std::vector<int> steps_per_epoch;
  style::TrainingCallbacks callbacks;
  callbacks.progress = [&](const style::TrainingProgress& p) {
    if (p.phase == style::TrainingProgress::Phase::Training && p.step == p.steps_per_epoch) steps_per_epoch.push_back(p.steps_per_epoch);
  };
  ASSERT_EQ(style::trainStyleNetwork(config, callbacks).status, style::TrainingStatus::Completed);
  ASSERT_EQ(steps_per_epoch.size(), 4u);
  const int minimum = static_cast<int>((style::kFreshStyleMinimumSteps + 3) / 4);
  for (int steps : steps_per_epoch) EXPECT_EQ(steps, minimum);
  config.settings.init = dir / "style.net";
  config.settings.output = dir / "warm.net";
  steps_per_epoch.clear();
  ASSERT_EQ(style::trainStyleNetwork(config, callbacks).status, style::TrainingStatus::Completed);
  ASSERT_EQ(steps_per_epoch.size(), 4u);
  EXPECT_LT(steps_per_epoch.front(), minimum) << "the fixtures' windows are fewer than the minimum's batches";
}

TEST(TrainStyleNetwork, DeterministicResumableAndWarmStartable) {
  TempDir dir;
  auto config = tinyStyleConfig(dir, 2);
  const auto first = style::trainStyleNetwork(config);
  config.settings.output = dir / "again.net";
  const auto second = style::trainStyleNetwork(config);
  EXPECT_EQ(test::weightsOf(first.model.transformation), test::weightsOf(second.model.transformation));

  config.settings.output = dir / "split.net";
  ASSERT_EQ(style::trainStyleNetwork(config, test::cancelAtEndOfEpoch(1)).status, style::TrainingStatus::Cancelled);
  config.settings.resume = true;
  const auto resumed = style::trainStyleNetwork(config);
  EXPECT_EQ(test::weightsOf(first.model.transformation), test::weightsOf(resumed.model.transformation));

  // Warm start: continues from the given network's weights, so its first epoch starts lower.
  config.settings.resume = false;
  config.settings.init = dir / "style.net";
  config.settings.output = dir / "warm.net";
  config.settings.epochs = 1;
  const auto warm = style::trainStyleNetwork(config);
  EXPECT_LT(warm.history.front().total, first.history.front().total);
}

}  // namespace
}  // namespace motionstyle
