#include "style/adaptation.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <random>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "style/training_loop.h"
#include "style/training_state.h"

namespace motionstyle::style {
namespace {

long frameCount(const std::vector<MotionClip>& clips) {
  long frames = 0;
  for (const MotionClip& clip : clips) frames += clip.frameCount();
  return frames;
}

// Replay clips in a seeded order until they hold `frames` frames (all of them if they hold fewer).
std::vector<MotionClip> chooseReplay(const std::vector<MotionClip>& replay, long frames, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const std::vector<int> order = shuffledIndices(static_cast<int>(replay.size()), rng);
  std::vector<MotionClip> chosen;
  long total = 0;
  for (int i : order) {
    if (total >= frames) break;
    chosen.push_back(replay[static_cast<std::size_t>(i)]);
    total += chosen.back().frameCount();
  }
  return chosen;
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
  return text;
}

std::string fileList(const std::vector<MotionClip>& clips) {
  constexpr std::size_t kListed = 20;
  std::string list;
  for (std::size_t i = 0; i < clips.size() && i < kListed; ++i)
    list += (i ? ", " : "") + clips[i].file.filename().string();
  if (clips.size() > kListed) list += " and " + std::to_string(clips.size() - kListed) + " more";
  return list;
}

double meanFamiliarity(const nn::LossNetworkModel& model, const MotionClip& clip) {
  return measureFamiliarity(model, clip.features.values).mean_cm;
}

constexpr std::size_t kMaxMemoryDescription = 2000;  // the file format reads up to 4096

}  // namespace

void AdaptationSettings::validate() const {
  if (epochs < 1 || epochs > 100000) throw std::invalid_argument("adaptation epochs must be in [1, 100000]");
  if (!(learning_rate > 0.0) || !std::isfinite(learning_rate) || learning_rate > 1.0)
    throw std::invalid_argument("adaptation learning rate must be in (0, 1]");
  if (!(replay_ratio >= 0.0) || !std::isfinite(replay_ratio) || replay_ratio > 100.0)
    throw std::invalid_argument("replay ratio must be in [0, 100]");
  if (!(memory_weight >= 0.0) || !std::isfinite(memory_weight) || memory_weight > 1000.0)
    throw std::invalid_argument("memory weight must be in [0, 1000]");
  if (output.empty() && checkpoint.empty())
    throw std::invalid_argument("adaptation needs an output file (or at least a checkpoint path)");
}

std::filesystem::path AdaptationSettings::checkpointPath() const {
  if (!checkpoint.empty()) return checkpoint;
  std::filesystem::path path = output;
  path += ".checkpoint";
  return path;
}

void AdaptationJob::validate() const {
  settings.validate();
  loss_network.normalisation.validate();
  if (clips.empty()) throw std::invalid_argument("adaptation needs at least one clip of your own");
  for (const MotionClip& clip : clips)
    if (clip.frameCount() < 1 || clip.features.values.rows() != kFeatureCount || !clip.features.values.allFinite())
      throw InputError(clip.file.string(), 0, "the clip's features are empty or not finite");
  if (memory) {
    memory->validate();
    if (settings.train_encoder) throw std::invalid_argument("a reconstruction memory keeps the encoder: it cannot train it");
    memory->requireMatches(loss_network, "the reconstruction memory");
  }
}

std::vector<MotionClip> AdaptationJob::replayToMix() const {
  if (replay.empty()) return {};
  return chooseReplay(replay, static_cast<long>(settings.replay_ratio * static_cast<double>(frameCount(clips))),
                      settings.seed);
}

AdaptationResult AdaptationJob::run(const TrainingCallbacks& callbacks) const {
  validate();
  const auto started = std::chrono::steady_clock::now();
  LossNetworkTrainingConfig config;
  TrainingSettings& training = config.settings;
  training.epochs = settings.epochs;
  training.learning_rate = settings.learning_rate;
  training.seed = settings.seed;
  training.checkpoint = settings.checkpointPath();
  training.checkpoint_durability = settings.checkpoint_durability;
  config.clips = clips;
  const std::vector<MotionClip> mixed = replayToMix();
  config.clips.insert(config.clips.end(), mixed.begin(), mixed.end());
  config.init_model = loss_network;
  config.shape = loss_network.network.shape();
  config.sparsity = loss_network.metadata.training.sparsity;
  config.dropout = loss_network.metadata.training.dropout;
  config.train_encoder = settings.train_encoder;
  if (memory) {
    config.memory = &*memory;
    config.memory_weight = settings.memory_weight;
  }
  if (callbacks.log)
    callbacks.log("adapting on " + std::to_string(clips.size()) + " clip(s) (" + std::to_string(frameCount(clips)) +
                  " frames) with " + std::to_string(mixed.size()) + " replay clip(s) mixed in" +
                  (memory && settings.memory_weight > 0.0 ? " and the memory of " + memory->description : std::string()) + "; " +
                  (settings.train_encoder ? "encoder and decoder learn" : "the decoder learns, the encoder is kept"));

  AdaptationResult result;
  LossNetworkTrainingResult trained = trainLossNetwork(config, callbacks);
  result.status = trained.status;
  result.model = std::move(trained.model);
  result.replay_clips = static_cast<int>(mixed.size());
  if (memory && settings.memory_weight > 0.0) result.memory = memory->description;
  nn::NetworkMetadata& metadata = result.model.metadata;
  metadata.properties.emplace_back("adapted_from", loss_network_name);
  metadata.properties.emplace_back("adapted_on", fileList(clips));
  metadata.properties.emplace_back("adapted_clips", std::to_string(clips.size()));
  metadata.properties.emplace_back("adapted_frames", std::to_string(frameCount(clips)));
  metadata.properties.emplace_back("adapted_replay_clips", std::to_string(mixed.size()));
  if (memory && settings.memory_weight > 0.0) {
    char weight[32];
    std::snprintf(weight, sizeof weight, "%g", settings.memory_weight);
    metadata.properties.emplace_back("adapted_memory",
                                     memory->description + " (" + std::to_string(memory->clips) + " clips, weight " + weight + ")");
  }
  metadata.properties.emplace_back("adapted_encoder", settings.train_encoder ? "trained" : "kept");
  metadata.properties.emplace_back("adapted_date", today());
  if (result.status == TrainingStatus::Completed) {
    double before = 0.0, after = 0.0;
    for (const MotionClip& clip : clips) {
      ClipFamiliarity figures{clip.file, meanFamiliarity(loss_network, clip), meanFamiliarity(result.model, clip)};
      before += figures.before_cm * clip.frameCount();
      after += figures.after_cm * clip.frameCount();
      result.clips.push_back(figures);
    }
    result.mean_before_cm = before / static_cast<double>(frameCount(clips));
    result.mean_after_cm = after / static_cast<double>(frameCount(clips));
    if (!settings.train_encoder) {
      std::vector<MotionClip> adapted_on = clips;
      adapted_on.insert(adapted_on.end(), mixed.begin(), mixed.end());
      ReconstructionMemory learnt = rememberReconstruction(
          result.model, adapted_on, "the " + std::to_string(clips.size()) + " clip(s) it was adapted on (" + fileList(clips) + ")");
      if (memory && settings.memory_weight > 0.0) {
        std::string both = memory->description + "; " + learnt.description;
        if (both.size() > kMaxMemoryDescription) both = both.substr(0, kMaxMemoryDescription - 3) + "...";
        result.memory_after = mergeMemories(*memory, settings.memory_weight, learnt, 1.0, std::move(both));
      } else {
        result.memory_after = std::move(learnt);
      }
    }
    if (!settings.output.empty()) {  // the network and its memory: both or neither
      AtomicFileBatch batch;
      batch.stage(settings.output, nn::serialiseLossNetwork(result.model));
      if (result.memory_after) {
        result.memory_file = memoryFileBeside(settings.output);
        batch.stage(result.memory_file, serialiseReconstructionMemoryCompactly(*result.memory_after));
      }
      batch.commit();
      if (!settings.keep_checkpoint) removeCheckpoint(training.checkpoint);
    }
  }
  result.seconds = secondsSince(started);
  return result;
}

void AdaptNetworksJob::validate() const {
  loss.validate();
  if (style_epochs < 1 || style_epochs > 100000) throw std::invalid_argument("style epochs must be in [1, 100000]");
  if (!(style_learning_rate > 0.0) || !std::isfinite(style_learning_rate))
    throw std::invalid_argument("style learning rate must be > 0");
  for (const StyleToRetrain& style : styles)
    if (style.model.style_targets.empty())
      throw std::invalid_argument(style.name + " stores no style targets (made before format 3): retrain it from its "
                                                "style clips instead");
  if (!styles.empty() && scratch.empty()) throw std::invalid_argument("retraining styles needs a scratch folder");
}

AdaptNetworksJob::Result AdaptNetworksJob::run(const TrainingCallbacks& callbacks) const {
  validate();
  const auto started = std::chrono::steady_clock::now();
  const int stages = 1 + static_cast<int>(styles.size());
  const auto stageCallbacks = [&](const std::string& stage) {
    TrainingCallbacks c = callbacks;
    if (callbacks.progress)
      c.progress = [&callbacks, stage](const TrainingProgress& p) {
        TrainingProgress named = p;
        named.message = stage + (p.message.empty() ? "" : ": " + p.message);
        callbacks.progress(named);
      };
    return c;
  };
  Result result;
  result.loss = loss.run(stageCallbacks(styles.empty() ? "adapting the loss network"
                                                       : "adapting the loss network (1 of " + std::to_string(stages) + ")"));
  result.status = result.loss.status;
  for (std::size_t i = 0; i < styles.size() && result.status == TrainingStatus::Completed; ++i) {
    StyleTrainingConfig config;
    TrainingSettings& settings = config.settings;
    settings.epochs = style_epochs;
    settings.learning_rate = style_learning_rate;
    settings.seed = loss.settings.seed;
    settings.checkpoint = scratch / (styles[i].name + ".adapting.checkpoint");
    settings.checkpoint_durability = loss.settings.checkpoint_durability;
    config.loss_network_model = result.loss.model;
    config.content_clips = loss.clips;
    const std::vector<MotionClip> mixed = loss.replayToMix();
    config.content_clips.insert(config.content_clips.end(), mixed.begin(), mixed.end());
    config.init_model = styles[i].model;
    config.style_targets = styles[i].model.style_targets;
    config.weights = styles[i].model.metadata.training.weights;
    config.shape = styles[i].model.transformation.shape();
    const std::string stage = "retraining " + styles[i].name + " (" + std::to_string(i + 2) + " of " +
                              std::to_string(stages) + ")";
    StyleTrainingResult trained = trainStyleNetwork(config, stageCallbacks(stage));
    result.status = trained.status;
    if (trained.status != TrainingStatus::Completed) break;
    trained.model.metadata.properties.emplace_back("adapted_from", styles[i].name);
    trained.model.metadata.properties.emplace_back("adapted_on", fileList(loss.clips));
    trained.model.metadata.properties.emplace_back("adapted_date", today());
    result.styles.push_back({styles[i].name, std::move(trained.model)});
  }
  result.seconds = secondsSince(started);
  return result;
}

}  // namespace motionstyle::style
