// Network files made to hurt (issue 13): CRC-valid files whose statistics, training settings, weights
// or strings are non-physical or unsafe must be refused on load with an InputError naming the file and
// the field, and the writer must never write what the reader refuses.

#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/text_safety.h"
#include "loss_fixtures.h"
#include "nn/binary_io.h"
#include "nn/network_file.h"

namespace motionstyle::nn {
namespace {

constexpr std::size_t kHeaderBytes = 24;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Placeholders of the strings under test: each is replaced in the bytes by a payload of the same length.
const std::string kClipName = "CLIPNAMECLIP";
const std::string kTermName = "TERMNAMETERM";
const std::string kPropertyKey = "PROPKEYPROPK";
const std::string kPropertyValue = "PROPVALPROPV";

StyleModel smallStyleModel() {
  std::mt19937 rng(21);
  StyleModel model{TransformationNetwork<float>({kFeatureCount, 3, 3, true}), LossNetwork<float>({kFeatureCount, 4, 3}),
                   test::randomNormalisation(rng), {}, {}};
  model.transformation.initialise(22);
  model.loss_network.initialise(23);
  model.metadata.training.epochs = 2;
  model.metadata.style_clips = {{kClipName, contentHash("clip")}};
  model.metadata.loss_history = {{kTermName, "total"}, {{1.0, 2.0}, {0.5, 1.0}}};
  model.metadata.properties = {{kPropertyKey, kPropertyValue}};
  model.style_targets = {{"walk", Mat<float>::Constant(4, 4, 0.5f)}};
  return model;
}

LossNetworkModel smallLossNetwork() {
  const StyleModel style = smallStyleModel();
  return {style.loss_network, style.normalisation, style.metadata};
}

void fixCrc(std::string& bytes) {
  const std::uint32_t crc = crc32(std::string_view(bytes).substr(0, bytes.size() - 4));
  for (int i = 0; i < 4; ++i) bytes[bytes.size() - 4 + static_cast<std::size_t>(i)] = static_cast<char>((crc >> (8 * i)) & 0xFFu);
}

void putU32(std::string& bytes, std::size_t offset, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) bytes[offset + static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xFFu);
}

void putF64(std::string& bytes, std::size_t offset, double v) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  for (int i = 0; i < 8; ++i) bytes[offset + static_cast<std::size_t>(i)] = static_cast<char>((bits >> (8 * i)) & 0xFFu);
}

void putF32(std::string& bytes, std::size_t offset, float v) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &v, sizeof bits);
  putU32(bytes, offset, bits);
}

// Offsets of the metadata fields (NETWORK_FORMAT.md, "Layout"), from the joint set's stored length.
struct Offsets {
  std::size_t fps = kHeaderBytes, height = 0, mean = 0, std = 0, epochs = 0, learning_rate = 0, batch = 0,
              window = 0, loss_weights = 0, sparsity = 0, dropout = 0;
};

Offsets offsetsOf(const std::string& bytes) {
  Offsets o;
  ByteReader length(std::string_view(bytes).substr(o.fps + 8, 4), "probe");
  o.height = o.fps + 8 + 4 + length.u32("joint set length");
  o.mean = o.height + 8 + 4 + 4;  // height, feature count, mean count
  o.std = o.mean + 8 * kFeatureCount + 4;
  o.epochs = o.std + 8 * kFeatureCount;
  o.learning_rate = o.epochs + 4;
  o.batch = o.learning_rate + 8 + 8;  // learning rate, seed
  o.window = o.batch + 4;
  o.loss_weights = o.window + 4;
  o.sparsity = o.loss_weights + 5 * 8;
  o.dropout = o.sparsity + 8;
  return o;
}

std::size_t offsetOf(const std::string& bytes, std::string_view what) {
  const std::size_t at = bytes.find(what);
  EXPECT_NE(at, std::string::npos) << what;
  return at;
}

// Both kinds of file refuse `bytes` with an InputError naming the file and mentioning `needle`, and the
// message itself is safe text (no terminal escape, valid UTF-8).
void expectRefused(const std::string& bytes, const std::string& needle, bool style) {
  try {
    if (style)
      parseStyleModel(bytes, "net.msn");
    else
      parseLossNetwork(bytes, "net.msn");
    ADD_FAILURE() << "no InputError (expected one mentioning '" << needle << "')";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    EXPECT_EQ(e.file(), "net.msn");
    EXPECT_EQ(textSafetyProblem(e.what()), "") << "unsafe error message";
  }
}

template <typename Patch>
void expectBothKindsRefuse(Patch&& patch, const std::string& needle) {
  for (bool style : {false, true}) {
    std::string bytes = style ? serialiseStyleModel(smallStyleModel()) : serialiseLossNetwork(smallLossNetwork());
    patch(bytes, offsetsOf(bytes));
    fixCrc(bytes);
    expectRefused(bytes, needle, style);
  }
}

TEST(NetworkFileHostile, NonPhysicalNormalisationIsRefused) {
  for (double mean : {1e308, -1e308, 1e7, -2e6, kInf, kNaN})
    for (int index : {0, 65})
      expectBothKindsRefuse(
          [&](std::string& b, const Offsets& o) { putF64(b, o.mean + 8 * static_cast<std::size_t>(index), mean); },
          "normalisation mean[" + std::to_string(index) + "]");
  for (double std : {1e-301, 5e-324, 1e-7, 0.0, -1.0, -1e-301, kNaN, kInf, 1e7, 1e300})
    for (int index : {0, 64})
      expectBothKindsRefuse(
          [&](std::string& b, const Offsets& o) { putF64(b, o.std + 8 * static_cast<std::size_t>(index), std); },
          "normalisation std[" + std::to_string(index) + "]");
}

TEST(NetworkFileHostile, NonPhysicalRepresentationIsRefused) {
  for (double fps : {1e300, 1e5, 1e-300, 0.0, -60.0, kNaN})
    expectBothKindsRefuse([&](std::string& b, const Offsets& o) { putF64(b, o.fps, fps); }, "fps");
  for (double height : {1e-300, 0.5, 1e6, kInf})
    expectBothKindsRefuse([&](std::string& b, const Offsets& o) { putF64(b, o.height, height); }, "reference body height");
}

TEST(NetworkFileHostile, TrainingSettingsThatLaterCodeUsesAreChecked) {
  const auto f64At = [](std::size_t Offsets::*field, double v, std::size_t extra = 0) {
    return [=](std::string& b, const Offsets& o) { putF64(b, o.*field + extra, v); };
  };
  const auto u32At = [](std::size_t Offsets::*field, std::uint32_t v) {
    return [=](std::string& b, const Offsets& o) { putU32(b, o.*field, v); };
  };
  for (double dropout : {1.0, 1.5, -0.1, kNaN}) expectBothKindsRefuse(f64At(&Offsets::dropout, dropout), "dropout");
  for (double sparsity : {-1.0, kInf, 1e300}) expectBothKindsRefuse(f64At(&Offsets::sparsity, sparsity), "sparsity");
  for (double lr : {kNaN, -1e-3, kInf}) expectBothKindsRefuse(f64At(&Offsets::learning_rate, lr), "learning rate");
  for (std::size_t term = 0; term < 5; ++term)
    for (double weight : {-1.0, kInf, 1e300})
      expectBothKindsRefuse(f64At(&Offsets::loss_weights, weight, 8 * term), "loss weight");
  expectBothKindsRefuse(u32At(&Offsets::epochs, 0x80000000u), "epochs");
  expectBothKindsRefuse(u32At(&Offsets::batch, 0xFFFFFFFFu), "batch windows");
  expectBothKindsRefuse(u32At(&Offsets::window, 0x80000000u), "window frames");
}

TEST(NetworkFileHostile, NonFiniteOrHugeLossHistoryIsRefused) {
  // The history {{1, 2}, {0.5, 1}}: patch the value 0.5.
  std::string half(8, '\0');
  putF64(half, 0, 0.5);
  for (double value : {kNaN, kInf, -kInf, 1e300})
    expectBothKindsRefuse([&](std::string& b, const Offsets&) { putF64(b, offsetOf(b, half), value); }, "loss history");
}

TEST(NetworkFileHostile, HugeWeightsAndStyleTargetsAreRefused) {
  for (float weight : {1e30f, -1e6f, 2e5f}) {
    expectBothKindsRefuse(
        [&](std::string& b, const Offsets&) {
          putF32(b, offsetOf(b, "encoder.bias") + std::string("encoder.bias").size() + 8, weight);
        },
        "encoder.bias");
    std::string bytes = serialiseStyleModel(smallStyleModel());
    putF32(bytes, offsetOf(bytes, "transform2.weight") + std::string("transform2.weight").size() + 8, weight);
    fixCrc(bytes);
    expectRefused(bytes, "transform2.weight", true);
  }
  for (float gram : {1e30f, -1e13f}) {
    std::string bytes = serialiseStyleModel(smallStyleModel());
    putF32(bytes, offsetOf(bytes, "style_target:walk") + std::string("style_target:walk").size() + 8 + 4 * 5, gram);
    fixCrc(bytes);
    expectRefused(bytes, "style_target:walk", true);
  }
}

// Replaces the placeholder (same length as the payload's padded form) in the serialised bytes.
std::string withString(const std::string& placeholder, const std::string& payload, bool style) {
  std::string bytes = style ? serialiseStyleModel(smallStyleModel()) : serialiseLossNetwork(smallLossNetwork());
  std::string padded = payload;
  padded.resize(placeholder.size(), 'x');
  const std::size_t at = offsetOf(bytes, placeholder);
  if (at != std::string::npos) bytes.replace(at, placeholder.size(), padded);
  fixCrc(bytes);
  return bytes;
}

TEST(NetworkFileHostile, UnsafeStringsAreRefused) {
  const std::vector<std::pair<std::string, std::string>> payloads = {
      {"\x1b]0;title\x07", "control character 0x1b"},
      {"\xff\xfe", "invalid UTF-8"},
      {"ok\xc3", "invalid UTF-8"},        // a truncated two-byte sequence
      {"\xc0\xaf", "invalid UTF-8"},      // overlong '/'
      {"\xed\xa0\x80", "invalid UTF-8"},  // a surrogate
      {"a\xc2\x9b" "31m", "control character 0x9b"},  // C1 CSI
      {"tab\there", "control character 0x09"},
      {"new\nline", "control character 0x0a"},
  };
  for (const std::string& placeholder : {kClipName, kTermName, kPropertyKey, kPropertyValue})
    for (const auto& [payload, needle] : payloads)
      for (bool style : {false, true}) {
        SCOPED_TRACE(placeholder + " <- " + safeText(payload));
        expectRefused(withString(placeholder, payload, style), needle, style);
      }
  // The joint set: refused as unsafe text, and its bytes never reach the message.
  StyleModel model = smallStyleModel();
  model.metadata.representation.joint_set = "JOINTSETJOINTSET";
  std::string bytes = serialiseStyleModel(model);
  bytes.replace(offsetOf(bytes, "JOINTSETJOINTSET"), 16, std::string("\x1b]0;owned\x07xxxxx\x1b"));
  fixCrc(bytes);
  expectRefused(bytes, "joint set", true);
}

TEST(NetworkFileHostile, NonAsciiUtf8StringsStillRoundTrip) {
  StyleModel model = smallStyleModel();
  model.metadata.style_clips[0].name = "Zoë_gehen_歩く.bvh";
  model.metadata.properties.emplace_back("note", "Größe 1,80 m — ok");
  const StyleModel loaded = parseStyleModel(serialiseStyleModel(model), "net.msn");
  EXPECT_EQ(loaded.metadata, model.metadata);
}

TEST(NetworkFileHostile, TheWriterNeverWritesWhatTheReaderRefuses) {
  // Unsafe metadata text is made safe on the way out (U+FFFD), so the file stays readable.
  StyleModel unsafe_text = smallStyleModel();
  unsafe_text.metadata.style_clips[0].name = "latin1_\xe9t\xe9.bvh";
  unsafe_text.metadata.properties.emplace_back("adapted_on", "a\x1b[31mb");
  const StyleModel loaded = parseStyleModel(serialiseStyleModel(unsafe_text), "net.msn");
  EXPECT_EQ(loaded.metadata.style_clips[0].name, "latin1_\xEF\xBF\xBDt\xEF\xBF\xBD.bvh");
  EXPECT_EQ(loaded.metadata.properties.back().second, "a\xEF\xBF\xBD[31mb");
  // Non-physical numbers are refused (std::invalid_argument: a programming error, not the user's).
  StyleModel huge_mean = smallStyleModel();
  huge_mean.normalisation.mean(3) = 1e308;
  EXPECT_THROW(serialiseStyleModel(huge_mean), std::invalid_argument);
  StyleModel huge_weight = smallStyleModel();
  huge_weight.transformation.conv1.weight.value(0, 0) = 1e6f;  // above 1e5
  EXPECT_THROW(serialiseStyleModel(huge_weight), std::invalid_argument);
  StyleModel bad_dropout = smallStyleModel();
  bad_dropout.metadata.training.dropout = 1.0;
  EXPECT_THROW(serialiseStyleModel(bad_dropout), std::invalid_argument);
}

}  // namespace
}  // namespace motionstyle::nn
