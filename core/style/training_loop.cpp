#include "style/training_loop.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>

#include "common/errors.h"
#include "nn/compute_pool.h"
#include "style/cancellation.h"

namespace motionstyle::style {

std::mt19937 epochGenerator(std::uint32_t seed, int epoch, std::uint32_t purpose) {
  std::seed_seq sequence{seed, static_cast<std::uint32_t>(epoch), purpose};
  return std::mt19937(sequence);
}

std::vector<int> shuffledIndices(int count, std::mt19937& rng) {
  std::vector<int> order(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) order[static_cast<std::size_t>(i)] = i;
  for (int i = count - 1; i > 0; --i) {
    const auto j = static_cast<std::size_t>(rng() % static_cast<std::uint32_t>(i + 1));
    std::swap(order[static_cast<std::size_t>(i)], order[j]);
  }
  return order;
}

GradientAccumulator::GradientAccumulator(std::vector<nn::Parameter<float>*> parameters)
    : parameters_(std::move(parameters)) {
  for (const nn::Parameter<float>* p : parameters_) sum_.push_back(nn::Mat<float>::Zero(p->value.rows(), p->value.cols()));
}

namespace {

// f(begin, end) over ranges of a parameter's columns (its value, gradient and sums alike), on the pool.
template <typename Range>
void forColumns(const nn::Parameter<float>& p, const Range& f) {
  nn::parallelItems(p.value.cols(), p.value.rows(), f);
}

}  // namespace

void GradientAccumulator::begin() {
  for (std::size_t i = 0; i < parameters_.size(); ++i) {
    nn::Parameter<float>& p = *parameters_[i];
    p.grad.resize(p.value.rows(), p.value.cols());
    forColumns(p, [&](int begin, int end) {
      sum_[i].middleCols(begin, end - begin).setZero();
      p.grad.middleCols(begin, end - begin).setZero();
    });
  }
}

void GradientAccumulator::add(float fraction) {
  for (std::size_t i = 0; i < parameters_.size(); ++i) {
    nn::Parameter<float>& p = *parameters_[i];
    forColumns(p, [&](int begin, int end) {
      sum_[i].middleCols(begin, end - begin) += fraction * p.grad.middleCols(begin, end - begin);
      p.grad.middleCols(begin, end - begin).setZero();
    });
  }
}

void GradientAccumulator::finish() {
  for (std::size_t i = 0; i < parameters_.size(); ++i) {
    nn::Parameter<float>& p = *parameters_[i];
    forColumns(p, [&](int begin, int end) { p.grad.middleCols(begin, end - begin) = sum_[i].middleCols(begin, end - begin); });
  }
}

bool parametersFinite(const std::vector<nn::Parameter<float>*>& parameters) {
  std::atomic<bool> finite = true;
  for (const nn::Parameter<float>* p : parameters)
    forColumns(*p, [&](int begin, int end) {
      if (!p->value.middleCols(begin, end - begin).allFinite()) finite = false;
    });
  return finite;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void runTrainingLoop(const LoopSetup& setup, std::vector<EpochRecord>& history, const TrainingCallbacks& callbacks,
                     TrainingResult& result) {
  result.status = runTrainingLoop(setup, history, callbacks);
  result.history = history;
  result.epochs_completed = history.empty() ? 0 : history.back().epoch;
}

LoopSetup startTraining(const TrainedNetwork& network, const TrainingSettings& settings, std::uint64_t data_fingerprint,
                        nn::Adam<float>& optimiser, std::vector<EpochRecord>& history,
                        const TrainingCallbacks& callbacks, std::chrono::steady_clock::time_point started) {
  std::optional<LoadedCheckpoint> checkpoint;
  if (settings.resume) {
    checkpoint = readCheckpoint(settings.checkpointPath());
    network.resume(checkpoint->network_bytes, settings.checkpointPath());
  } else if (network.warm_start) {
    network.warm_start();
  } else {
    network.fresh();
  }
  LoopSetup setup;
  setup.settings = &settings;
  setup.parameters = network.parameters();
  optimiser = nn::Adam<float>(setup.parameters, settings.adamOptions());
  setup.optimiser = &optimiser;
  setup.started = started;
  if (checkpoint) {
    setup.first_epoch = restoreFromState(checkpoint->state, network.kind, data_fingerprint, settings.checkpointPath(),
                                         optimiser, history);
    if (callbacks.log) callbacks.log("resuming after epoch " + std::to_string(setup.first_epoch - 1));
  }
  return setup;
}

void runTraining(const TrainedNetwork& network, LoopSetup setup, std::uint64_t data_fingerprint,
                 std::vector<EpochRecord>& history, const TrainingCallbacks& callbacks, TrainingResult& result) {
  const TrainingSettings& settings = *setup.settings;
  setup.end_epoch = [&](const std::vector<EpochRecord>& so_far) {
    network.set_metadata(so_far);
    saveCheckpoint(settings, network.serialise(), network.kind, *setup.optimiser, so_far, data_fingerprint);
    if (network.snapshot) network.snapshot();
  };
  runTrainingLoop(setup, history, callbacks, result);
  network.set_metadata(history);
  if (result.status == TrainingStatus::Completed && !settings.output.empty()) {
    network.save(settings.output);
    if (!settings.keep_checkpoint) removeCheckpoint(settings.checkpointPath());
  }
  result.seconds = secondsSince(setup.started);
}

void markCancelledBeforeTraining(TrainingResult& result, std::chrono::steady_clock::time_point started) {
  result.status = TrainingStatus::Cancelled;
  result.seconds = secondsSince(started);
}

namespace {

void accumulateTerms(std::vector<NamedLoss>& sum, const std::vector<NamedLoss>& terms, double fraction) {
  if (sum.empty())
    for (const NamedLoss& term : terms) sum.push_back({term.name, 0.0});
  for (std::size_t i = 0; i < terms.size() && i < sum.size(); ++i) sum[i].value += fraction * terms[i].value;
}

// The end of a divergence message: where the last good network is (the checkpoint of the last
// completed epoch; none before the first).
std::string keptCheckpoint(const TrainingSettings& settings) {
  std::error_code ignored;
  const std::filesystem::path checkpoint = settings.checkpointPath();
  if (checkpoint.empty() || !std::filesystem::exists(checkpoint, ignored)) return "; no epoch completed, no checkpoint";
  return "; the last good checkpoint is kept: " + checkpoint.string();
}

}  // namespace

TrainingStatus runTrainingLoop(const LoopSetup& setup, std::vector<EpochRecord>& history,
                               const TrainingCallbacks& callbacks) {
  const TrainingSettings& settings = *setup.settings;
  const int batch = settings.batch_size;
  const auto stepsPerEpoch = [&](int windows) {
    return windows > 0 ? std::max((windows + batch - 1) / batch, setup.minimum_steps_per_epoch) : 0;
  };
  const long total_steps = static_cast<long>(stepsPerEpoch(setup.window_count)) * (settings.epochs - setup.first_epoch + 1);
  long steps_done = 0;
  const auto loop_start = std::chrono::steady_clock::now();
  GradientAccumulator accumulator(setup.parameters);

  for (int epoch = setup.first_epoch; epoch <= settings.epochs; ++epoch) {
    const auto epoch_start = std::chrono::steady_clock::now();
    std::mt19937 shuffle_rng = epochGenerator(settings.seed, epoch, 1);
    std::mt19937 layer_rng = epochGenerator(settings.seed, epoch, 2);
    int window_count = setup.window_count;
    if (setup.begin_epoch) {
      try {
        window_count = setup.begin_epoch(epoch);
      } catch (const OperationCancelled&) {
        return TrainingStatus::Cancelled;
      }
    }
    const int steps_per_epoch = stepsPerEpoch(window_count);
    std::vector<int> order = shuffledIndices(window_count, shuffle_rng);
    if (steps_per_epoch > (window_count + batch - 1) / batch && window_count > 0) {  // too few: pass over them again
      while (static_cast<int>(order.size()) < steps_per_epoch * batch) {
        const std::vector<int> again = shuffledIndices(window_count, shuffle_rng);
        order.insert(order.end(), again.begin(), again.end());
      }
      order.resize(static_cast<std::size_t>(steps_per_epoch * batch));
    }
    const int ordered = static_cast<int>(order.size());
    EpochRecord record;
    record.epoch = epoch;
    int clipped_steps = 0;
    for (int step = 0; step < steps_per_epoch; ++step) {
      const int begin = step * batch;
      const int end = std::min(ordered, begin + batch);
      accumulator.begin();
      StepLosses losses;
      for (int micro = begin; micro < end; micro += kMicroBatchWindows) {
        if (cancelRequested(callbacks.cancel)) {
          accumulator.begin();  // discard the step in flight
          return TrainingStatus::Cancelled;
        }
        const int micro_end = std::min(end, micro + kMicroBatchWindows);
        const std::vector<int> windows(order.begin() + micro, order.begin() + micro_end);
        const StepLosses micro_losses = setup.micro_step(windows, layer_rng);
        const double fraction = static_cast<double>(micro_end - micro) / (end - begin);
        accumulator.add(static_cast<float>(fraction));
        losses.total += fraction * micro_losses.total;
        accumulateTerms(losses.terms, micro_losses.terms, fraction);
      }
      accumulator.finish();
      if (!std::isfinite(losses.total))
        throw TrainingDiverged("training diverged at epoch " + std::to_string(epoch) + ", step " +
                               std::to_string(step + 1) + ": the loss is not finite (lower the learning rate?)" + keptCheckpoint(settings));
      const long global_step = static_cast<long>(epoch - 1) * steps_per_epoch + step;
      setup.optimiser->setLearningRate(scheduledLearningRate(settings.schedule, settings.learning_rate, global_step,
                                                             static_cast<long>(settings.epochs) * steps_per_epoch));
      setup.optimiser->step();
      if (setup.optimiser->clippedInLastStep() > 0) ++clipped_steps;
      if (!parametersFinite(setup.parameters))
        throw TrainingDiverged("training diverged at epoch " + std::to_string(epoch) + ", step " +
                               std::to_string(step + 1) + ": the weights are no longer finite (lower the learning rate?)" + keptCheckpoint(settings));
      ++steps_done;
      record.total += losses.total / steps_per_epoch;
      accumulateTerms(record.terms, losses.terms, 1.0 / steps_per_epoch);
      if (callbacks.progress) {
        TrainingProgress progress;
        progress.phase = TrainingProgress::Phase::Training;
        progress.epoch = epoch;
        progress.epochs = settings.epochs;
        progress.step = step + 1;
        progress.steps_per_epoch = steps_per_epoch;
        progress.total = losses.total;
        progress.terms = losses.terms;
        progress.elapsed_seconds = secondsSince(setup.started);
        const double per_step = secondsSince(loop_start) / static_cast<double>(steps_done);
        progress.eta_seconds = per_step * static_cast<double>(std::max(0L, total_steps - steps_done));
        callbacks.progress(progress);
      }
    }
    record.seconds = secondsSince(epoch_start);
    history.push_back(record);
    if (clipped_steps > 0 && callbacks.log)
      callbacks.log("epoch " + std::to_string(epoch) + ": " + std::to_string(clipped_steps) +
                    " step(s) with an outlier gradient, scaled down to the clip bound");
    setup.end_epoch(history);
    if (callbacks.progress) {
      TrainingProgress progress;
      progress.phase = TrainingProgress::Phase::EpochEnd;
      progress.epoch = epoch;
      progress.epochs = settings.epochs;
      progress.step = steps_per_epoch;
      progress.steps_per_epoch = steps_per_epoch;
      progress.total = record.total;
      progress.terms = record.terms;
      progress.elapsed_seconds = secondsSince(setup.started);
      progress.eta_seconds = secondsSince(loop_start) / static_cast<double>(steps_done) *
                             static_cast<double>(std::max(0L, total_steps - steps_done));
      callbacks.progress(progress);
    }
  }
  return TrainingStatus::Completed;
}

namespace {

TrainingClips loadClips(const std::vector<std::filesystem::path>& inputs, const std::vector<MotionClip>& preloaded,
                        const TrainingSettings& settings, const TrainingCallbacks& callbacks, const std::string& what,
                        std::chrono::steady_clock::time_point started) {
  TrainingClips data;
  if (!preloaded.empty()) {
    for (const MotionClip& clip : preloaded)
      if (clip.features.values.rows() != kFeatureCount || clip.frameCount() < 1 || !clip.features.values.allFinite() ||
          clip.features.contacts.cols() != clip.frameCount() || !clip.features.contacts.allFinite() ||
          clip.bone_lengths.size() != nn::kBoneCount || !clip.bone_lengths.allFinite())
        throw InputError(clip.file.string(), 0, "the clip's features are empty, inconsistent or not finite (NaN?)");
    for (std::size_t i = 0; i < preloaded.size(); ++i) {
      const bool held = settings.holdout_every > 0 && (i + 1) % static_cast<std::size_t>(settings.holdout_every) == 0;
      if (held) {
        data.held_out_files.push_back(preloaded[i].file);
      } else {
        data.training_files.push_back(preloaded[i].file);
        data.clips.push_back(preloaded[i]);
      }
    }
  } else {
    const HoldoutSplit split = splitHoldout(findBvhFiles(inputs), settings.holdout_every);
    data.held_out_files = split.held_out;
    // Files named explicitly always fail when bad; files found in folders follow the skip policy.
    std::vector<std::filesystem::path> explicit_files;
    for (const auto& input : inputs)
      if (!std::filesystem::is_directory(input)) explicit_files.push_back(input);
    const auto on_file = [&](int done, int total) {
      if (!callbacks.progress) return;
      TrainingProgress progress;
      progress.phase = TrainingProgress::Phase::Loading;
      progress.message = "loading " + what + " clip " + std::to_string(done) + " of " + std::to_string(total);
      progress.elapsed_seconds = secondsSince(started);
      callbacks.progress(progress);
    };
    int done = 0;
    const int total = static_cast<int>(split.training.size());
    DatasetOptions dataset = settings.dataset;
    dataset.keep_motion = dataset.keep_motion || settings.augmentation.enabled();
    for (const std::filesystem::path& file : split.training) {
      throwIfCancelled(callbacks.cancel);
      const bool from_folder =
          std::find(explicit_files.begin(), explicit_files.end(), file) == explicit_files.end();
      try {
        data.clips.push_back(loadMotionClip(file, dataset));
        data.training_files.push_back(file);
      } catch (const InputError& error) {
        if (settings.dataset.bad_files == BadFilePolicy::Fail || !from_folder) throw;
        if (callbacks.log) callbacks.log("warning: skipped " + file.string() + ": " + error.detail());
      }
      on_file(++done, total);
    }
    if (data.clips.empty())
      throw InputError(inputs.empty() ? std::string() : inputs.front().string(), 0,
                       "no usable " + what + " clip (every file was held out or skipped)");
  }
  if (data.clips.empty()) throw InputError("", 0, "no usable " + what + " clip after the hold-out split");
  if (callbacks.log) {
    std::string note = what + ": " + std::to_string(data.clips.size()) + " clip(s)";
    if (!data.held_out_files.empty()) note += ", " + std::to_string(data.held_out_files.size()) + " held out";
    callbacks.log(note);
  }
  return data;
}

}  // namespace

std::optional<TrainingClips> loadTrainingClips(const std::vector<std::filesystem::path>& inputs,
                                               const std::vector<MotionClip>& preloaded,
                                               const TrainingSettings& settings, const TrainingCallbacks& callbacks,
                                               const std::string& what, std::chrono::steady_clock::time_point started,
                                               TrainingResult& result) {
  try {
    TrainingClips data = loadClips(inputs, preloaded, settings, callbacks, what, started);
    result.training_files = data.training_files;
    result.held_out_files = data.held_out_files;
    return data;
  } catch (const OperationCancelled&) {
    markCancelledBeforeTraining(result, started);
    return std::nullopt;
  }
}

nn::NetworkMetadata trainingMetadata(const TrainingSettings& settings, const std::vector<EpochRecord>& history,
                                     const TrainingClips& data) {
  nn::NetworkMetadata metadata;
  metadata.representation = currentRepresentation(settings.dataset.features);
  metadata.training.epochs = history.empty() ? 0 : history.back().epoch;
  metadata.training.learning_rate = settings.learning_rate;
  metadata.properties.emplace_back("lr_schedule", scheduleName(settings.schedule));
  metadata.properties.emplace_back("gradient_clip", std::to_string(settings.gradient_clip));
  metadata.training.seed = settings.seed;
  metadata.training.batch_windows = settings.batch_size;
  metadata.training.window_frames = settings.windows.frames;
  if (!history.empty()) {
    metadata.loss_history.terms.push_back("total");
    for (const NamedLoss& term : history.front().terms) metadata.loss_history.terms.push_back(term.name);
    for (const EpochRecord& record : history) {
      std::vector<double> values{record.total};
      for (const NamedLoss& term : record.terms) values.push_back(term.value);
      values.resize(metadata.loss_history.terms.size(), 0.0);
      metadata.loss_history.epochs.push_back(std::move(values));
    }
  }
  metadata.properties.emplace_back("tool", "motionstyle core/style training");
  metadata.properties.emplace_back("training_clips", std::to_string(data.training_files.size()));
  metadata.properties.emplace_back("held_out_clips", std::to_string(data.held_out_files.size()));
  if (settings.holdout_every > 0) metadata.properties.emplace_back("holdout_every", std::to_string(settings.holdout_every));
  metadata.properties.emplace_back("window_step", std::to_string(settings.windows.step));
  metadata.properties.emplace_back("nn_threads", std::to_string(nn::computePool().threadCount()));
  if (settings.augmentation.enabled()) metadata.properties.emplace_back("augmentation", describe(settings.augmentation));
  return metadata;
}

std::uint64_t dataFingerprint(const TrainingClips& data, const TrainingSettings& settings,
                              const std::vector<std::string>& extra) {
  std::vector<std::string> parts;
  for (std::size_t i = 0; i < data.clips.size(); ++i)
    parts.push_back(data.clips[i].file.string() + "#" + std::to_string(data.clips[i].frameCount()));
  parts.push_back("batch=" + std::to_string(settings.batch_size));
  parts.push_back("lr=" + std::to_string(settings.learning_rate));
  parts.push_back(std::string("schedule=") + scheduleName(settings.schedule));
  parts.push_back("clip=" + std::to_string(settings.gradient_clip));
  parts.push_back("seed=" + std::to_string(settings.seed));
  parts.push_back("window=" + std::to_string(settings.windows.frames) + "/" + std::to_string(settings.windows.step));
  if (settings.augmentation.enabled()) parts.push_back("augmentation=" + describe(settings.augmentation));
  parts.insert(parts.end(), extra.begin(), extra.end());
  return fingerprint(parts);
}

void saveCheckpoint(const TrainingSettings& settings, const std::string& network_bytes, nn::NetworkKind kind,
                    const nn::Adam<float>& optimiser, const std::vector<EpochRecord>& history,
                    std::uint64_t data_fingerprint) {
  TrainingState state;
  state.kind = kind;
  state.epochs_completed = history.empty() ? 0 : history.back().epoch;
  state.adam_steps = optimiser.stepCount();
  state.data_fingerprint = data_fingerprint;
  state.first_moments = optimiser.firstMoments();
  state.second_moments = optimiser.secondMoments();
  state.history = history;
  writeCheckpoint(settings.checkpointPath(), network_bytes, std::move(state), settings.checkpoint_durability);
}

int restoreFromState(const TrainingState& state, nn::NetworkKind kind, std::uint64_t data_fingerprint,
                     const std::filesystem::path& checkpoint, nn::Adam<float>& optimiser,
                     std::vector<EpochRecord>& history) {
  if (state.kind != kind) throw InputError(checkpoint.string(), 0, "the checkpoint is for the other network kind");
  if (state.data_fingerprint != data_fingerprint)
    throw InputError(checkpoint.string(), 0,
                     "the checkpoint was made with other data or settings (clips, batch, learning rate, seed, "
                     "windows or weights): resume with the same ones, or train without --resume");
  try {
    optimiser.restore(state.adam_steps, state.first_moments, state.second_moments);
  } catch (const std::invalid_argument& error) {
    throw InputError(checkpoint.string(), 0, std::string("the checkpoint's optimiser state does not fit: ") + error.what());
  }
  history = state.history;
  return state.epochs_completed + 1;
}

}  // namespace motionstyle::style
