#pragma once
// Reconstruction memory: what a loss network's decoder must go on reconstructing, kept without the
// clips it learnt from, so that adapting it to a user's clips ("adapt", adaptation.h) forgets nothing
// even where the original data cannot be shipped (the Bandai licence: networks may ship, data not).
//
// With the encoder kept (adaptation trains the decoder W~0 alone), the decoder's reconstruction error
// over any set of clips is a quadratic in its weights. Stack the K taps a decoded frame t reads,
// z(t) = [d(t - c); ...; d(t + K - 1 - c)] with d = AverageDepool2(H) - b0 (hidden units), c = K / 2,
// and W = [W_0 ... W_K-1] (features x K*hidden, tap-major as the decoder stores it):
//   E(W) = mean_t,f (W z(t) - x(t))_f^2 = (tr(W S W^T) - 2 tr(W P) + q) / F
//   dE/dW = 2 (W S - P^T) / F
// S = mean_t z z^T, P = mean_t z x^T, q = mean_t |x|^2, F features, x the normalised frames. S is
// kept as its lags, C(m) = mean_s d(s) d(s + m)^T for m = 0..K-1 (S's block (l, k) is C(k - l), or
// C(l - k)^T above the diagonal): per clip the pairs a window edge cuts are left out, a K / frames
// share of each clip's terms. Why this rather than a pull toward the old weights: it weighs each
// weight by what the original clips ask of it, as mixing them back in does (ten CMU clips adapted:
// the Bandai held-out clips 0.48 -> 0.46 cm, the CMU ones 1.20 -> 0.73), where a pull toward W~0 that
// kept Bandai at 0.55 left the CMU clips at 1.02 (docs/decisions.md, "Adapting without forgetting").

#include <Eigen/Core>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "nn/binary_io.h"
#include "nn/network_file.h"
#include "style/motion_dataset.h"

namespace motionstyle::style {

struct ReconstructionMemory {
  int features = 0, hidden = 0, width = 0;  // the loss network's shape
  std::vector<Eigen::MatrixXf> lags;        // C(0..width-1), hidden x hidden each (float: the networks' precision)
  Eigen::MatrixXd cross;                    // P: width*hidden x features
  double squared_norm = 0.0;                // q
  double frames = 0.0;                      // frames the means are over
  int clips = 0;
  // encoderFingerprint() of the loss network the memory was made with: the hidden units d depend on
  // its encoder and normalisation only, so an adapted network (decoder changed) still matches.
  std::uint64_t encoder_fingerprint = 0;
  std::string description;                  // what it remembers, e.g. "1220 Bandai clips"

  // Throws std::invalid_argument naming the first inconsistency (shapes, non-finite values, no frames).
  void validate() const;
  // Whether `model`'s shape and encoderFingerprint are the memory's.
  bool fits(const nn::LossNetworkModel& model) const;
  // Throws std::invalid_argument naming `memory_name` unless it fits(model).
  void requireMatches(const nn::LossNetworkModel& model, const std::string& memory_name) const;
};

// FNV-1a over the loss network's shape, encoder weights and bias and normalisation.
std::uint64_t encoderFingerprint(const nn::LossNetworkModel& model);

// The memory of `clips` (their features as they are: the caller loads them as the network was trained,
// without rig canonicalisation) through `model`. Throws std::invalid_argument when there is no frame;
// OperationCancelled (cancellation.h) when `cancel` is set between clips.
ReconstructionMemory rememberReconstruction(const nn::LossNetworkModel& model, const std::vector<MotionClip>& clips,
                                            std::string description, const std::atomic<bool>* cancel = nullptr);

// What a network adapted with `kept` must go on reconstructing: (kept_weight * kept + added_weight *
// added) / (kept_weight + added_weight), term by term, the objective the adaptation minimised (its
// clips counted once, the memory kept_weight times). Frames and clips add up. Throws
// std::invalid_argument unless both are valid, of one shape and one encoder, and the weights > 0.
ReconstructionMemory mergeMemories(const ReconstructionMemory& kept, double kept_weight, const ReconstructionMemory& added,
                                   double added_weight, std::string description);

// E(W) and, when `gradient` is not null, dE/dW into it (features x width*hidden). decoder_weight: the
// decoder's W~0. Throws std::invalid_argument for a weight of another shape.
double memoryError(const ReconstructionMemory& memory, const Eigen::MatrixXf& decoder_weight,
                   Eigen::MatrixXf* gradient = nullptr);

// The memory file that goes with a network file: network.net -> network.memory.
std::filesystem::path memoryFileBeside(const std::filesystem::path& network_file);

// The memory that fits `model` (requireMatches), looked for beside its file (memoryFileBeside), then the shipped loss network's (common/resource_paths.h); nullopt when none fits or
// can be read. An adapted network keeps its encoder, so the memory of the one it came from still fits.
std::optional<ReconstructionMemory> findMatchingMemory(const nn::LossNetworkModel& model,
                                                       const std::filesystem::path& network_file);

// The file (written atomically): "MSRMEMORY" format 1, little-endian (nn/binary_io.h), the values in
// `precision` (f16 halves the file; the shipped memory uses it), a CRC-32 at the end.
void saveReconstructionMemory(const ReconstructionMemory& memory, const std::filesystem::path& file,
                              nn::WeightPrecision precision = nn::WeightPrecision::F32);
// The file's bytes (for writing it together with another file: AtomicFileBatch).
std::string serialiseReconstructionMemory(const ReconstructionMemory& memory,
                                          nn::WeightPrecision precision = nn::WeightPrecision::F32);
// The same in f16 (half the size: the shipped memory's figures do not move), or in f32 where a value
// is beyond f16's range.
std::string serialiseReconstructionMemoryCompactly(const ReconstructionMemory& memory);
// Throws InputError naming the file for a file that is not one, is cut short or fails validate().
ReconstructionMemory loadReconstructionMemory(const std::filesystem::path& file);

}  // namespace motionstyle::style
