// trainStyleNetwork: one transformation network T per style (eq. 4-10) against a frozen loss network.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "common/errors.h"
#include "nn/binary_io.h"
#include "style/cancellation.h"
#include "style/training.h"
#include "style/training_loop.h"
#include "style/training_state.h"

namespace motionstyle::style {
namespace {

// Windows of hidden units L(I) per content window, computed once: the content target of eq. 4 never
// changes while T trains (the biggest saving of the training loop after the GEMMs themselves).
nn::Mat<float> encodeAllWindows(const nn::LossNetwork<float>& loss_network, const WindowSet& windows,
                                const TrainingCallbacks& callbacks, std::chrono::steady_clock::time_point started) {
  const int pooled = nn::evenFrames(windows.frames) / 2;
  nn::Mat<float> hidden(loss_network.shape().hidden, static_cast<Eigen::Index>(windows.count()) * pooled);
  constexpr int kChunk = 8;
  for (int first = 0; first < windows.count(); first += kChunk) {
    throwIfCancelled(callbacks.cancel);
    if (callbacks.progress) {
      TrainingProgress progress;
      progress.phase = TrainingProgress::Phase::Loading;
      progress.message = "encoding content window " + std::to_string(first + 1) + " of " + std::to_string(windows.count());
      progress.elapsed_seconds = secondsSince(started);
      callbacks.progress(progress);
    }
    const int count = std::min(kChunk, windows.count() - first);
    hidden.middleCols(static_cast<Eigen::Index>(first) * pooled, static_cast<Eigen::Index>(count) * pooled) =
        nn::contentHidden(loss_network,
                          nn::Mat<float>(windows.values.middleCols(static_cast<Eigen::Index>(first) * windows.frames,
                                                                   static_cast<Eigen::Index>(count) * windows.frames)),
                          windows.frames);
  }
  return hidden;
}

bool sameEncoder(const nn::LossNetwork<float>& a, const nn::LossNetwork<float>& b) {
  return a.shape() == b.shape() && a.encoder.weight.value == b.encoder.weight.value &&
         a.encoder.bias.value == b.encoder.bias.value;
}

std::string gramHash(const nn::Mat<float>& gram) {
  return nn::contentHash(std::string_view(reinterpret_cast<const char*>(gram.data()),
                                          static_cast<std::size_t>(gram.size()) * sizeof(float)));
}

// The targets a network trained on `styles` stores: one per label of the pairing table, and the
// default ("") when there is one, so that pairTargets pairs as pairStyles did.
std::vector<nn::StyleTarget> targetsOf(const std::vector<StyleSource>& styles, const std::vector<nn::Mat<float>>& grams) {
  std::vector<nn::StyleTarget> targets;
  for (const auto& [label, style] : styleLabelTable(styles))
    if (!label.empty()) targets.push_back({label, grams[static_cast<std::size_t>(style)]});
  for (std::size_t i = 0; i < styles.size(); ++i)
    if (!styles[i].label) {
      targets.push_back({"", grams[i]});
      break;
    }
  return targets;
}

std::string fileHash(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return nn::contentHash(bytes.str());
}

std::vector<std::string> settingsParts(const StyleTrainingConfig& config, const std::vector<std::string>& style_hashes,
                                       const std::vector<int>& pairing, const nn::LossNetworkModel& loss) {
  std::vector<std::string> parts = {"style", "hidden=" + std::to_string(config.shape.hidden),
                                    "width=" + std::to_string(config.shape.width),
                                    "residual=" + std::to_string(config.shape.residual)};
  const nn::LossWeights& w = config.weights;
  for (double v : {w.content, w.style, w.foot, w.bone, w.trajectory}) parts.push_back(std::to_string(v));
  parts.insert(parts.end(), style_hashes.begin(), style_hashes.end());
  for (int p : pairing) parts.push_back(std::to_string(p));
  parts.push_back(nn::contentHash(nn::serialiseLossNetworkFormat1(nn::LossNetworkModel{loss.network, loss.normalisation, {}})));
  return parts;
}

}  // namespace

StyleTrainingResult trainStyleNetwork(const StyleTrainingConfig& config, const TrainingCallbacks& callbacks) {
  config.validate();
  const TrainingSettings& settings = config.settings;
  const auto started = std::chrono::steady_clock::now();
  StyleTrainingResult result;
  result.model.transformation = nn::TransformationNetwork<float>(config.shape);

  const nn::LossNetworkModel loss = config.loss_network_model
                                        ? *config.loss_network_model
                                        : loadCompatibleLossNetwork(config.loss_network, settings.dataset.features);
  const FeatureStatistics& statistics = loss.normalisation;

  // Style clips: every one must cover the loss network's filter (25 frames at 60 fps).
  const DatasetOptions style_options = styleClipOptions(settings.dataset, loss.network.shape().width);
  std::vector<MotionClip> style_clips;
  std::vector<std::string> style_hashes;
  for (const StyleSource& source : config.styles) {
    style_clips.push_back(loadMotionClip(source.file, style_options));
    style_hashes.push_back(fileHash(source.file));
  }

  // Without style clips: stored targets, given or taken from the network the run starts from.
  std::vector<nn::StyleTarget> stored = config.style_targets;
  nn::NetworkMetadata stored_metadata;  // the style clips the stored targets came from
  std::string stored_source = "the given style targets";
  if (config.styles.empty() && stored.empty()) {
    const nn::StyleModel initial =
        config.init_model ? *config.init_model : loadCompatibleStyleModel(settings.init, settings.dataset.features);
    stored_source = config.init_model ? std::string("the network to retrain") : settings.init.string();
    if (initial.style_targets.empty())
      throw InputError(stored_source, 0, "the network stores no style targets (made before format 3): give its style "
                                         "clips with --style");
    if (!sameEncoder(initial.loss_network, loss.network))
      throw InputError(stored_source, 0, "the network's style targets were computed by another encoder than this "
                                         "loss network's (adapt keeps the encoder unless --train-encoder): give the "
                                         "style clips with --style");
    stored = initial.style_targets;
    stored_metadata = initial.metadata;
  }
  for (const nn::StyleTarget& target : stored) style_hashes.push_back("stored:" + target.label + ":" + gramHash(target.gram));

  std::optional<TrainingClips> loaded =
      loadTrainingClips(config.content, config.content_clips, settings, callbacks, "content", started, result);
  if (!loaded) return result;
  const TrainingClips& data = *loaded;
  std::vector<std::string> labels;
  for (const MotionClip& clip : data.clips) labels.push_back(clip.labels.content);
  std::vector<std::string> target_names;  // per style clip or stored target, for the log
  if (!config.styles.empty()) {
    result.pairing = pairStyles(labels, config.styles);
    for (const StyleSource& source : config.styles) target_names.push_back(source.file.filename().string());
  } else {
    std::vector<std::string> target_labels;
    for (const nn::StyleTarget& target : stored) target_labels.push_back(target.label);
    result.pairing = pairTargets(labels, target_labels, stored_source);
    for (const std::string& label : target_labels) target_names.push_back("stored target '" + label + "'");
  }
  if (callbacks.log) {
    std::map<std::string, std::pair<int, int>> table;  // label -> (clips, style)
    for (std::size_t i = 0; i < labels.size(); ++i) {
      auto& entry = table[labels[i]];
      ++entry.first;
      entry.second = result.pairing[i];
    }
    for (const auto& [label, entry] : table)
      callbacks.log("pairing: " + (label.empty() ? std::string("(no label)") : label) + " (" +
                    std::to_string(entry.first) + " clips) -> " + target_names[static_cast<std::size_t>(entry.second)]);
  }

  // Targets computed once: style Gram matrices per style clip (or stored), L(I) per content window.
  std::vector<nn::Mat<float>> style_grams;
  for (const MotionClip& clip : style_clips) {
    style_grams.push_back(nn::styleGram(loss.network, statistics.normalized(clip.features.values)));
  }
  for (const nn::StyleTarget& target : stored) style_grams.push_back(target.gram);
  result.model.style_targets = config.styles.empty() ? stored : targetsOf(config.styles, style_grams);
  WindowSet windows = makeWindows(data.clips, statistics, settings.windows);
  nn::Mat<float> content_hidden;
  try {
    content_hidden = encodeAllWindows(loss.network, windows, callbacks, started);
  } catch (const OperationCancelled&) {
    markCancelledBeforeTraining(result, started);
    return result;
  }
  if (callbacks.log)
    callbacks.log(std::to_string(windows.count()) + " windows of " + std::to_string(windows.frames) + " frames");

  nn::StyleModel& model = result.model;
  model.loss_network = loss.network;
  model.normalisation = loss.normalisation;
  std::vector<EpochRecord> history;
  nn::Adam<float> optimiser(model.transformation.parameters(), settings.adamOptions());
  const std::uint64_t fingerprint = dataFingerprint(data, settings, settingsParts(config, style_hashes, result.pairing, loss));
  TrainedNetwork network;
  network.kind = nn::NetworkKind::Style;
  network.resume = [&](const std::string& network_bytes, const std::filesystem::path& checkpoint) {
    nn::StyleModel resumed = nn::parseStyleModel(network_bytes, checkpoint.string());
    if (!(resumed.transformation.shape() == config.shape))
      throw InputError(checkpoint.string(), 0, "the checkpoint's network has another shape");
    model.transformation = std::move(resumed.transformation);
  };
  if (config.init_model || !settings.init.empty())
    network.warm_start = [&] {
      nn::StyleModel initial =
          config.init_model ? *config.init_model : loadCompatibleStyleModel(settings.init, settings.dataset.features);
      if (!(initial.transformation.shape() == config.shape))
        throw InputError(settings.init.string(), 0, "the --init network has another shape than requested");
      model.transformation = std::move(initial.transformation);
      if (callbacks.log) callbacks.log("warm start from " + (config.init_model ? stored_source : settings.init.string()));
    };
  network.fresh = [&] { model.transformation.initialise(settings.seed); };
  network.parameters = [&] { return model.transformation.parameters(); };
  network.serialise = [&] { return nn::serialiseStyleModel(model); };
  network.save = [&](const std::filesystem::path& file) { nn::saveStyleModel(model, file); };
  if (callbacks.style_snapshot) network.snapshot = [&] { callbacks.style_snapshot(model); };
  LoopSetup setup = startTraining(network, settings, fingerprint, optimiser, history, callbacks, started);
  if (!config.init_model && settings.init.empty())  // fresh (a resumed fresh run keeps the same schedule)
    setup.minimum_steps_per_epoch = static_cast<int>((kFreshStyleMinimumSteps + settings.epochs - 1) / settings.epochs);

  nn::LossNetwork<float> loss_network = loss.network;  // forward caches are per instance
  const FeatureStatistics normalisation = loss.normalisation;
  const int frames = windows.frames;
  const int pooled = nn::evenFrames(frames) / 2;
  setup.window_count = windows.count();
  if (settings.augmentation.enabled())
    setup.begin_epoch = [&](int epoch) {
      windows = makeWindows(augmentedEpoch(data.clips, settings.augmentation, settings.seed, epoch, settings.dataset),
                            statistics, settings.windows);
      TrainingCallbacks quiet;  // re-encoding is part of the epoch: no "loading" progress mid-run
      quiet.cancel = callbacks.cancel;
      content_hidden = encodeAllWindows(loss.network, windows, quiet, started);
      return windows.count();
    };
  setup.micro_step = [&](const std::vector<int>& indices, std::mt19937&) {
    nn::StyleBatch<float> batch;
    batch.frames = frames;
    batch.content = gatherWindows(windows.values, frames, indices);
    batch.contacts = gatherWindows(windows.contacts, frames, indices);
    batch.content_hidden = gatherWindows(content_hidden, pooled, indices);
    batch.bone_lengths.resize(windows.bone_lengths.rows(), static_cast<Eigen::Index>(indices.size()));
    std::vector<std::size_t> gram_of_window;
    for (std::size_t i = 0; i < indices.size(); ++i) {
      batch.bone_lengths.col(static_cast<Eigen::Index>(i)) = windows.bone_lengths.col(indices[i]);
      const int clip = windows.clip_index[static_cast<std::size_t>(indices[i])];
      gram_of_window.push_back(static_cast<std::size_t>(result.pairing[static_cast<std::size_t>(clip)]));
    }
    // One shared target when every window has the same (a single style clip): no per-window copies.
    const bool shared = std::all_of(gram_of_window.begin(), gram_of_window.end(),
                                    [&](std::size_t g) { return g == gram_of_window.front(); });
    if (shared) gram_of_window.resize(1);
    for (std::size_t g : gram_of_window) batch.style_grams.push_back(style_grams[g]);
    const nn::ObjectiveTerms terms = nn::accumulateObjective(model.transformation, loss_network, batch, normalisation, config.weights);
    return StepLosses{terms.total,
                      {{"content", terms.content}, {"style", terms.style}, {"foot", terms.foot}, {"bone", terms.bone},
                       {"trajectory", terms.trajectory}}};
  };
  const auto metadata = [&](const std::vector<EpochRecord>& so_far) {
    nn::NetworkMetadata m = trainingMetadata(settings, so_far, data);
    m.training.weights = config.weights;
    m.training.sparsity = loss.metadata.training.sparsity;
    m.training.dropout = loss.metadata.training.dropout;
    for (std::size_t i = 0; i < config.styles.size(); ++i)
      m.style_clips.push_back({config.styles[i].file.filename().string(), style_hashes[i]});
    for (const auto& [label, style] : styleLabelTable(config.styles))
      m.properties.emplace_back("style_for_" + (label.empty() ? std::string("unlabelled") : label),
                                config.styles[static_cast<std::size_t>(style)].file.filename().string());
    if (config.styles.empty()) {  // trained from stored targets: the clips they came from
      m.style_clips = stored_metadata.style_clips;
      for (const auto& [key, value] : stored_metadata.properties)
        if (key.rfind("style_for_", 0) == 0) m.properties.emplace_back(key, value);
      m.properties.emplace_back("style_targets_from", std::filesystem::path(stored_source).filename().string());
    }
    return m;
  };
  network.set_metadata = [&](const std::vector<EpochRecord>& so_far) { model.metadata = metadata(so_far); };
  runTraining(network, setup, fingerprint, history, callbacks, result);
  return result;
}

}  // namespace motionstyle::style
