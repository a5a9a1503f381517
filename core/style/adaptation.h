#pragma once
// Adapting the loss network to a user's own clips ("adapt"): the loss network is fine-tuned on clips of
// the user's studio, actors and rigs (no labels needed), so that it reconstructs them, and so that the
// manifold projection keeps their content and the familiarity reading (familiarity.h) says so.
//
//   - Only the decoder learns by default (AdaptationSettings::train_encoder = false): the encoder, which
//     defines every content and style target (eq. 4-6), stays as it was, so every style network keeps
//     its style targets and can be retrained against the adapted network on the user's clips without
//     the style clip it was made from (style targets: nn::StyleModel::style_targets).
//   - Nothing is forgotten: clips of the original training data, when given (`replay`), are mixed in,
//     replay_ratio times the user's frames; every epoch sees all of the user's windows. Without them,
//     the network's reconstruction memory (`memory`, reconstruction_memory.h) stands in for them.
//   - Training as trainLossNetwork (training.h): a warm start from the given network, a checkpoint
//     every epoch, cancellation within a second (the last good checkpoint is kept), progress, and the
//     learning-rate schedule; deterministic for a seed and thread count.
// The adapted network records what it was adapted on (metadata properties "adapted_*": the loss network
// it came from, file names, clip and frame counts, replay counts, the date).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "nn/network_file.h"
#include "style/familiarity.h"
#include "style/motion_dataset.h"
#include "style/reconstruction_memory.h"
#include "style/training.h"

namespace motionstyle::style {

struct AdaptationSettings {
  int epochs = 200;
  double learning_rate = 5e-4;      // Adam, cosine decay over the run
  bool train_encoder = false;       // see the top of this file
  double replay_ratio = 1.0;        // replay frames per user frame (when replay clips are given)
  // The reconstruction memory's weight (AdaptationJob::memory): its clips count as memory_weight times
  // the user's frames. 10: the original clips kept as well as by mixing them in (docs/decisions.md).
  double memory_weight = 10.0;
  std::uint32_t seed = 1;
  std::filesystem::path output;     // the adapted network file (written at the end); may be empty
  std::filesystem::path checkpoint; // default: output + ".checkpoint"
  bool keep_checkpoint = false;     // as TrainingSettings::keep_checkpoint
  // As TrainingSettings::checkpoint_durability; the style stages' checkpoints too.
  FileDurability checkpoint_durability = FileDurability::Synced;

  void validate() const;  // std::invalid_argument naming the field
  std::filesystem::path checkpointPath() const;  // `checkpoint`, or output + ".checkpoint"
};

struct ClipFamiliarity {
  std::filesystem::path file;
  double before_cm = 0.0;  // the original network's familiarity figure (mean reconstruction error)
  double after_cm = 0.0;   // the adapted network's
};

struct AdaptationResult {
  TrainingStatus status = TrainingStatus::Completed;
  nn::LossNetworkModel model;            // the adapted network (when cancelled: after the last step)
  std::vector<ClipFamiliarity> clips;    // per user clip (Completed only)
  double mean_before_cm = 0.0;           // frame-weighted over the user's clips
  double mean_after_cm = 0.0;
  int replay_clips = 0;                  // replay clips mixed in
  std::string memory;                    // the reconstruction memory kept (its description); empty: none
  // What the adapted network must go on reconstructing (Completed, encoder kept): the memory kept,
  // merged with the clips it was adapted on as the adaptation weighed them (mergeMemories). Written
  // beside settings.output (memoryFileBeside) with the network, both or neither, so that adapting the
  // adapted network again keeps these clips too.
  std::optional<ReconstructionMemory> memory_after;
  std::filesystem::path memory_file;     // where memory_after was written; empty: not written
  double seconds = 0.0;
};

// Plain inputs of one adaptation.
struct AdaptationJob {
  nn::LossNetworkModel loss_network;       // the network to adapt (e.g. the shipped one)
  std::string loss_network_name;           // for the metadata ("loss_network", a file name)
  std::vector<MotionClip> clips;           // the user's clips (at least one frame each)
  std::vector<MotionClip> replay;          // clips of the original training data; may be empty
  // What the loss network must go on reconstructing (reconstruction_memory.h): the shipped network's
  // memory of its training data when the data itself is not at hand. Must match loss_network's encoder.
  std::optional<ReconstructionMemory> memory;
  AdaptationSettings settings;

  // Throws std::invalid_argument for empty clips, bad settings or a loss network that is not valid.
  void validate() const;
  AdaptationResult run(const TrainingCallbacks& callbacks = {}) const;
  // The replay clips mixed in: seeded from settings.seed, replay_ratio x the user's frames.
  std::vector<MotionClip> replayToMix() const;
};

// One action for the user (the app's Adapt tab, motionstyle-cli adapt --retrain): adapt the loss
// network, then retrain each chosen style network against it, warm-started, on the user's clips (and
// the replay clips) with the style targets the network stores (nn::StyleModel::style_targets).
// Progress comes through `callbacks` for every stage in turn; TrainingProgress::message names the
// stage ("adapting the loss network", "retraining elderly (1 of 2)"). Cancelling stops the stage in
// flight: the stages already done are in the result.
struct StyleToRetrain {
  std::string name;      // e.g. "elderly"
  nn::StyleModel model;  // must store style targets
};

constexpr int kDefaultStyleAdaptationEpochs = 30;

struct AdaptNetworksJob {
  AdaptationJob loss;                // the loss network stage (its clips and replay serve both stages)
  std::vector<StyleToRetrain> styles;
  int style_epochs = kDefaultStyleAdaptationEpochs;
  double style_learning_rate = 5e-4;
  std::filesystem::path scratch;     // folder for the style stages' checkpoints

  void validate() const;  // AdaptationJob::validate, and every style stores targets; invalid_argument
  struct Result {
    AdaptationResult loss;
    std::vector<StyleToRetrain> styles;  // retrained, against loss.model
    TrainingStatus status = TrainingStatus::Completed;
    double seconds = 0.0;
  };
  Result run(const TrainingCallbacks& callbacks = {}) const;
};

}  // namespace motionstyle::style
