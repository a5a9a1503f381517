#pragma once
// The epoch/step loop shared by trainLossNetwork and trainStyleNetwork (internal to core/style):
// shuffling, batches split into micro-batches, gradient averaging, the optimiser step, divergence and
// cancellation checks, progress, and the end-of-epoch hook (checkpoint).

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include "nn/tensor.h"
#include "style/training.h"
#include "style/training_state.h"

namespace motionstyle::style {

// Windows per micro-batch: larger batches are split so that the cancellation flag is seen often and
// memory stays bounded. 16 x 240 frames is one default step, ~50-80 ms on two cores with the spectral
// convolutions (tests/bench/nn), so cancellation still takes effect within ~0.1 s; smaller
// micro-batches made the per-frequency products too small to run efficiently (4 windows: 25 segments
// per product) and repeated the kernel-gradient transforms. The step's gradient is the window-weighted
// mean of the micro-batch gradients.
constexpr int kMicroBatchWindows = 16;

// A generator seeded from (seed, epoch, purpose) with std::seed_seq, whose algorithm the standard fixes:
// an epoch's shuffle and dropout do not depend on earlier epochs, so resuming reproduces them.
std::mt19937 epochGenerator(std::uint32_t seed, int epoch, std::uint32_t purpose);

// Fisher-Yates over 0..count-1 with draws straight from the generator (std::shuffle's algorithm is
// library-specific).
std::vector<int> shuffledIndices(int count, std::mt19937& rng);

// Sums fraction * grad over micro-batches, then hands the total back to the parameters.
class GradientAccumulator {
 public:
  explicit GradientAccumulator(std::vector<nn::Parameter<float>*> parameters);
  void begin();                  // zero the sum and the parameters' gradients
  void add(float fraction);      // sum += fraction * grad; grad = 0
  void finish();                 // grad = sum
 private:
  std::vector<nn::Parameter<float>*> parameters_;
  std::vector<nn::Mat<float>> sum_;
};

bool parametersFinite(const std::vector<nn::Parameter<float>*>& parameters);

struct StepLosses {
  double total = 0;
  std::vector<NamedLoss> terms;
};

struct LoopSetup {
  const TrainingSettings* settings = nullptr;
  int window_count = 0;  // windows per epoch (the first epoch's when begin_epoch changes it)
  int first_epoch = 1;  // 1-based; > 1 when resuming
  // An epoch takes at least this many steps: when its windows give fewer, they are passed over again,
  // reshuffled (a fresh style network on one short clip: style_training.cpp).
  int minimum_steps_per_epoch = 1;
  std::vector<nn::Parameter<float>*> parameters;
  nn::Adam<float>* optimiser = nullptr;
  // Adds the gradient of the loss over `windows` (one micro-batch) into the parameters' gradients
  // (unscaled) and returns its unweighted terms and weighted total. `rng` is the epoch's generator for
  // stochastic layers (dropout).
  std::function<StepLosses(const std::vector<int>& windows, std::mt19937& rng)> micro_step;
  // Optional: called before each epoch's first step (augmentation: a fresh window set); returns that
  // epoch's window count, which micro_step's indices then refer to.
  std::function<int(int epoch)> begin_epoch;
  // Called after each completed epoch (history already appended): checkpoint, snapshot.
  std::function<void(const std::vector<EpochRecord>& history)> end_epoch;
  std::chrono::steady_clock::time_point started;
};

// Runs epochs first_epoch..settings->epochs. Returns Completed or Cancelled; throws TrainingDiverged.
TrainingStatus runTrainingLoop(const LoopSetup& setup, std::vector<EpochRecord>& history,
                               const TrainingCallbacks& callbacks);

// runTrainingLoop, then the end both trainers share: the result's status, history and epoch count.
void runTrainingLoop(const LoopSetup& setup, std::vector<EpochRecord>& history, const TrainingCallbacks& callbacks,
                     TrainingResult& result);

// The network a run trains, as the steps both trainers share need it. Taking a network over (each
// throws InputError on a network of another shape):
//   RESUME     (settings.resume): resume(the checkpoint's network bytes, its path), then the optimiser's
//              state and the history are restored (restoreFromState), "resuming after epoch N" logged;
//   WARM START (warm_start set): warm_start() takes an earlier network's weights;
//   FRESH      otherwise: fresh() initialises.
// Its file: set_metadata(history so far), serialise() for checkpoints, save(settings.output) at the end,
// snapshot() after each epoch (optional). One shape, so that the loss network and the style network
// start, checkpoint and finish the same way.
struct TrainedNetwork {
  nn::NetworkKind kind = nn::NetworkKind::LossNetwork;
  std::function<void(const std::string& network_bytes, const std::filesystem::path& checkpoint)> resume;
  std::function<void()> warm_start;  // empty: no earlier network to start from
  std::function<void()> fresh;
  std::function<std::vector<nn::Parameter<float>*>()> parameters;  // the trained ones, once taken over
  std::function<void(const std::vector<EpochRecord>& history)> set_metadata;
  std::function<std::string()> serialise;
  std::function<void(const std::filesystem::path& file)> save;
  std::function<void()> snapshot;
};

// Takes the network over (resume, warm start or fresh, above), makes `optimiser` a new Adam on its
// parameters (restored when resuming) and returns the loop's setup with settings, first epoch,
// parameters, optimiser and start time filled in; the caller adds the windows and the steps.
LoopSetup startTraining(const TrainedNetwork& network, const TrainingSettings& settings, std::uint64_t data_fingerprint,
                        nn::Adam<float>& optimiser, std::vector<EpochRecord>& history,
                        const TrainingCallbacks& callbacks, std::chrono::steady_clock::time_point started);

// Runs the loop with a checkpoint (and snapshot) after each epoch, then sets the final metadata; once
// Completed, saves to settings.output (when set) and removes the checkpoint unless kept; the time spent.
void runTraining(const TrainedNetwork& network, LoopSetup setup, std::uint64_t data_fingerprint,
                 std::vector<EpochRecord>& history, const TrainingCallbacks& callbacks, TrainingResult& result);

// A run cancelled before its first step (while loading data or encoding content): status Cancelled,
// the time spent. Nothing was trained or written.
void markCancelledBeforeTraining(TrainingResult& result, std::chrono::steady_clock::time_point started);

double secondsSince(std::chrono::steady_clock::time_point start);

// Loads `inputs` (or takes `preloaded`), applies the hold-out split and reports loading progress and
// skipped files through the callbacks. `what` names the data in messages ("training", "content").
struct TrainingClips {
  std::vector<MotionClip> clips;
  std::vector<std::filesystem::path> training_files;
  std::vector<std::filesystem::path> held_out_files;
};
// The result's training and held-out file lists are filled in; cancelled while loading, it returns
// std::nullopt with the result marked as markCancelledBeforeTraining does.
std::optional<TrainingClips> loadTrainingClips(const std::vector<std::filesystem::path>& inputs,
                                               const std::vector<MotionClip>& preloaded,
                                               const TrainingSettings& settings, const TrainingCallbacks& callbacks,
                                               const std::string& what, std::chrono::steady_clock::time_point started,
                                               TrainingResult& result);

// Metadata shared by both network kinds: representation, training settings, loss history, properties.
nn::NetworkMetadata trainingMetadata(const TrainingSettings& settings, const std::vector<EpochRecord>& history,
                                     const TrainingClips& data);

// The fingerprint of the data and settings a checkpoint must match to be resumed.
std::uint64_t dataFingerprint(const TrainingClips& data, const TrainingSettings& settings,
                              const std::vector<std::string>& extra);

// Writes the checkpoint (network bytes + state) and logs where.
void saveCheckpoint(const TrainingSettings& settings, const std::string& network_bytes, nn::NetworkKind kind,
                    const nn::Adam<float>& optimiser, const std::vector<EpochRecord>& history,
                    std::uint64_t data_fingerprint);

// Restores the optimiser and history from a checkpoint state, after checking kind and fingerprint.
// Returns the first epoch to run.
int restoreFromState(const TrainingState& state, nn::NetworkKind kind, std::uint64_t data_fingerprint,
                     const std::filesystem::path& checkpoint, nn::Adam<float>& optimiser,
                     std::vector<EpochRecord>& history);

}  // namespace motionstyle::style
