#pragma once
// Network files: the trained loss network and per-style networks, with everything needed
// to use and to trust them. Binary, little-endian, versioned, CRC-protected; the byte-level
// specification is core/nn/NETWORK_FORMAT.md. Saved atomically (writeFileAtomically). Loading a
// truncated, corrupt, foreign, future-version or mismatched file throws InputError naming the file,
// never crashes and never allocates more than the file's own size justifies.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "nn/loss_network.h"
#include "nn/binary_io.h"
#include "nn/losses.h"
#include "nn/transformation_objective.h"
#include "nn/transformation_network.h"

namespace motionstyle::nn {

// Version 2 added the weight encoding (f32 or f16), version 3 the style targets of style files.
// Readers read 1 to 3; writers write 3.
constexpr std::uint32_t kNetworkFormatVersion = 3;
// The joint sets of the 66-value representation (feature_layout.h) this build reads: the 21 canonical
// joints in the reference proportions and, for content clips, the reference rig's girdle placement
// (features/proportions.h, features/rig_canonicalisation.h; what this build computes by default). Older
// sets are still described by `info`, but refused for use: the same joints in the reference proportions
// only, and in each clip's own proportions (networks trained before those steps).
inline constexpr std::string_view kRetargetedJointSetName = "canonical-21-reference-rig";
inline constexpr std::string_view kProportionsJointSetName = "canonical-21-reference-proportions";
inline constexpr std::string_view kCanonicalJointSetName = "canonical-21";

enum class NetworkKind : std::uint32_t { LossNetwork = 1, Style = 2 };

// The representation the network was trained on. A network only makes sense on frames built the same
// way: checkCompatible() compares.
struct RepresentationInfo {
  double fps = kDefaultFeatureFps;                          // frames per second of the frames
  std::string joint_set = std::string(kRetargetedJointSetName);
  double reference_body_height_cm = kReferenceSkeletalHeightCm;  // skeletal height characters are scaled to
  int feature_count = kFeatureCount;                        // values per frame
  bool operator==(const RepresentationInfo&) const = default;
};

// How the network was trained (informative; reproducibility).
struct TrainingConfig {
  int epochs = 0;
  double learning_rate = 1e-3;
  std::uint64_t seed = 0;
  int batch_windows = 16;    // windows per batch
  int window_frames = 240;   // frames per window
  LossWeights weights;       // style networks (eq. 10)
  double sparsity = kDefaultSparsity;   // loss network alpha (eq. 3)
  double dropout = kDefaultInputDropout;  // loss network input dropout
  bool operator==(const TrainingConfig&) const = default;
};

struct StyleClipRef {
  std::string name;          // e.g. the BVH file name
  std::string content_hash;  // contentHash() of the file's bytes (binary_io.h)
  bool operator==(const StyleClipRef&) const = default;
};

// Loss per epoch and term: epochs[e][i] is term terms[i] after epoch e.
struct LossHistory {
  std::vector<std::string> terms;
  std::vector<std::vector<double>> epochs;
  bool operator==(const LossHistory&) const = default;
};

struct NetworkMetadata {
  RepresentationInfo representation;
  TrainingConfig training;
  std::vector<StyleClipRef> style_clips;                       // style networks: the clip(s) of the style
  LossHistory loss_history;
  std::vector<std::pair<std::string, std::string>> properties;  // free-form: "created", "tool_version", ...
  bool operator==(const NetworkMetadata&) const = default;
};

struct LossNetworkModel {
  LossNetwork<float> network;
  FeatureStatistics normalisation;  // 66 + 66: x_n = (x - mean) / std
  NetworkMetadata metadata;
};

// The target of eq. 5 for the content clips of one label: Gram(L(S)) of its style clip S through the
// style network's own loss network (nn::styleGram), hidden x hidden.
struct StyleTarget {
  std::string label;  // content label ("walk", "run", ...); "" for the default (every other label)
  Mat<float> gram;
  bool operator==(const StyleTarget&) const = default;
};

// A style network is self-contained: it embeds the loss network it was trained against, which is also
// the one whose projection cleans its output (the two must not be mixed up), and its style targets, so
// that it can be retrained (on other content, against a loss network with the same encoder) without
// the style clips it was made from. Files before format 3 have no targets.
struct StyleModel {
  TransformationNetwork<float> transformation;
  LossNetwork<float> loss_network;
  FeatureStatistics normalisation;
  NetworkMetadata metadata;
  std::vector<StyleTarget> style_targets;
};

// The loss network a style network embeds, as a loss network model of its own: the network, the
// normalisation and the representation, and the sparsity and dropout it was trained with (what a warm
// start, the optimisation method or an adaptation needs of it).
LossNetworkModel embeddedLossNetwork(const StyleModel& model);

// Serialise to bytes (the exact file content, format kNetworkFormatVersion) / save atomically, the
// weights stored in `precision` (F16: half the size; metadata and statistics stay f64). Strings are
// written as safeText() (common/text_safety.h: a Latin-1 file name becomes U+FFFD, not an unreadable
// file). Throws std::invalid_argument when the model is internally inconsistent (e.g. normalisation of
// the wrong size), holds a number outside network_limits.h's bounds or, for F16, has a weight outside
// binary16's finite range (what the reader would refuse is never written); WriteError on I/O.
std::string serialiseLossNetwork(const LossNetworkModel& model, WeightPrecision precision = WeightPrecision::F32);
std::string serialiseStyleModel(const StyleModel& model, WeightPrecision precision = WeightPrecision::F32);
void saveLossNetwork(const LossNetworkModel& model, const std::filesystem::path& file,
                     WeightPrecision precision = WeightPrecision::F32);
void saveStyleModel(const StyleModel& model, const std::filesystem::path& file,
                    WeightPrecision precision = WeightPrecision::F32);

// The bytes a format-1 build wrote for this model (f32, no weight-encoding field). Training
// fingerprints hash these, so that checkpoints written before format 2 stay resumable; tests use it.
std::string serialiseLossNetworkFormat1(const LossNetworkModel& model);

// Parse bytes (source_name names them in errors) / load a file. InputError on anything wrong, incl.
// a file of the other kind, a feature count or joint set this build does not use, shapes that do
// not match the declared architecture, non-finite weights or statistics, numbers outside
// network_limits.h's bounds, and strings that are not valid UTF-8 or hold control characters. The
// message names the file and the field, and never echoes an unsafe string.
LossNetworkModel parseLossNetwork(std::string_view bytes, const std::string& source_name);
StyleModel parseStyleModel(std::string_view bytes, const std::string& source_name);
LossNetworkModel loadLossNetwork(const std::filesystem::path& file);
StyleModel loadStyleModel(const std::filesystem::path& file);

// The kind of a network file after full validation (for a CLI that accepts either).
NetworkKind networkFileKind(const std::filesystem::path& file);

// What a network file is, as stored (after full validation; InputError as for loading).
struct NetworkFileInfo {
  std::uint32_t format_version = kNetworkFormatVersion;
  NetworkKind kind = NetworkKind::LossNetwork;
  WeightPrecision precision = WeightPrecision::F32;  // format 1 is always F32
  std::uint64_t bytes = 0;                           // file size
};
NetworkFileInfo networkFileInfo(std::string_view bytes, const std::string& source_name);
NetworkFileInfo networkFileInfo(const std::filesystem::path& file);

// Throws InputError (naming `file`) listing every field of `actual` that differs from `expected`.
void checkCompatible(const RepresentationInfo& actual, const RepresentationInfo& expected,
                     const std::string& file);

// Human-readable summary (used by `motionstyle-cli info NET`).
std::string describe(const LossNetworkModel& model);
std::string describe(const StyleModel& model);
// Loads either kind and describes it, with its format version, weight precision and size (InputError
// as for loading).
std::string describeNetworkFile(const std::filesystem::path& file);

}  // namespace motionstyle::nn
