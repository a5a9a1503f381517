#pragma once
// What a checkpoint needs beyond the network file to continue training exactly: the optimiser's
// moments and step count, the completed epochs with their losses, and fingerprints tying the state to
// its network file and to the data it was trained on.
//
// The optimiser is nn::Adam<float>: its moments and step count are read with firstMoments(),
// secondMoments(), stepCount() and put back with restore().
//
// The state is a ".state" sidecar beside the checkpoint network file (the network file format has no
// room for optimiser state). Binary, little-endian (nn/binary_io.h):
//   "MSTRAINSTATE\0\0\0\0" (16 bytes), u32 version = 1, u32 network kind (1 loss network, 2 style),
//   u32 epochs completed, u64 Adam steps, u64 data fingerprint, u64 FNV-1a of the network file's bytes
//   (not a CRC: a network file ends with its own CRC-32, so the CRC of any valid one is the same constant),
//   u32 tensor count n, then n first moments and n second moments (nn::ByteWriter::tensor), u32 epochs,
//   per epoch: u32 epoch, f64 total, f64 seconds, u32 terms, per term str name + f64 value;
//   finally u32 CRC-32 of everything before it.

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "common/atomic_file.h"
#include "nn/adam.h"
#include "nn/network_file.h"
#include "style/training.h"

namespace motionstyle::style {

struct TrainingState {
  nn::NetworkKind kind = nn::NetworkKind::LossNetwork;
  int epochs_completed = 0;
  long adam_steps = 0;
  std::uint64_t data_fingerprint = 0;
  std::uint64_t network_hash = 0;  // fingerprint() of the checkpoint network file's bytes
  std::vector<nn::Mat<float>> first_moments;
  std::vector<nn::Mat<float>> second_moments;
  std::vector<EpochRecord> history;
};

std::string serialiseTrainingState(const TrainingState& state);
// InputError naming source_name on anything malformed (magic, version, lengths, CRC).
TrainingState parseTrainingState(std::string_view bytes, const std::string& source_name);

// The sidecar of a checkpoint network file: checkpoint + ".state".
std::filesystem::path statePath(const std::filesystem::path& checkpoint);

// Writes the network bytes to `checkpoint`, then the state (with network_hash set from those bytes) to
// statePath(checkpoint), each atomically. WriteError on failure: the previous files stay intact (if the
// state write fails after the network was replaced, the pair no longer matches and resume says so).
// `durability`: whether both files are fsync'ed first (common/atomic_file.h).
void writeCheckpoint(const std::filesystem::path& checkpoint, const std::string& network_bytes, TrainingState state,
                     FileDurability durability = FileDurability::Synced);

// Removes a checkpoint's network file and its state sidecar (the ones that exist). Never throws: a
// checkpoint left behind costs disk space, not correctness.
void removeCheckpoint(const std::filesystem::path& checkpoint);

// Reads the checkpoint's network bytes and its state and checks they belong together. InputError
// naming the file on a missing, corrupt or mismatched pair.
struct LoadedCheckpoint {
  std::string network_bytes;
  TrainingState state;
};
LoadedCheckpoint readCheckpoint(const std::filesystem::path& checkpoint);

// FNV-1a 64 over a sequence of strings (each followed by a 0 byte): the data fingerprint.
std::uint64_t fingerprint(const std::vector<std::string>& parts);

}  // namespace motionstyle::style
