// libFuzzer target for the network file reader (core/nn/network_file.h) and, on what it accepts, the
// writer and describe().
//
// Each input is parsed twice: as it is (the header, size and CRC-32 checks), and with its body size and
// CRC-32 repaired (NETWORK_FORMAT.md: u64 at byte 16, trailing u32), because almost every mutation
// breaks the checksum and would otherwise never reach the metadata, architecture and tensor checks.
// The reader may only return a model or throw InputError. Anything else is a finding: a crash, a
// sanitizer report, another exception type escaping (libFuzzer reports it as a crash), an InputError
// without the file name or with an unsafe message, an accepted model whose description holds unsafe
// text, or one whose save -> load round trip does not reproduce it exactly (for a format-3 file: the
// very same bytes).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "common/errors.h"
#include "common/text_safety.h"
#include "nn/binary_io.h"
#include "nn/network_file.h"

namespace {

using namespace motionstyle;
using namespace motionstyle::nn;

constexpr const char* kSource = "fuzz.net";

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "fuzz_network_file finding: %s\n", what.c_str());
  std::abort();
}

void requireSafe(const std::string& text, const char* what) {
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    if (const std::string problem = textSafetyProblem(std::string_view(text).substr(start, end - start)); !problem.empty())
      finding(std::string(what) + " holds unsafe text: " + problem);
    start = end + 1;
  }
}

template <typename Network>
bool sameParameters(Network a, Network b) {  // names, shapes and values; by value: parameters() is not const
  const auto pa = a.parameters();
  const auto pb = b.parameters();
  if (pa.size() != pb.size()) return false;
  for (std::size_t i = 0; i < pa.size(); ++i)
    if (pa[i]->name != pb[i]->name || pa[i]->value.rows() != pb[i]->value.rows() ||
        pa[i]->value.cols() != pb[i]->value.cols() || pa[i]->value != pb[i]->value)
      return false;
  return true;
}

bool sameCommon(const FeatureStatistics& a, const FeatureStatistics& b, const NetworkMetadata& ma, const NetworkMetadata& mb) {
  return a.mean == b.mean && a.std == b.std && ma == mb;
}

// Save -> load reproduces the model; a format-3 file is reproduced byte for byte.
void checkAccepted(std::string_view bytes, const NetworkFileInfo& info) {
  std::string again;
  if (info.kind == NetworkKind::Style) {
    const StyleModel model = parseStyleModel(bytes, kSource);
    requireSafe(describe(model), "describe()");
    again = serialiseStyleModel(model, info.precision);
    const StyleModel reloaded = parseStyleModel(again, "rewritten.net");
    if (!sameParameters(model.transformation, reloaded.transformation) || !sameParameters(model.loss_network, reloaded.loss_network) ||
        !sameCommon(model.normalisation, reloaded.normalisation, model.metadata, reloaded.metadata) ||
        model.style_targets != reloaded.style_targets || model.transformation.shape().residual != reloaded.transformation.shape().residual)
      finding("style network: save -> load changed the model");
  } else {
    const LossNetworkModel model = parseLossNetwork(bytes, kSource);
    requireSafe(describe(model), "describe()");
    again = serialiseLossNetwork(model, info.precision);
    const LossNetworkModel reloaded = parseLossNetwork(again, "rewritten.net");
    if (!sameParameters(model.network, reloaded.network) ||
        !sameCommon(model.normalisation, reloaded.normalisation, model.metadata, reloaded.metadata))
      finding("loss network: save -> load changed the model");
  }
  if (info.format_version == kNetworkFormatVersion && again != bytes) finding("a format-3 file is not rewritten byte for byte");
}

void parseOne(std::string_view bytes) {
  try {
    checkAccepted(bytes, networkFileInfo(bytes, kSource));
  } catch (const InputError& error) {
    if (error.file() != kSource || error.line() != 0) finding("InputError without the file name or with a line");
    requireSafe(error.what(), "an InputError message");
  } catch (const std::invalid_argument& error) {
    // Only the writer throws this (a model it must not write): the reader accepted something it should not.
    finding(std::string("the writer refuses what the reader accepted: ") + error.what());
  }
}

// The input with the header's body size and the trailing CRC-32 made consistent with its length.
std::string repaired(std::string_view bytes) {
  constexpr std::size_t kHeader = 24, kCrc = 4;
  std::string out(bytes);
  if (out.size() < kHeader + kCrc) return out;
  const std::uint64_t body = out.size() - kHeader - kCrc;
  for (int i = 0; i < 8; ++i) out[16 + static_cast<std::size_t>(i)] = static_cast<char>((body >> (8 * i)) & 0xFFu);
  const std::uint32_t crc = crc32(std::string_view(out).substr(0, out.size() - kCrc));
  for (int i = 0; i < 4; ++i)
    out[out.size() - kCrc + static_cast<std::size_t>(i)] = static_cast<char>((crc >> (8 * i)) & 0xFFu);
  return out;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  parseOne(bytes);
  const std::string fixed = repaired(bytes);
  if (fixed != bytes) parseOne(fixed);
  return 0;
}
