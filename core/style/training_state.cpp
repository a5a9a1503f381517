#include "style/training_state.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "nn/binary_io.h"

namespace motionstyle::style {
namespace {

constexpr std::string_view kMagic("MSTRAINSTATE\0\0\0\0", 16);
constexpr std::uint32_t kVersion = 1;
constexpr std::uint32_t kMaxEpochs = 1'000'000;
constexpr std::uint32_t kMaxTerms = 64;

std::string readWholeFile(const std::filesystem::path& file, const char* what) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), 0, std::string("cannot open the ") + what);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace

std::string serialiseTrainingState(const TrainingState& state) {
  if (state.first_moments.size() != state.second_moments.size())
    throw std::invalid_argument("serialiseTrainingState: moment lists differ in length");
  nn::ByteWriter out;
  out.raw(kMagic);
  out.u32(kVersion);
  out.u32(static_cast<std::uint32_t>(state.kind));
  out.u32(static_cast<std::uint32_t>(state.epochs_completed));
  out.u64(static_cast<std::uint64_t>(state.adam_steps));
  out.u64(state.data_fingerprint);
  out.u64(state.network_hash);
  out.u32(static_cast<std::uint32_t>(state.first_moments.size()));
  // Tensor names "m0", "v0", ... (appended, not "m" + to_string: GCC 12 -Wrestrict false positive).
  const auto named = [](char prefix, std::size_t i) {
    std::string name(1, prefix);
    name += std::to_string(i);
    return name;
  };
  for (std::size_t i = 0; i < state.first_moments.size(); ++i) out.tensor(named('m', i), state.first_moments[i]);
  for (std::size_t i = 0; i < state.second_moments.size(); ++i) out.tensor(named('v', i), state.second_moments[i]);
  out.u32(static_cast<std::uint32_t>(state.history.size()));
  for (const EpochRecord& record : state.history) {
    out.u32(static_cast<std::uint32_t>(record.epoch));
    out.f64(record.total);
    out.f64(record.seconds);
    out.u32(static_cast<std::uint32_t>(record.terms.size()));
    for (const NamedLoss& term : record.terms) {
      out.str(term.name);
      out.f64(term.value);
    }
  }
  out.u32(nn::crc32(out.bytes()));
  return out.bytes();
}

TrainingState parseTrainingState(std::string_view bytes, const std::string& source_name) {
  nn::ByteReader in(bytes, source_name);
  if (in.take(kMagic.size(), "magic") != kMagic) in.fail("not a MotionStyle training-state file (bad magic)");
  if (bytes.size() < kMagic.size() + 4 || nn::crc32(bytes.substr(0, bytes.size() - 4)) !=
                                              nn::ByteReader(bytes.substr(bytes.size() - 4), source_name).u32("CRC"))
    in.fail("CRC mismatch: the training-state file is corrupt or truncated");
  const std::uint32_t version = in.u32("version");
  if (version != kVersion) in.fail("unsupported training-state version " + std::to_string(version));
  TrainingState state;
  const std::uint32_t kind = in.u32("kind");
  if (kind != 1 && kind != 2) in.fail("unknown network kind " + std::to_string(kind));
  state.kind = static_cast<nn::NetworkKind>(kind);
  state.epochs_completed = static_cast<int>(in.u32("epochs completed"));
  state.adam_steps = static_cast<long>(in.u64("optimiser steps"));
  state.data_fingerprint = in.u64("data fingerprint");
  state.network_hash = in.u64("network hash");
  const std::uint32_t tensors = in.u32("tensor count");
  if (tensors > 64) in.fail("implausible tensor count " + std::to_string(tensors));
  for (std::uint32_t i = 0; i < tensors; ++i) state.first_moments.push_back(in.tensor().value);
  for (std::uint32_t i = 0; i < tensors; ++i) state.second_moments.push_back(in.tensor().value);
  const std::uint32_t epochs = in.u32("epoch count");
  if (epochs > kMaxEpochs) in.fail("implausible epoch count");
  for (std::uint32_t e = 0; e < epochs; ++e) {
    EpochRecord record;
    record.epoch = static_cast<int>(in.u32("epoch"));
    record.total = in.f64("epoch loss");
    record.seconds = in.f64("epoch seconds");
    const std::uint32_t terms = in.u32("term count");
    if (terms > kMaxTerms) in.fail("implausible loss-term count");
    for (std::uint32_t t = 0; t < terms; ++t) {
      NamedLoss term;
      term.name = in.str("term name", 256);
      term.value = in.f64("term value");
      record.terms.push_back(std::move(term));
    }
    state.history.push_back(std::move(record));
  }
  if (in.remaining() != 4) in.fail("unexpected bytes after the epoch history");
  return state;
}

std::filesystem::path statePath(const std::filesystem::path& checkpoint) {
  std::filesystem::path sidecar = checkpoint;
  sidecar += ".state";
  return sidecar;
}

void writeCheckpoint(const std::filesystem::path& checkpoint, const std::string& network_bytes, TrainingState state,
                     FileDurability durability) {
  state.network_hash = fingerprint({network_bytes});
  const std::string state_bytes = serialiseTrainingState(state);
  writeFileAtomically(checkpoint, network_bytes, durability);
  writeFileAtomically(statePath(checkpoint), state_bytes, durability);
}

void removeCheckpoint(const std::filesystem::path& checkpoint) {
  std::error_code ignored;
  std::filesystem::remove(checkpoint, ignored);
  std::filesystem::remove(statePath(checkpoint), ignored);
}

LoadedCheckpoint readCheckpoint(const std::filesystem::path& checkpoint) {
  LoadedCheckpoint loaded;
  loaded.network_bytes = readWholeFile(checkpoint, "checkpoint (nothing to resume: train without --resume)");
  const std::filesystem::path sidecar = statePath(checkpoint);
  loaded.state = parseTrainingState(readWholeFile(sidecar, "checkpoint's training state"), sidecar.string());
  if (loaded.state.network_hash != fingerprint({loaded.network_bytes}))
    throw InputError(checkpoint.string(), 0,
                     "the checkpoint and its training state (" + sidecar.filename().string() +
                         ") do not belong together (interrupted while writing?): train without --resume");
  return loaded;
}

std::uint64_t fingerprint(const std::vector<std::string>& parts) {
  std::uint64_t hash = 1469598103934665603ull;
  for (const std::string& part : parts) {
    for (char c : part) {
      hash ^= static_cast<unsigned char>(c);
      hash *= 1099511628211ull;
    }
    hash ^= 0;
    hash *= 1099511628211ull;
  }
  return hash;
}

}  // namespace motionstyle::style
