// trainAutoencoder: the loss network L (eq. 1-3) on 240-frame windows of a motion database.
#include <chrono>
#include <string>

#include "common/errors.h"
#include "style/cancellation.h"
#include "style/training.h"
#include "style/training_loop.h"

namespace motionstyle::style {
namespace {

std::vector<std::string> settingsParts(const AutoencoderTrainingConfig& config) {
  return {"autoencoder", "hidden=" + std::to_string(config.shape.hidden), "width=" + std::to_string(config.shape.width),
          "sparsity=" + std::to_string(config.sparsity), "dropout=" + std::to_string(config.dropout)};
}

}  // namespace

AutoencoderTrainingResult trainAutoencoder(const AutoencoderTrainingConfig& config, const TrainingCallbacks& callbacks) {
  config.validate();
  const TrainingSettings& settings = config.settings;
  const auto started = std::chrono::steady_clock::now();
  AutoencoderTrainingResult result;
  result.model.network = nn::Autoencoder<float>(config.shape);

  TrainingClips data;
  try {
    data = loadTrainingClips(config.data, config.clips, settings, callbacks, "training", started);
  } catch (const OperationCancelled&) {
    markCancelledBeforeTraining(result, started);
    return result;
  }
  result.training_files = data.training_files;
  result.held_out_files = data.held_out_files;

  nn::AutoencoderModel& model = result.model;
  std::vector<EpochRecord> history;
  std::vector<nn::Parameter<float>*> parameters = model.network.parameters();
  nn::Adam<float> optimiser(parameters, settings.adamOptions());
  const std::uint64_t fingerprint = dataFingerprint(data, settings, settingsParts(config));
  int first_epoch = 1;

  if (settings.resume) {
    const LoadedCheckpoint checkpoint = readCheckpoint(settings.checkpointPath());
    nn::AutoencoderModel resumed = nn::parseAutoencoder(checkpoint.network_bytes, settings.checkpointPath().string());
    if (!(resumed.network.shape() == config.shape))
      throw InputError(settings.checkpointPath().string(), 0, "the checkpoint's autoencoder has another shape");
    model = std::move(resumed);
    parameters = model.network.parameters();
    optimiser = nn::Adam<float>(parameters, settings.adamOptions());
    first_epoch = restoreFromState(checkpoint.state, nn::NetworkKind::Autoencoder, fingerprint,
                                   settings.checkpointPath(), optimiser, history);
    if (callbacks.log) callbacks.log("resuming after epoch " + std::to_string(first_epoch - 1));
  } else if (!settings.init.empty()) {
    // Warm start: the earlier network's weights AND its normalisation (the weights only make sense on
    // inputs normalised the way they were trained).
    nn::AutoencoderModel initial = loadCompatibleAutoencoder(settings.init, settings.dataset.features);
    if (!(initial.network.shape() == config.shape))
      throw InputError(settings.init.string(), 0, "the --init autoencoder has another shape than requested");
    model.network = std::move(initial.network);
    model.normalisation = initial.normalisation;
    parameters = model.network.parameters();
    optimiser = nn::Adam<float>(parameters, settings.adamOptions());
  } else {
    std::vector<Eigen::MatrixXd> values;
    for (const MotionClip& clip : data.clips) values.push_back(clip.features.values);
    model.normalisation = toNormalisation(computeFeatureStatistics(values));
    model.network.initialise(settings.seed);
  }

  const WindowSet windows = makeWindows(data.clips, toStatistics(model.normalisation), settings.windows);
  if (callbacks.log)
    callbacks.log(std::to_string(windows.count()) + " windows of " + std::to_string(windows.frames) + " frames");
  const int frames = windows.frames;
  const float alpha = static_cast<float>(config.sparsity);
  const float dropout = static_cast<float>(config.dropout);

  LoopSetup setup;
  setup.settings = &settings;
  setup.window_count = windows.count();
  setup.first_epoch = first_epoch;
  setup.parameters = parameters;
  setup.optimiser = &optimiser;
  setup.started = started;
  setup.micro_step = [&](const std::vector<int>& indices, std::mt19937& rng) {
    const nn::Mat<float> batch = gatherWindows(windows.values, frames, indices);
    const nn::ReconstructionTerms terms =
        model.network.accumulateReconstruction(batch, frames, alpha, dropout, dropout > 0.0f ? &rng : nullptr);
    return StepLosses{terms.total, {{"mse", terms.mse}, {"sparsity", terms.sparsity}}};
  };
  setup.end_epoch = [&](const std::vector<EpochRecord>& so_far) {
    model.metadata = trainingMetadata(settings, so_far, data);
    model.metadata.training.sparsity = config.sparsity;
    model.metadata.training.dropout = config.dropout;
    saveCheckpoint(settings, nn::serialiseAutoencoder(model), nn::NetworkKind::Autoencoder, optimiser, so_far, fingerprint);
    if (callbacks.autoencoder_snapshot) callbacks.autoencoder_snapshot(model);
  };

  runTrainingLoop(setup, history, callbacks, result);
  model.metadata = trainingMetadata(settings, history, data);
  model.metadata.training.sparsity = config.sparsity;
  model.metadata.training.dropout = config.dropout;
  if (result.status == TrainingStatus::Completed && !settings.output.empty()) nn::saveAutoencoder(model, settings.output);
  result.seconds = secondsSince(started);
  return result;
}

}  // namespace motionstyle::style
