// trainLossNetwork: the loss network L (eq. 1-3) on 240-frame windows of a motion database.
#include <chrono>
#include <string>

#include "common/errors.h"
#include "style/cancellation.h"
#include "style/reconstruction_memory.h"
#include "style/training.h"
#include "style/training_loop.h"
#include "style/training_state.h"

namespace motionstyle::style {
namespace {

std::vector<std::string> settingsParts(const LossNetworkTrainingConfig& config) {
  return {"loss_network", "hidden=" + std::to_string(config.shape.hidden), "width=" + std::to_string(config.shape.width),
          "sparsity=" + std::to_string(config.sparsity), "dropout=" + std::to_string(config.dropout),
          "foot=" + std::to_string(config.foot_weight),
          config.train_encoder ? "encoder=trained" : "encoder=frozen"};
}

}  // namespace

LossNetworkTrainingResult trainLossNetwork(const LossNetworkTrainingConfig& config, const TrainingCallbacks& callbacks) {
  config.validate();
  const TrainingSettings& settings = config.settings;
  // The loss network learns motion as captured: its files without rig canonicalisation (the styles'
  // girdle posture included); content clips are canonicalised toward what it learnt.
  TrainingSettings loading = settings;
  loading.dataset.features.canonical_rig = false;
  const auto started = std::chrono::steady_clock::now();
  LossNetworkTrainingResult result;
  result.model.network = nn::LossNetwork<float>(config.shape);

  std::optional<TrainingClips> loaded =
      loadTrainingClips(config.data, config.clips, loading, callbacks, "training", started, result);
  if (!loaded) return result;
  const TrainingClips& data = *loaded;

  nn::LossNetworkModel& model = result.model;
  std::vector<EpochRecord> history;
  nn::Adam<float> optimiser(model.network.parameters(), settings.adamOptions());
  const std::uint64_t fingerprint = dataFingerprint(data, settings, settingsParts(config));
  TrainedNetwork network;
  network.kind = nn::NetworkKind::LossNetwork;
  network.resume = [&](const std::string& network_bytes, const std::filesystem::path& checkpoint) {
    nn::LossNetworkModel resumed = nn::parseLossNetwork(network_bytes, checkpoint.string());
    if (!(resumed.network.shape() == config.shape))
      throw InputError(checkpoint.string(), 0, "the checkpoint's loss network has another shape");
    model = std::move(resumed);
  };
  if (config.init_model || !settings.init.empty())
    network.warm_start = [&] {
      // The earlier network's weights AND its normalisation (the weights only make sense on inputs
      // normalised the way they were trained).
      nn::LossNetworkModel initial =
          config.init_model ? *config.init_model : loadCompatibleLossNetwork(settings.init, settings.dataset.features);
      if (!(initial.network.shape() == config.shape))
        throw InputError(settings.init.string(), 0, "the --init loss network has another shape than requested");
      model.network = std::move(initial.network);
      model.normalisation = initial.normalisation;
    };
  network.fresh = [&] {
    std::vector<Eigen::MatrixXd> values;
    for (const MotionClip& clip : data.clips) values.push_back(clip.features.values);
    model.normalisation = computeFeatureStatistics(values);
    model.network.initialise(settings.seed);
  };
  // A frozen encoder (adaptation) trains the decoder's W~0 alone: the optimiser's state is the decoder's.
  network.parameters = [&] {
    return config.train_encoder ? model.network.parameters()
                                : std::vector<nn::Parameter<float>*>{&model.network.decoder.weight};
  };
  network.serialise = [&] { return nn::serialiseLossNetwork(model); };
  network.save = [&](const std::filesystem::path& file) { nn::saveLossNetwork(model, file); };
  if (callbacks.loss_network_snapshot) network.snapshot = [&] { callbacks.loss_network_snapshot(model); };
  LoopSetup setup = startTraining(network, settings, fingerprint, optimiser, history, callbacks, started);
  const FeatureStatistics& statistics = model.normalisation;
  WindowSet windows = makeWindows(data.clips, statistics, settings.windows);
  if (callbacks.log)
    callbacks.log(std::to_string(windows.count()) + " windows of " + std::to_string(windows.frames) + " frames");
  const int frames = windows.frames;
  const float alpha = static_cast<float>(config.sparsity);
  const float dropout = static_cast<float>(config.dropout);

  setup.window_count = windows.count();
  if (settings.augmentation.enabled())
    setup.begin_epoch = [&](int epoch) {
      windows = makeWindows(augmentedEpoch(data.clips, settings.augmentation, settings.seed, epoch, loading.dataset),
                            statistics, settings.windows);
      return windows.count();
    };
  const FeatureStatistics normalisation = model.normalisation;
  setup.micro_step = [&](const std::vector<int>& indices, std::mt19937& rng) {
    const nn::Mat<float> batch = gatherWindows(windows.values, frames, indices);
    const nn::Mat<float> contacts = gatherWindows(windows.contacts, frames, indices);
    const nn::ReconstructionFootTerm<float> foot{&contacts, &normalisation, static_cast<float>(config.foot_weight)};
    const nn::ReconstructionTerms terms =
        model.network.accumulateReconstruction(batch, frames, alpha, dropout, dropout > 0.0f ? &rng : nullptr, foot);
    if (!config.train_encoder) {  // the frozen encoder's gradients are never used
      model.network.encoder.weight.zeroGrad();
      model.network.encoder.bias.zeroGrad();
    }
    StepLosses losses{terms.total, {{"mse", terms.mse}, {"sparsity", terms.sparsity}}};
    if (config.foot_weight > 0.0) losses.terms.emplace_back("foot", terms.foot);
    if (config.memory != nullptr && config.memory_weight > 0.0) {  // once per step: the micro-batch fractions sum to 1
      Eigen::MatrixXf gradient;
      const double remembered = memoryError(*config.memory, model.network.decoder.weight.value, &gradient);
      model.network.decoder.weight.grad += static_cast<float>(config.memory_weight) * gradient;
      losses.total += config.memory_weight * remembered;
      losses.terms.emplace_back("memory", remembered);
    }
    return losses;
  };
  const auto metadata = [&](const std::vector<EpochRecord>& so_far) {
    nn::NetworkMetadata m = trainingMetadata(settings, so_far, data);
    m.training.sparsity = config.sparsity;
    m.training.dropout = config.dropout;
    if (config.foot_weight > 0.0) m.properties.emplace_back("foot_weight", std::to_string(config.foot_weight));
    return m;
  };
  network.set_metadata = [&](const std::vector<EpochRecord>& so_far) { model.metadata = metadata(so_far); };
  runTraining(network, setup, fingerprint, history, callbacks, result);
  return result;
}

}  // namespace motionstyle::style
