// Shared pieces of the training API: settings validation, the representation stamp, model loading.
#include "style/training.h"

#include "style/reconstruction_memory.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "nn/compute_pool.h"

namespace motionstyle::style {

double scheduledLearningRate(LearningRateSchedule schedule, double learning_rate, long step, long total_steps) {
  if (schedule == LearningRateSchedule::Constant || total_steps <= 1) return learning_rate;
  const long warmup = std::min(kWarmupSteps, total_steps / 10);
  const double warming = step < warmup ? static_cast<double>(step + 1) / static_cast<double>(warmup) : 1.0;
  const double progress = std::clamp(static_cast<double>(step) / static_cast<double>(total_steps - 1), 0.0, 1.0);
  const double cosine = 0.5 * (1.0 + std::cos(std::numbers::pi * progress));  // 1 -> 0
  return warming * learning_rate * (kFinalLearningRateFraction + (1.0 - kFinalLearningRateFraction) * cosine);
}

const char* scheduleName(LearningRateSchedule schedule) {
  return schedule == LearningRateSchedule::Cosine ? "cosine" : "constant";
}

std::filesystem::path TrainingSettings::checkpointPath() const {
  if (!checkpoint.empty()) return checkpoint;
  std::filesystem::path path = output;
  path += ".checkpoint";
  return path;
}

nn::AdamOptions TrainingSettings::adamOptions() const {
  nn::AdamOptions options;
  options.learning_rate = learning_rate;
  options.gradient_clip = gradient_clip;
  return options;
}

void TrainingSettings::validate() const {
  if (epochs < 1) throw std::invalid_argument("epochs must be >= 1");
  if (batch_size < 1) throw std::invalid_argument("batch size must be >= 1");
  if (!std::isfinite(learning_rate) || learning_rate <= 0) throw std::invalid_argument("learning rate must be > 0");
  if (!std::isfinite(gradient_clip) || gradient_clip < 0) throw std::invalid_argument("gradient clip must be >= 0");
  if (threads < 0) throw std::invalid_argument("threads must be >= 0");
  if (threads > 0 && threads != nn::computePool().threadCount())
    throw std::invalid_argument("threads = " + std::to_string(threads) + " but the nn compute pool runs " +
                                std::to_string(nn::computePool().threadCount()) +
                                " (set MOTIONSTYLE_NN_THREADS before the first network runs)");
  if (output.empty() && checkpoint.empty())
    throw std::invalid_argument("an output path (or at least a checkpoint path) is required");
  if (resume && !init.empty()) throw std::invalid_argument("--resume and --init exclude each other");
  if (holdout_every < 0 || holdout_every == 1) throw std::invalid_argument("hold-out must be 0 (none) or every N >= 2");
  windows.validate();
  augmentation.validate();
}

void LossNetworkTrainingConfig::validate() const {
  settings.validate();
  if (data.empty() && clips.empty()) throw std::invalid_argument("no training data (folders, files or clips)");
  if (!std::isfinite(sparsity) || sparsity < 0) throw std::invalid_argument("sparsity must be >= 0");
  if (!std::isfinite(dropout) || dropout < 0 || dropout >= 1) throw std::invalid_argument("dropout must be in [0, 1)");
  if (!std::isfinite(foot_weight) || foot_weight < 0) throw std::invalid_argument("foot weight must be >= 0");
  if (!train_encoder && settings.resume)
    throw std::invalid_argument("a run that trains only the decoder cannot be resumed: start it again");
  if (shape.features != kFeatureCount) throw std::invalid_argument("the loss network must take 66 features");
  if (shape.hidden < 1 || shape.width < 1 || shape.width % 2 == 0)
    throw std::invalid_argument("loss network hidden units must be >= 1 and the width odd");
  if (!std::isfinite(memory_weight) || memory_weight < 0 || memory_weight > 1000)
    throw std::invalid_argument("memory weight must be in [0, 1000]");
  if (memory != nullptr && memory_weight > 0) {
    if (train_encoder) throw std::invalid_argument("a reconstruction memory keeps the encoder: it cannot train it");
    if (!init_model) throw std::invalid_argument("a reconstruction memory needs the network it was made with to start from");
    memory->validate();
    memory->requireMatches(*init_model, "the reconstruction memory");
  }
}

void StyleTrainingConfig::validate() const {
  settings.validate();
  if (loss_network.empty() && !loss_network_model) throw std::invalid_argument("no loss network (--loss-network) given");
  if (content.empty() && content_clips.empty()) throw std::invalid_argument("no content clips given");
  if (styles.empty() && style_targets.empty() && settings.init.empty() && !init_model)
    throw std::invalid_argument("no style clip given (nor stored style targets or a network to take them from)");
  weights.validate();
  if (shape.features != kFeatureCount) throw std::invalid_argument("the transformation network must take 66 features");
  if (shape.hidden < 1 || shape.width < 1 || shape.width % 2 == 0)
    throw std::invalid_argument("transformation network hidden units must be >= 1 and the width odd");
}

nn::RepresentationInfo currentRepresentation(const FeatureOptions& options) {
  nn::RepresentationInfo info;
  info.fps = options.fps;
  info.joint_set = std::string(options.retarget_proportions ? nn::kRetargetedJointSetName : nn::kCanonicalJointSetName);
  info.reference_body_height_cm = kReferenceSkeletalHeightCm;
  info.feature_count = kFeatureCount;
  return info;
}

nn::LossNetworkModel loadCompatibleLossNetwork(const std::filesystem::path& file, const FeatureOptions& options) {
  nn::LossNetworkModel model = nn::loadLossNetwork(file);
  nn::checkCompatible(model.metadata.representation, currentRepresentation(options), file.string());
  return model;
}

nn::StyleModel loadCompatibleStyleModel(const std::filesystem::path& file, const FeatureOptions& options) {
  nn::StyleModel model = nn::loadStyleModel(file);
  nn::checkCompatible(model.metadata.representation, currentRepresentation(options), file.string());
  return model;
}

}  // namespace motionstyle::style
