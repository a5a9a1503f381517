#pragma once
// The training API shared by the CLI (train-loss-network, train-style) and the GUI's worker thread.
//
//   trainLossNetwork:  the loss network L (eq. 1-3) on windows of a motion database.
//   trainStyleNetwork: one transformation network T per style (eq. 4-10) against a trained L.
//
// Both run on the calling thread (the GUI calls them from a worker) and use the nn compute pool for
// both cores. Data: 240-frame windows at 60 fps with a step of 120 (training_windows.h), shuffled
// every epoch with a seeded std::mt19937; float32 networks; Adam.
//
// Guarantees:
//   - Progress: `progress` is called after every optimisation step, when data loading advances and
//     when an epoch closes (with the epoch's mean losses). On this project's data a step takes well
//     under a second, so callers that draw (a terminal bar, a curve) should throttle themselves.
//   - Cancellation: `cancel` is polled between files while loading, and between MICRO-BATCHES inside
//     a step (each step is split into micro-batches of at most 4 windows whose gradients are combined
//     as the batch mean), so it takes effect well within 1 s. A cancelled run returns status Cancelled;
//     the step in flight is discarded; the checkpoint of the last completed epoch is left as it was;
//     no output file is written.
//   - Checkpoint: after every epoch the network and the optimiser state are written atomically to the
//     checkpoint path (a network file plus a ".state" sidecar, checkpoint.h). `resume` continues from
//     it and reproduces uninterrupted training exactly (same seed, thread count and data).
//   - Determinism: the same config (seed, data, batch) and the same nn thread count give bit-identical
//     networks. Per-epoch shuffles and dropout masks come from std::seed_seq{seed, epoch, purpose}.
//   - Divergence: a non-finite loss or weight stops training with TrainingDiverged; the last good
//     checkpoint is kept (nothing is written after the divergence).
// Errors: InputError for bad data (style/motion_dataset.h), std::invalid_argument for a bad config,
// WriteError when a checkpoint or the output cannot be written (the earlier files stay intact).

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "nn/adam.h"
#include "nn/network_file.h"
#include "style/augmentation.h"
#include "style/motion_dataset.h"
#include "style/style_pairing.h"
#include "style/training_windows.h"

namespace motionstyle::style {


struct NamedLoss {
  std::string name;  // "mse", "sparsity" (loss network); "content", "style", "foot", "bone", "trajectory"
  double value = 0;  // UNWEIGHTED term
};

struct TrainingProgress {
  enum class Phase { Loading, Training, EpochEnd };
  Phase phase = Phase::Loading;
  std::string message;             // e.g. "loading clip 12 of 40"; empty while training
  int epoch = 0;                   // 1-based epoch in progress (or just closed, for EpochEnd)
  int epochs = 0;                  // total epochs of the run
  int step = 0;                    // 1-based step within the epoch (EpochEnd: steps_per_epoch)
  int steps_per_epoch = 0;
  double total = 0;                // weighted total loss of the step (EpochEnd: mean over the epoch)
  std::vector<NamedLoss> terms;    // the step's unweighted terms (EpochEnd: means over the epoch)
  double elapsed_seconds = 0;      // since this call of trainX started
  double eta_seconds = -1;         // estimated remaining seconds, -1 when unknown (first step)
};

struct EpochRecord {
  int epoch = 0;  // 1-based
  double total = 0;
  std::vector<NamedLoss> terms;  // means over the epoch's steps
  double seconds = 0;            // wall time of the epoch
};

struct TrainingCallbacks {
  std::function<void(const TrainingProgress&)> progress;  // may be empty
  std::function<void(const std::string&)> log;            // notes and warnings (skipped files, pairing)
  const std::atomic<bool>* cancel = nullptr;               // set to true from any thread to stop
  // After every epoch's checkpoint, a copy of the model so far (the GUI's live preview). May be empty.
  std::function<void(const nn::LossNetworkModel&)> loss_network_snapshot;
  std::function<void(const nn::StyleModel&)> style_snapshot;
};

enum class TrainingStatus { Completed, Cancelled };

// How Adam's learning rate moves over a run. Cosine decays it from learning_rate to
// kFinalLearningRateFraction x learning_rate along half a cosine over all the run's steps (epochs x
// steps per epoch, resumed epochs included), so that training ends at a small rate instead of
// wherever a late loss spike left it. Cosine also warms up: the rate rises linearly over the first
// kWarmupSteps steps (at most a tenth of the run), because Adam's first steps move every weight by about
// the full rate whatever its gradient (the runs behind both: docs/decisions.md).
enum class LearningRateSchedule { Constant, Cosine };
constexpr double kFinalLearningRateFraction = 0.01;
constexpr long kWarmupSteps = 100;

// The learning rate of (0-based) step `step` of `total_steps` under `schedule`.
double scheduledLearningRate(LearningRateSchedule schedule, double learning_rate, long step, long total_steps);
const char* scheduleName(LearningRateSchedule schedule);  // "constant", "cosine"

// What every training run shares.
struct TrainingSettings {
  int epochs = 100;
  int batch_size = 16;            // windows per step
  double learning_rate = 1e-3;    // Adam, at the start of the run
  LearningRateSchedule schedule = LearningRateSchedule::Cosine;
  // Adam's outlier clipping (nn::AdamOptions::gradient_clip): a batch whose gradient is more than this
  // many times its expected norm is scaled down to it. 0 = off.
  double gradient_clip = 3.0;
  std::uint32_t seed = 1;
  // Total nn threads (both cores by default). 0 = the compute pool as it is; any other value must equal
  // nn::computePool().threadCount() (the pool is process-wide: the CLI sets MOTIONSTYLE_NN_THREADS
  // before first use), else std::invalid_argument.
  int threads = 0;
  std::filesystem::path output;      // the trained network file, written atomically at the end
  std::filesystem::path checkpoint;  // default: output + ".checkpoint"
  // false: a completed run that wrote `output` removes its checkpoint (the network file and its .state
  // sidecar, megabytes the user did not ask for); a cancelled or failed run always keeps it.
  bool keep_checkpoint = false;
  // Unsynced: each checkpoint is still swapped in atomically (a reader never sees half of one) but not
  // fsync'ed, so a power cut may lose it. For checkpoints no later boot reads (the app's, in its
  // temporary folder): a cancel waits for the write in flight, and a CI run's close during training
  // once took 1.7 s, most likely waiting on an fsync (docs/decisions.md).
  FileDurability checkpoint_durability = FileDurability::Synced;
  bool resume = false;               // continue from `checkpoint` (its epoch count must be < epochs)
  std::filesystem::path init;        // warm start from this network file (not with resume)
  WindowOptions windows;
  DatasetOptions dataset;
  int holdout_every = 0;             // splitHoldout(): every N-th file is kept out of training
  // Every epoch trains on a fresh augmented copy of each clip (augmentation.h); off = the clips as
  // loaded. Training clips then keep their Motion in memory.
  AugmentationOptions augmentation;

  std::filesystem::path checkpointPath() const;
  void validate() const;  // std::invalid_argument naming the bad field
  nn::AdamOptions adamOptions() const;  // learning_rate (before the schedule) and gradient_clip
};

struct TrainingResult {
  TrainingStatus status = TrainingStatus::Completed;
  int epochs_completed = 0;           // including resumed ones
  std::vector<EpochRecord> history;   // every completed epoch, resumed ones included
  std::vector<std::filesystem::path> training_files;
  std::vector<std::filesystem::path> held_out_files;
  double seconds = 0;
};

// ---- Loss network -------------------------------------------------------------------------------

struct ReconstructionMemory;  // reconstruction_memory.h

struct LossNetworkTrainingConfig {
  TrainingSettings settings;
  // Folders and/or files (ignored when `clips` is not empty), featurised without rig canonicalisation:
  // the loss network learns motion as captured (features/rig_canonicalisation.h).
  std::vector<std::filesystem::path> data;
  std::vector<MotionClip> clips;            // preloaded clips (the GUI's library)
  nn::LossNetworkShape shape;
  double sparsity = nn::kDefaultSparsity;       // alpha of eq. 3 (mean |w|)
  double dropout = nn::kDefaultInputDropout;    // input dropout rate in [0, 1)
  double foot_weight = 0.0;  // eq. 7 on the reconstruction (nn::ReconstructionFootTerm), per cm^2
  // Warm start from a model in memory (wins over settings.init): its weights and normalisation.
  std::optional<nn::LossNetworkModel> init_model;
  // false: only the decoder (eq. 2's W~0) learns; the encoder (W0, b0), and with it every content and
  // style target computed through it, stays as it was (adaptation.h).
  bool train_encoder = true;
  // What the network must go on reconstructing (reconstruction_memory.h): memory_weight * E(W~0) added
  // to the loss, the memory's clips as if mixed in memory_weight times the training clips' frames.
  // Needs train_encoder false (the memory holds the encoder's hidden units) and a matching encoder.
  const ReconstructionMemory* memory = nullptr;
  double memory_weight = 0.0;

  void validate() const;
};

struct LossNetworkTrainingResult : TrainingResult {
  // The trained network with its normalisation (computed over the training clips) and metadata; when
  // cancelled, the weights after the last completed step (the checkpoint file holds the last epoch's).
  nn::LossNetworkModel model;
};

LossNetworkTrainingResult trainLossNetwork(const LossNetworkTrainingConfig& config,
                                           const TrainingCallbacks& callbacks = {});

// ---- Transformation network ---------------------------------------------------------------------

// A style network's epochs. Full: the shipped networks' training. Quick: a usable style in seconds
// (the same held-out style ratio within a few hundredths, a tenth of the time; fewer than 5 epochs end
// inside the learning-rate warm-up and barely style; figures in docs/decisions.md).
constexpr int kFullStyleEpochs = 100;
constexpr int kQuickStyleEpochs = 6;
// A fresh style network (no warm start) takes at least this many optimisation steps over its run, its
// epochs passing over a small training set again: the quick style's steps over the shipped content
// (6 epochs of 17). One short clip gave one step an epoch, six in all, and a network that destroyed
// the motion (docs/decisions.md, "A quick style from one clip of content").
constexpr long kFreshStyleMinimumSteps = 100;

struct StyleTrainingConfig {
  TrainingSettings settings;
  std::filesystem::path loss_network;        // the loss network file (with its normalisation)
  std::optional<nn::LossNetworkModel> loss_network_model;  // preloaded loss network (wins over the path)
  std::vector<std::filesystem::path> content;  // content folders/files (ignored when content_clips set)
  std::vector<MotionClip> content_clips;       // preloaded content
  std::vector<StyleSource> styles;             // style clips and their pairing (style_pairing.h)
  // Without style clips: these stored targets (pairTargets), else those of the settings.init network,
  // whose loss network must then have the same encoder as this run's (adaptation.h).
  std::vector<nn::StyleTarget> style_targets;
  // Warm start from a network in memory (wins over settings.init): its transformation network.
  std::optional<nn::StyleModel> init_model;
  nn::LossWeights weights;                     // content 1, style 100, foot/bone/trajectory 0.01
  nn::TransformationShape shape;

  void validate() const;
};

struct StyleTrainingResult : TrainingResult {
  nn::StyleModel model;      // transformation + the loss network it was trained against + normalisation
  std::vector<int> pairing;  // per training clip: index into config.styles (or the stored targets)
};

// The representation this build's features use (fps from the options, 21 canonical joints, the
// reference skeletal height, 66 values): written into network files and checked when loading them.
nn::RepresentationInfo currentRepresentation(const FeatureOptions& options = {});

// Loads a network file and checks it was made for currentRepresentation(options): InputError naming the
// file otherwise (a network for a different representation).
nn::LossNetworkModel loadCompatibleLossNetwork(const std::filesystem::path& file, const FeatureOptions& options = {});
nn::StyleModel loadCompatibleStyleModel(const std::filesystem::path& file, const FeatureOptions& options = {});


StyleTrainingResult trainStyleNetwork(const StyleTrainingConfig& config, const TrainingCallbacks& callbacks = {});

}  // namespace motionstyle::style
