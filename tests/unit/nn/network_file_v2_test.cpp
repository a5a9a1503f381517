// Network file format 2 (weight encoding f32 / f16): damaged and unsupported f16 files first, then
// round trips in both precisions, and format-1 files (what earlier builds wrote) still loading.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <unistd.h>

#include "common/errors.h"
#include "loss_fixtures.h"
#include "network_file_fixtures.h"
#include "nn/binary_io.h"
#include "nn/half_float.h"
#include "nn/network_file.h"

namespace motionstyle::nn {
namespace {

constexpr std::size_t kHeaderBytes = 24;

StyleModel smallStyleModel() {
  std::mt19937 rng(11);
  StyleModel model{TransformationNetwork<float>({kFeatureCount, 3, 3, true}), LossNetwork<float>({kFeatureCount, 4, 3}),
                   test::randomNormalisation(rng), {}, {}};
  model.transformation.initialise(12);
  model.loss_network.initialise(13);
  model.loss_network.encoder.bias.value.setConstant(0.125f);
  model.metadata.training.epochs = 2;
  model.metadata.loss_history = {{"content", "total"}, {{1.0, 2.0}, {0.5, 1.0}}};
  model.metadata.properties = {{"created", "2026-01-01T00:00:00Z"}};
  return model;
}

LossNetworkModel smallLossNetwork() {
  const StyleModel style = smallStyleModel();
  return {style.loss_network, style.normalisation, style.metadata};
}

std::uint32_t readU32(const std::string& bytes, std::size_t offset) {
  ByteReader r(std::string_view(bytes).substr(offset, 4), "probe");
  return r.u32("probe");
}

void putU32(std::string& bytes, std::size_t offset, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) bytes[offset + static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xFFu);
}

void fixCrc(std::string& bytes) {
  putU32(bytes, bytes.size() - 4, crc32(std::string_view(bytes).substr(0, bytes.size() - 4)));
}

// Offset of the weight-encoding field in a format-2 file: it is the u32 just before the loss network's
// architecture (features 66, hidden 4, width 3), found by scanning for that triple.
std::size_t weightEncodingOffset(const std::string& bytes) {
  for (std::size_t i = kHeaderBytes; i + 16 <= bytes.size(); ++i)
    if (readU32(bytes, i + 4) == kFeatureCount && readU32(bytes, i + 8) == 4 && readU32(bytes, i + 12) == 3) return i;
  ADD_FAILURE() << "architecture not found";
  return 0;
}

// A format-1 file made by hand from a format-2 f32 one: drop the weight-encoding field, set version 1,
// shrink the body size, recompute the CRC. Independent of the writer's own format-1 path.
std::string downgradeToFormat1(std::string bytes) {
  const std::size_t field = weightEncodingOffset(bytes);
  EXPECT_EQ(readU32(bytes, field), 1u);  // f32
  bytes.erase(field, 4);
  putU32(bytes, 8, 1);
  ByteReader size_reader(std::string_view(bytes).substr(16, 8), "probe");
  const std::uint64_t body = size_reader.u64("body") - 4;
  for (int i = 0; i < 8; ++i) bytes[16 + static_cast<std::size_t>(i)] = static_cast<char>((body >> (8 * i)) & 0xFFu);
  fixCrc(bytes);
  return bytes;
}

using test::expectInputError;

template <typename Network>
std::vector<Mat<float>> weightsOf(Network network) {
  std::vector<Mat<float>> all;
  for (const auto* p : network.parameters()) all.push_back(p->value);
  return all;
}

TEST(NetworkFileV2Invalid, TruncatedOrDamagedF16FilesAreRejected) {
  const std::string bytes = serialiseStyleModel(smallStyleModel(), WeightPrecision::F16);
  for (std::size_t length = 0; length < bytes.size(); ++length)
    EXPECT_THROW(parseStyleModel(std::string_view(bytes).substr(0, length), "net.msn"), InputError) << length;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::string damaged = bytes;
    damaged[i] = static_cast<char>(damaged[i] ^ 0x10);
    EXPECT_THROW(parseStyleModel(damaged, "net.msn"), InputError) << "byte " << i;
  }
  expectInputError([&] { parseStyleModel(bytes.substr(0, bytes.size() - 1), "net.msn"); }, "truncated");
}

TEST(NetworkFileV2Invalid, UnknownOrMislabelledWeightEncoding) {
  const std::string bytes = serialiseStyleModel(smallStyleModel(), WeightPrecision::F16);
  const std::size_t field = weightEncodingOffset(bytes);
  ASSERT_EQ(readU32(bytes, field), 2u);
  std::string unknown = bytes;
  putU32(unknown, field, 3);
  fixCrc(unknown);
  expectInputError([&] { parseStyleModel(unknown, "net.msn"); }, "unknown weight encoding 3");
  // f16 data labelled f32: the declared weights no longer fit in the file.
  std::string mislabelled = bytes;
  putU32(mislabelled, field, 1);
  fixCrc(mislabelled);
  expectInputError([&] { parseStyleModel(mislabelled, "net.msn"); }, "needs");
  // A format-1 header on a format-2 body: the encoding field is read as the architecture.
  std::string old_header = bytes;
  putU32(old_header, 8, 1);
  fixCrc(old_header);
  EXPECT_THROW(parseStyleModel(old_header, "net.msn"), InputError);
}

TEST(NetworkFileV2Invalid, NonFiniteHalfWeightIsRejected) {
  std::string bytes = serialiseLossNetwork(smallLossNetwork(), WeightPrecision::F16);
  // The last tensor is decoder.weight: its last two bytes are one f16 weight. Make it infinity.
  bytes[bytes.size() - 6] = 0x00;
  bytes[bytes.size() - 5] = static_cast<char>(0x7C);
  fixCrc(bytes);
  expectInputError([&] { parseLossNetwork(bytes, "net.msn"); }, "non-finite");
}

TEST(NetworkFileV2Invalid, WeightsOutsideTheHalfRangeAreNotWrittenAsF16) {
  StyleModel big = smallStyleModel();
  big.transformation.conv2.weight.value(1, 1) = 70000.0f;
  EXPECT_THROW(serialiseStyleModel(big, WeightPrecision::F16), std::invalid_argument);
  EXPECT_NO_THROW(parseStyleModel(serialiseStyleModel(big, WeightPrecision::F32), "net.msn"));
  StyleModel nan = smallStyleModel();
  nan.loss_network.decoder.weight.value(0, 0) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(serialiseStyleModel(nan, WeightPrecision::F16), std::invalid_argument);
  StyleModel at_limit = smallStyleModel();
  at_limit.transformation.conv1.weight.value(0, 0) = -kHalfMax;
  const StyleModel loaded = parseStyleModel(serialiseStyleModel(at_limit, WeightPrecision::F16), "net.msn");
  EXPECT_EQ(loaded.transformation.conv1.weight.value(0, 0), -kHalfMax);
}

TEST(NetworkFileV2, F32RoundTripIsExactAndWritesTheCurrentFormat) {
  const StyleModel model = smallStyleModel();
  const std::string bytes = serialiseStyleModel(model);
  EXPECT_EQ(readU32(bytes, 8), 3u);
  EXPECT_EQ(kNetworkFormatVersion, 3u);
  const StyleModel loaded = parseStyleModel(bytes, "net.msn");
  EXPECT_EQ(weightsOf(loaded.transformation), weightsOf(model.transformation));
  EXPECT_EQ(weightsOf(loaded.loss_network), weightsOf(model.loss_network));
  EXPECT_EQ(loaded.metadata, model.metadata);
  const NetworkFileInfo info = networkFileInfo(bytes, "net.msn");
  EXPECT_EQ(info.format_version, 3u);
  EXPECT_EQ(info.kind, NetworkKind::Style);
  EXPECT_EQ(info.precision, WeightPrecision::F32);
  EXPECT_EQ(info.bytes, bytes.size());
}

TEST(NetworkFileV2, F16RoundTripRoundsEachWeightOnceAndIsStable) {
  const StyleModel model = smallStyleModel();
  const std::string bytes = serialiseStyleModel(model, WeightPrecision::F16);
  const StyleModel loaded = parseStyleModel(bytes, "net.msn");
  EXPECT_EQ(networkFileInfo(bytes, "net.msn").precision, WeightPrecision::F16);
  EXPECT_EQ(loaded.metadata, model.metadata);
  EXPECT_EQ(loaded.normalisation.mean, model.normalisation.mean);  // statistics stay f64
  EXPECT_EQ(loaded.normalisation.std, model.normalisation.std);
  const auto original = weightsOf(model.transformation);
  const auto rounded = weightsOf(loaded.transformation);
  ASSERT_EQ(original.size(), rounded.size());
  for (std::size_t i = 0; i < original.size(); ++i)
    for (Eigen::Index k = 0; k < original[i].size(); ++k) {
      const float w = original[i].data()[k];
      EXPECT_EQ(rounded[i].data()[k], halfToFloat(floatToHalf(w)));
      EXPECT_LE(std::abs(rounded[i].data()[k] - w), std::abs(w) * std::ldexp(1.0f, -11) + std::ldexp(1.0f, -25));
    }
  // Values already representable survive exactly: f16 -> f32 -> f16 gives the same bytes.
  EXPECT_EQ(serialiseStyleModel(loaded, WeightPrecision::F16), bytes);
  const StyleModel as_f32 = parseStyleModel(serialiseStyleModel(loaded, WeightPrecision::F32), "net.msn");
  EXPECT_EQ(weightsOf(as_f32.transformation), rounded);
  // About half the size: the weights dominate.
  const std::string f32 = serialiseStyleModel(model);
  const std::size_t weight_count = 3 * 66 * 3 + 3 + 3 * 3 * 3 + 3 + 66 * 3 * 3 + 66 + 2 * 66 * 4 * 3 + 4;
  EXPECT_EQ(f32.size() - bytes.size(), 2 * weight_count);
}

TEST(NetworkFileV2, LossNetworkRoundTripsInBothPrecisions) {
  const LossNetworkModel model = smallLossNetwork();
  for (WeightPrecision precision : {WeightPrecision::F32, WeightPrecision::F16}) {
    const LossNetworkModel loaded = parseLossNetwork(serialiseLossNetwork(model, precision), "net.msn");
    const auto a = weightsOf(model.network);
    const auto b = weightsOf(loaded.network);
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (precision == WeightPrecision::F32) {
        EXPECT_EQ(a[i], b[i]);
      }
      EXPECT_LE((a[i] - b[i]).cwiseAbs().maxCoeff(), a[i].cwiseAbs().maxCoeff() * std::ldexp(1.0f, -11));
    }
  }
}

TEST(NetworkFileV2, Format1FilesStillLoad) {
  const LossNetworkModel loss_network = smallLossNetwork();
  const std::string by_hand = downgradeToFormat1(serialiseLossNetwork(loss_network));
  EXPECT_EQ(serialiseLossNetworkFormat1(loss_network), by_hand);  // the writer's format-1 path matches the spec
  const LossNetworkModel loaded = parseLossNetwork(by_hand, "net.msn");
  EXPECT_EQ(weightsOf(loaded.network), weightsOf(loss_network.network));
  EXPECT_EQ(loaded.metadata, loss_network.metadata);
  const NetworkFileInfo info = networkFileInfo(by_hand, "net.msn");
  EXPECT_EQ(info.format_version, 1u);
  EXPECT_EQ(info.precision, WeightPrecision::F32);

  const StyleModel style = smallStyleModel();
  const StyleModel loaded_style = parseStyleModel(downgradeToFormat1(serialiseStyleModel(style)), "net.msn");
  EXPECT_EQ(weightsOf(loaded_style.transformation), weightsOf(style.transformation));
  // Re-saving a format-1 network writes format 2 with the same weights.
  EXPECT_EQ(serialiseStyleModel(loaded_style), serialiseStyleModel(style));
}

TEST(NetworkFileV2, SavedFilesDescribeTheirPrecision) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("nn_file_v2_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  saveStyleModel(smallStyleModel(), dir / "half.msn", WeightPrecision::F16);
  saveLossNetwork(smallLossNetwork(), dir / "full.msn");
  EXPECT_EQ(networkFileInfo(dir / "half.msn").precision, WeightPrecision::F16);
  EXPECT_EQ(networkFileInfo(dir / "full.msn").precision, WeightPrecision::F32);
  const std::string half = describeNetworkFile(dir / "half.msn");
  EXPECT_NE(half.find("format 3, weights f16"), std::string::npos) << half;
  EXPECT_NE(describeNetworkFile(dir / "full.msn").find("format 3, weights f32"), std::string::npos);
  std::filesystem::remove_all(dir);
}

// Format 3: style files carry their style targets (eq. 5's Gram per content label).
TEST(NetworkFileV3, StyleTargetsAreCheckedThenRoundTrip) {
  StyleModel model = smallStyleModel();
  const Eigen::Index hidden = model.loss_network.shape().hidden;
  model.style_targets = {{"walk", Mat<float>::Constant(hidden, hidden, 0.5f)}, {"", Mat<float>::Identity(hidden, hidden)}};
  StyleModel wrong_shape = model;
  wrong_shape.style_targets[0].gram = Mat<float>::Zero(hidden + 1, hidden);
  EXPECT_THROW(serialiseStyleModel(wrong_shape), std::invalid_argument);
  StyleModel not_finite = model;
  not_finite.style_targets[1].gram(0, 0) = std::numeric_limits<float>::infinity();
  EXPECT_THROW(serialiseStyleModel(not_finite), std::invalid_argument);
  StyleModel twice = model;
  twice.style_targets[1].label = "walk";
  EXPECT_THROW(parseStyleModel(serialiseStyleModel(twice), "net.msn"), InputError);

  for (WeightPrecision precision : {WeightPrecision::F32, WeightPrecision::F16}) {
    const StyleModel loaded = parseStyleModel(serialiseStyleModel(model, precision), "net.msn");
    ASSERT_EQ(loaded.style_targets.size(), 2u);
    EXPECT_EQ(loaded.style_targets[0].label, "walk");
    EXPECT_EQ(loaded.style_targets[1].label, "");
    EXPECT_EQ(loaded.style_targets[0].gram, model.style_targets[0].gram);  // 0.5 and 1 are exact in f16
    EXPECT_EQ(loaded.style_targets[1].gram, model.style_targets[1].gram);
  }
  EXPECT_TRUE(parseStyleModel(serialiseStyleModel(smallStyleModel()), "net.msn").style_targets.empty());
}

}  // namespace
}  // namespace motionstyle::nn
