#include "style/reconstruction_memory.h"

#include <cmath>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "common/resource_paths.h"
#include "nn/binary_io.h"
#include "nn/compute_pool.h"
#include "nn/layers.h"
#include "style/cancellation.h"

namespace motionstyle::style {
namespace {

constexpr std::string_view kMagic = "MSRMEMORY";
constexpr std::uint32_t kFormat = 1;
constexpr std::uintmax_t kMaxFileBytes = 1u << 30;

void mixBytes(std::uint64_t& hash, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 1099511628211ull;
  }
}

// The sums over one clip (the means' numerators).
struct ClipSums {
  std::vector<Eigen::MatrixXd> lags;
  Eigen::MatrixXd cross;
  double squared_norm = 0.0, frames = 0.0;
};

void addClip(const nn::LossNetworkModel& model, const MotionClip& clip, ClipSums& sums) {
  const nn::LossNetwork<float>& network = model.network;
  const int width = network.shape().width, hidden = network.shape().hidden, centre = width / 2;
  nn::Mat<float> x = model.normalisation.normalized(clip.features.values);
  const int frames = static_cast<int>(x.cols());
  nn::Mat<float> depooled = nn::AverageDepool2<float>::apply(network.encode(x, frames));
  depooled.colwise() -= network.encoder.bias.value.col(0);
  const int n = static_cast<int>(depooled.cols());  // frames rounded up to even: the last one repeated
  if (n != frames) {
    x.conservativeResize(Eigen::NoChange, n);
    x.col(n - 1) = x.col(n - 2);
  }
  for (int m = 0; m < width && m < n; ++m)
    sums.lags[static_cast<std::size_t>(m)] +=
        (depooled.leftCols(n - m) * depooled.rightCols(n - m).transpose()).cast<double>();
  for (int k = 0; k < width; ++k) {
    // Frame t reads d(t + k - centre): t in [max(0, centre - k), min(n, n + centre - k)).
    const int first = std::max(0, centre - k), end = std::min(n, n + centre - k);
    if (end <= first) continue;
    sums.cross.middleRows(static_cast<Eigen::Index>(k) * hidden, hidden) +=
        (depooled.middleCols(first + k - centre, end - first) * x.middleCols(first, end - first).transpose())
            .cast<double>();
  }
  sums.squared_norm += static_cast<double>(x.squaredNorm());
  sums.frames += n;
}

}  // namespace

std::uint64_t encoderFingerprint(const nn::LossNetworkModel& model) {
  std::uint64_t hash = 14695981039346656037ull;
  const nn::LossNetworkShape& shape = model.network.shape();
  const int dims[3] = {shape.features, shape.hidden, shape.width};
  mixBytes(hash, dims, sizeof dims);
  const nn::Mat<float>& weight = model.network.encoder.weight.value;
  const nn::Mat<float>& bias = model.network.encoder.bias.value;
  mixBytes(hash, weight.data(), sizeof(float) * static_cast<std::size_t>(weight.size()));
  mixBytes(hash, bias.data(), sizeof(float) * static_cast<std::size_t>(bias.size()));
  mixBytes(hash, model.normalisation.mean.data(), sizeof(double) * static_cast<std::size_t>(model.normalisation.mean.size()));
  mixBytes(hash, model.normalisation.std.data(), sizeof(double) * static_cast<std::size_t>(model.normalisation.std.size()));
  return hash;
}

void ReconstructionMemory::validate() const {
  if (features < 1 || hidden < 1 || width < 1 || hidden > 4096 || width > 255 || features > 4096)
    throw std::invalid_argument("reconstruction memory: its shape is not a loss network's");
  if (static_cast<int>(lags.size()) != width) throw std::invalid_argument("reconstruction memory: one lag per tap expected");
  for (const Eigen::MatrixXf& lag : lags)
    if (lag.rows() != hidden || lag.cols() != hidden || !lag.allFinite())
      throw std::invalid_argument("reconstruction memory: a lag matrix is not hidden x hidden and finite");
  if (cross.rows() != static_cast<Eigen::Index>(width) * hidden || cross.cols() != features || !cross.allFinite())
    throw std::invalid_argument("reconstruction memory: the cross moments are not width*hidden x features and finite");
  if (!(frames >= 1.0) || !std::isfinite(frames) || !(squared_norm >= 0.0) || !std::isfinite(squared_norm) || clips < 1)
    throw std::invalid_argument("reconstruction memory: no frames, or its totals are not finite");
}

bool ReconstructionMemory::fits(const nn::LossNetworkModel& model) const {
  const nn::LossNetworkShape& shape = model.network.shape();
  return shape.features == features && shape.hidden == hidden && shape.width == width &&
         encoderFingerprint(model) == encoder_fingerprint;
}

void ReconstructionMemory::requireMatches(const nn::LossNetworkModel& model, const std::string& memory_name) const {
  if (!fits(model))
    throw std::invalid_argument(memory_name + " was made with another loss network (its encoder or normalisation differ)");
}

ReconstructionMemory rememberReconstruction(const nn::LossNetworkModel& model, const std::vector<MotionClip>& clips,
                                            std::string description, const std::atomic<bool>* cancel) {
  const nn::LossNetworkShape& shape = model.network.shape();
  ClipSums sums;
  sums.lags.assign(static_cast<std::size_t>(shape.width), Eigen::MatrixXd::Zero(shape.hidden, shape.hidden));
  sums.cross = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(shape.width) * shape.hidden, shape.features);
  int counted = 0;
  for (const MotionClip& clip : clips) {
    throwIfCancelled(cancel);
    if (clip.frameCount() < 1) continue;
    if (clip.features.values.rows() != shape.features || !clip.features.values.allFinite())
      throw InputError(clip.file.string(), 0, "the clip's features do not fit the loss network or are not finite");
    addClip(model, clip, sums);
    ++counted;
  }
  if (counted == 0) throw std::invalid_argument("reconstruction memory: no clip with frames to remember");
  ReconstructionMemory memory;
  memory.features = shape.features;
  memory.hidden = shape.hidden;
  memory.width = shape.width;
  for (Eigen::MatrixXd& lag : sums.lags) memory.lags.push_back((lag / sums.frames).cast<float>());
  memory.cross = sums.cross / sums.frames;
  memory.squared_norm = sums.squared_norm / sums.frames;
  memory.frames = sums.frames;
  memory.clips = counted;
  memory.encoder_fingerprint = encoderFingerprint(model);
  memory.description = std::move(description);
  return memory;
}

double memoryError(const ReconstructionMemory& memory, const Eigen::MatrixXf& decoder_weight, Eigen::MatrixXf* gradient) {
  const int hidden = memory.hidden, width = memory.width;
  if (decoder_weight.rows() != memory.features || decoder_weight.cols() != static_cast<Eigen::Index>(width) * hidden)
    throw std::invalid_argument("memoryError: the decoder weight is not features x width*hidden");
  const Eigen::MatrixXf& weight = decoder_weight;
  // (W S)_k = sum_l W_l S_lk, S_lk = C(k - l) for l <= k, C(l - k)^T for l > k: tap k's products on the pool.
  Eigen::MatrixXf ws = Eigen::MatrixXf::Zero(weight.rows(), weight.cols());
  nn::parallelItems(width, static_cast<long>(width) * hidden * hidden, [&](int first, int end) {
    for (int k = first; k < end; ++k) {
      auto out = ws.middleCols(static_cast<Eigen::Index>(k) * hidden, hidden);
      for (int l = 0; l < width; ++l) {
        const auto w_l = weight.middleCols(static_cast<Eigen::Index>(l) * hidden, hidden);
        if (l <= k) out.noalias() += w_l * memory.lags[static_cast<std::size_t>(k - l)];
        else out.noalias() += w_l * memory.lags[static_cast<std::size_t>(l - k)].transpose();
      }
    }
  });
  const double quadratic = (ws.cast<double>().array() * weight.cast<double>().array()).sum();  // tr(W S W^T)
  const double linear = (weight.cast<double>().transpose().array() * memory.cross.array()).sum();  // tr(W P)
  const double features = memory.features;
  if (gradient != nullptr) *gradient = ((2.0 / features) * (ws.cast<double>() - memory.cross.transpose())).cast<float>();
  return (quadratic - 2.0 * linear + memory.squared_norm) / features;
}

std::filesystem::path memoryFileBeside(const std::filesystem::path& network_file) {
  std::filesystem::path beside = network_file;
  beside.replace_extension(".memory");
  if (beside == network_file) beside += ".memory";  // a network named *.memory
  return beside;
}

std::optional<ReconstructionMemory> findMatchingMemory(const nn::LossNetworkModel& model,
                                                       const std::filesystem::path& network_file) {
  std::vector<std::filesystem::path> candidates;
  if (!network_file.empty()) candidates.push_back(memoryFileBeside(network_file));
  if (const auto resources = resourceDirectory())
    if (const auto shipped = shippedMemoryFile(*resources, kShippedLossNetworkName)) candidates.push_back(*shipped);
  for (const std::filesystem::path& candidate : candidates) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(candidate, error)) continue;
    try {
      ReconstructionMemory memory = loadReconstructionMemory(candidate);
      if (memory.fits(model)) return memory;
    } catch (const Error&) {  // unreadable: not a memory to use
    }
  }
  return std::nullopt;
}

ReconstructionMemory mergeMemories(const ReconstructionMemory& kept, double kept_weight, const ReconstructionMemory& added,
                                   double added_weight, std::string description) {
  kept.validate();
  added.validate();
  if (kept.features != added.features || kept.hidden != added.hidden || kept.width != added.width ||
      kept.encoder_fingerprint != added.encoder_fingerprint)
    throw std::invalid_argument("mergeMemories: the memories were made with different loss networks");
  if (!(kept_weight > 0.0) || !(added_weight > 0.0) || !std::isfinite(kept_weight) || !std::isfinite(added_weight))
    throw std::invalid_argument("mergeMemories: the weights must be > 0 and finite");
  const double a = kept_weight / (kept_weight + added_weight), b = added_weight / (kept_weight + added_weight);
  ReconstructionMemory merged = kept;
  for (std::size_t m = 0; m < merged.lags.size(); ++m)
    merged.lags[m] = static_cast<float>(a) * kept.lags[m] + static_cast<float>(b) * added.lags[m];
  merged.cross = a * kept.cross + b * added.cross;
  merged.squared_norm = a * kept.squared_norm + b * added.squared_norm;
  merged.frames = kept.frames + added.frames;
  merged.clips = kept.clips + added.clips;
  merged.description = std::move(description);
  return merged;
}

void saveReconstructionMemory(const ReconstructionMemory& memory, const std::filesystem::path& file,
                              nn::WeightPrecision precision) {
  writeFileAtomically(file, serialiseReconstructionMemory(memory, precision));
}

std::string serialiseReconstructionMemoryCompactly(const ReconstructionMemory& memory) {
  try {
    return serialiseReconstructionMemory(memory, nn::WeightPrecision::F16);
  } catch (const std::invalid_argument&) {  // a value beyond f16's range (validate() passed above it)
    return serialiseReconstructionMemory(memory, nn::WeightPrecision::F32);
  }
}

std::string serialiseReconstructionMemory(const ReconstructionMemory& memory, nn::WeightPrecision precision) {
  memory.validate();
  nn::ByteWriter out;
  out.raw(kMagic);
  out.u32(kFormat);
  out.u32(static_cast<std::uint32_t>(memory.features));
  out.u32(static_cast<std::uint32_t>(memory.hidden));
  out.u32(static_cast<std::uint32_t>(memory.width));
  out.u64(memory.encoder_fingerprint);
  out.u32(static_cast<std::uint32_t>(memory.clips));
  out.f64(memory.frames);
  out.f64(memory.squared_norm);
  out.str(memory.description);
  out.u32(static_cast<std::uint32_t>(precision));
  for (std::size_t m = 0; m < memory.lags.size(); ++m) out.tensor("lag" + std::to_string(m), memory.lags[m], precision);
  out.tensor("cross", memory.cross.cast<float>(), precision);
  out.u32(nn::crc32(out.bytes()));
  return out.bytes();
}

ReconstructionMemory loadReconstructionMemory(const std::filesystem::path& file) {
  // A device or a huge file is refused before a byte is read (the shipped memory: 4 MB).
  const std::string bytes = nn::readFileBytes(file, kMaxFileBytes, "reconstruction memory");
  nn::ByteReader reader(bytes, file.string());
  if (reader.take(kMagic.size(), "the file's signature") != kMagic) reader.fail("not a reconstruction memory (no MSRMEMORY signature)");
  if (bytes.size() < kMagic.size() + 4) reader.fail("cut short");
  const std::string_view all(bytes);
  if (nn::crc32(all.substr(0, all.size() - 4)) != nn::ByteReader(all.substr(all.size() - 4), file.string()).u32("checksum"))
    reader.fail("its checksum does not match: the file is damaged");
  if (reader.u32("format") != kFormat) reader.fail("a reconstruction memory format this version cannot read");
  ReconstructionMemory memory;
  memory.features = static_cast<int>(reader.u32("features"));
  memory.hidden = static_cast<int>(reader.u32("hidden units"));
  memory.width = static_cast<int>(reader.u32("width"));
  if (memory.features < 1 || memory.features > 4096 || memory.hidden < 1 || memory.hidden > 4096 || memory.width < 1 ||
      memory.width > 255)
    reader.fail("its shape is not a loss network's");
  memory.encoder_fingerprint = reader.u64("encoder fingerprint");
  memory.clips = static_cast<int>(reader.u32("clips"));
  memory.frames = reader.f64("frames");
  memory.squared_norm = reader.f64("squared norm");
  memory.description = reader.str("description", 4096);
  const std::uint32_t code = reader.u32("value precision");
  if (code != static_cast<std::uint32_t>(nn::WeightPrecision::F32) && code != static_cast<std::uint32_t>(nn::WeightPrecision::F16))
    reader.fail("an unknown value precision");
  const auto precision = static_cast<nn::WeightPrecision>(code);
  for (int m = 0; m < memory.width; ++m) memory.lags.push_back(reader.tensor(precision).value);
  memory.cross = reader.tensor(precision).value.cast<double>();
  reader.u32("checksum");
  if (reader.remaining() != 0) reader.fail("bytes after the end");
  try {
    memory.validate();
  } catch (const std::invalid_argument& error) {
    throw InputError(file.string(), 0, error.what());
  }
  return memory;
}

}  // namespace motionstyle::style
