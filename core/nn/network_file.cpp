#include "nn/network_file.h"

#include <cmath>
#include <iterator>
#include <sstream>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "nn/binary_io.h"
#include "nn/network_limits.h"

namespace motionstyle::nn {
namespace {

constexpr std::string_view kMagic = "MSTYLNET";
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 + 8;  // magic, version, kind, body size
constexpr std::size_t kCrcBytes = 4;
constexpr std::uintmax_t kMaxFileBytes = 256u << 20;  // a default style file is ~7 MB
constexpr std::uint32_t kMaxDimension = 4096;
constexpr std::uint32_t kMaxWidth = 255;
constexpr std::uint32_t kMaxStyleTargets = 64;
constexpr std::string_view kStyleTargetPrefix = "style_target:";

const char* kindName(NetworkKind kind) {
  return kind == NetworkKind::LossNetwork ? "a loss network" : "a style network (the paper's transformation network)";
}

// Writing.
// A tensor the reader would refuse (network_limits.h) is never written.
void writeChecked(ByteWriter& w, const std::string& name, const Mat<float>& values, WeightPrecision precision,
                  float max_magnitude) {
  if (std::string problem = valuesProblem(name, values, max_magnitude); !problem.empty())
    throw std::invalid_argument("network file: " + problem);
  w.tensor(name, values, precision);
}

void writeConvTensors(ByteWriter& w, const Conv1d<float>& conv, WeightPrecision precision) {
  writeChecked(w, conv.weight.name, conv.weight.value, precision, kMaxWeightMagnitude);
  if (conv.hasBias()) writeChecked(w, conv.bias.name, conv.bias.value, precision, kMaxWeightMagnitude);
}

void requireWritable(const FeatureStatistics& normalisation, const NetworkMetadata& metadata) {
  normalisation.validate();
  for (const std::string& problem : {normalisationProblem(normalisation), metadataProblem(metadata)})
    if (!problem.empty()) throw std::invalid_argument("network file: " + problem);
  if (metadata.representation.feature_count != kFeatureCount)
    throw std::invalid_argument("network file: representation.feature_count must be " + std::to_string(kFeatureCount));
  for (const auto& epoch : metadata.loss_history.epochs)
    if (epoch.size() != metadata.loss_history.terms.size())
      throw std::invalid_argument("network file: every loss-history epoch needs one value per term");
}

// format_version 1 has no weight-encoding field and is always f32.
std::string serialise(NetworkKind kind, const FeatureStatistics& normalisation, const NetworkMetadata& m,
                      const LossNetwork<float>& loss_network, const TransformationNetwork<float>* transformation,
                      WeightPrecision precision, std::uint32_t format_version,
                      const std::vector<StyleTarget>& targets = {}) {
  if (format_version == 1 && precision != WeightPrecision::F32)
    throw std::invalid_argument("network file format 1 stores f32 weights only");
  requireWritable(normalisation, m);
  ByteWriter body;
  const RepresentationInfo& r = m.representation;
  body.f64(r.fps);
  body.str(r.joint_set);
  body.f64(r.reference_body_height_cm);
  body.u32(static_cast<std::uint32_t>(r.feature_count));
  body.f64Vector(normalisation.mean);
  body.f64Vector(normalisation.std);
  const TrainingConfig& t = m.training;
  body.u32(static_cast<std::uint32_t>(t.epochs));
  body.f64(t.learning_rate);
  body.u64(t.seed);
  body.u32(static_cast<std::uint32_t>(t.batch_windows));
  body.u32(static_cast<std::uint32_t>(t.window_frames));
  for (double v : {t.weights.content, t.weights.style, t.weights.foot, t.weights.bone, t.weights.trajectory})
    body.f64(v);
  body.f64(t.sparsity);
  body.f64(t.dropout);
  body.u32(static_cast<std::uint32_t>(m.style_clips.size()));
  for (const StyleClipRef& clip : m.style_clips) {
    body.str(clip.name);
    body.str(clip.content_hash);
  }
  body.u32(static_cast<std::uint32_t>(m.loss_history.terms.size()));
  for (const std::string& term : m.loss_history.terms) body.str(term);
  body.u32(static_cast<std::uint32_t>(m.loss_history.epochs.size()));
  for (const auto& epoch : m.loss_history.epochs)
    for (double v : epoch) body.f64(v);
  body.u32(static_cast<std::uint32_t>(m.properties.size()));
  for (const auto& [key, value] : m.properties) {
    body.str(key);
    body.str(value);
  }
  if (format_version >= 2) body.u32(static_cast<std::uint32_t>(precision));
  // Architecture, then tensors.
  body.u32(static_cast<std::uint32_t>(loss_network.shape().features));
  body.u32(static_cast<std::uint32_t>(loss_network.shape().hidden));
  body.u32(static_cast<std::uint32_t>(loss_network.shape().width));
  if (transformation != nullptr) {
    body.u32(static_cast<std::uint32_t>(transformation->shape().features));
    body.u32(static_cast<std::uint32_t>(transformation->shape().hidden));
    body.u32(static_cast<std::uint32_t>(transformation->shape().width));
    body.u8(transformation->shape().residual ? 1 : 0);
  }
  if (format_version < 3 && !targets.empty())
    throw std::invalid_argument("network file formats before 3 store no style targets");
  body.u32(static_cast<std::uint32_t>((transformation != nullptr ? 9u : 3u) + targets.size()));
  if (transformation != nullptr) {
    writeConvTensors(body, transformation->conv1, precision);
    writeConvTensors(body, transformation->conv2, precision);
    writeConvTensors(body, transformation->conv3, precision);
  }
  writeConvTensors(body, loss_network.encoder, precision);
  writeConvTensors(body, loss_network.decoder, precision);
  for (const StyleTarget& target : targets) {
    if (target.gram.rows() != loss_network.shape().hidden || target.gram.cols() != loss_network.shape().hidden || !target.gram.allFinite())
      throw std::invalid_argument("style target '" + target.label + "' must be a finite hidden x hidden matrix");
    writeChecked(body, std::string(kStyleTargetPrefix) + target.label, target.gram, precision, kMaxStyleTargetMagnitude);
  }

  ByteWriter file;
  file.raw(kMagic);
  file.u32(format_version);
  file.u32(static_cast<std::uint32_t>(kind));
  file.u64(body.bytes().size());
  file.raw(body.bytes());
  file.u32(crc32(file.bytes()));
  return std::move(file.bytes());
}

// Reading.
struct Parsed {
  std::uint32_t version = 0;
  NetworkKind kind{};
  WeightPrecision precision = WeightPrecision::F32;
  NetworkMetadata metadata;
  FeatureStatistics normalisation;
  LossNetworkShape loss_network_shape;
  TransformationShape t_shape;
  std::vector<ByteReader::Tensor> tensors;
};

struct Header {
  std::uint32_t version = 0;
  NetworkKind kind{};
};

// Header, size, version and CRC; leaves `reader` at the body.
Header readHeader(std::string_view bytes, ByteReader& reader) {
  if (bytes.size() < kHeaderBytes + kCrcBytes)
    reader.fail("truncated network file: " + std::to_string(bytes.size()) + " bytes, a network file has at least " +
                std::to_string(kHeaderBytes + kCrcBytes));
  if (bytes.substr(0, kMagic.size()) != kMagic) reader.fail("not a MotionStyle network file (wrong magic)");
  reader.take(kMagic.size(), "magic");
  const std::uint32_t version = reader.u32("format version");
  if (version == 0) reader.fail("corrupt network file: format version 0");
  if (version > kNetworkFormatVersion)
    reader.fail("network file format version " + std::to_string(version) +
                " is newer than this build supports (up to " + std::to_string(kNetworkFormatVersion) +
                "): update MotionStyle");
  const std::uint32_t kind = reader.u32("kind");
  const std::uint64_t body_size = reader.u64("body size");
  const std::uint64_t expected = kHeaderBytes + body_size + kCrcBytes;
  if (body_size > bytes.size() || expected > bytes.size())
    reader.fail("truncated network file: the header announces " + std::to_string(expected) + " bytes, the file has " +
                std::to_string(bytes.size()));
  if (expected < bytes.size())
    reader.fail("corrupt network file: " + std::to_string(bytes.size() - expected) + " unexpected trailing bytes");
  ByteReader crc_reader(bytes.substr(bytes.size() - kCrcBytes), reader.file());
  if (crc_reader.u32("CRC") != crc32(bytes.substr(0, bytes.size() - kCrcBytes)))
    reader.fail("corrupt network file: CRC-32 mismatch (the file was damaged or truncated)");
  if (kind != static_cast<std::uint32_t>(NetworkKind::LossNetwork) && kind != static_cast<std::uint32_t>(NetworkKind::Style))
    reader.fail("corrupt network file: unknown kind " + std::to_string(kind));
  return {version, static_cast<NetworkKind>(kind)};
}

std::uint32_t readCount(ByteReader& r, const char* what, std::size_t min_bytes_each) {
  const std::uint32_t count = r.u32(what);
  if (static_cast<std::uint64_t>(count) * min_bytes_each > r.remaining())
    r.fail(std::string("truncated or corrupt network file: ") + what + " claims " + std::to_string(count) + " entries");
  return count;
}

int readDimension(ByteReader& r, const char* what, std::uint32_t max) {
  const std::uint32_t v = r.u32(what);
  if (v < 1 || v > max) r.fail(std::string("corrupt network file: ") + what + " = " + std::to_string(v));
  return static_cast<int>(v);
}

void readMetadata(ByteReader& r, Parsed& p) {
  RepresentationInfo& rep = p.metadata.representation;
  rep.fps = r.f64("fps");
  rep.joint_set = r.str("joint set", 256);
  rep.reference_body_height_cm = r.f64("reference body height");
  rep.feature_count = static_cast<int>(r.u32("feature count"));
  p.normalisation.mean = r.f64Vector("normalisation mean");
  p.normalisation.std = r.f64Vector("normalisation std");
  TrainingConfig& t = p.metadata.training;
  t.epochs = static_cast<int>(r.u32("epochs"));
  t.learning_rate = r.f64("learning rate");
  t.seed = r.u64("seed");
  t.batch_windows = static_cast<int>(r.u32("batch windows"));
  t.window_frames = static_cast<int>(r.u32("window frames"));
  for (double* v : {&t.weights.content, &t.weights.style, &t.weights.foot, &t.weights.bone, &t.weights.trajectory})
    *v = r.f64("loss weight");
  t.sparsity = r.f64("sparsity");
  t.dropout = r.f64("dropout");
  const std::uint32_t clips = readCount(r, "style clip count", 8);
  for (std::uint32_t i = 0; i < clips; ++i) {
    StyleClipRef clip;
    clip.name = r.str("style clip name");
    clip.content_hash = r.str("style clip hash", 256);
    p.metadata.style_clips.push_back(std::move(clip));
  }
  const std::uint32_t terms = readCount(r, "loss term count", 4);
  for (std::uint32_t i = 0; i < terms; ++i) p.metadata.loss_history.terms.push_back(r.str("loss term", 256));
  const std::uint32_t epochs = r.u32("loss history epochs");
  if (static_cast<std::uint64_t>(epochs) * terms * 8 > r.remaining() || (terms == 0 && epochs != 0))
    r.fail("truncated or corrupt network file: loss history claims " + std::to_string(epochs) + " epochs");
  for (std::uint32_t e = 0; e < epochs; ++e) {
    std::vector<double> values(terms);
    for (double& v : values) v = r.f64("loss value");
    p.metadata.loss_history.epochs.push_back(std::move(values));
  }
  const std::uint32_t properties = readCount(r, "property count", 8);
  for (std::uint32_t i = 0; i < properties; ++i) {
    std::string key = r.str("property key", 4096);
    std::string value = r.str("property value");
    p.metadata.properties.emplace_back(std::move(key), std::move(value));
  }
}

// What this build can use: the 66-value canonical representation with matching statistics.
void validateRepresentation(const ByteReader& r, const Parsed& p) {
  const RepresentationInfo& rep = p.metadata.representation;
  if (rep.feature_count != kFeatureCount ||
      (rep.joint_set != kRetargetedJointSetName && rep.joint_set != kProportionsJointSetName &&
       rep.joint_set != kCanonicalJointSetName))
    r.fail("network file uses a different representation (" + std::to_string(rep.feature_count) + " features, joint set '" +
           rep.joint_set + "'); this build uses " + std::to_string(kFeatureCount) + " features of '" +
           std::string(kRetargetedJointSetName) + "'");
  // Non-physical numbers (network_limits.h): the writer never writes them, later code trusts them.
  for (const std::string& problem : {metadataProblem(p.metadata), normalisationProblem(p.normalisation)})
    if (!problem.empty()) r.fail("corrupt network file: " + problem);
  if (p.loss_network_shape.features != rep.feature_count)
    r.fail("network file: the loss network has " + std::to_string(p.loss_network_shape.features) + " features, the representation " +
           std::to_string(rep.feature_count));
}

WeightPrecision readWeightEncoding(ByteReader& r, std::uint32_t version) {
  if (version < 2) return WeightPrecision::F32;
  const std::uint32_t code = r.u32("weight encoding");
  if (code != static_cast<std::uint32_t>(WeightPrecision::F32) && code != static_cast<std::uint32_t>(WeightPrecision::F16))
    r.fail("corrupt network file: unknown weight encoding " + std::to_string(code) + " (1 = f32, 2 = f16)");
  return static_cast<WeightPrecision>(code);
}

void readArchitecture(ByteReader& r, Parsed& p) {
  p.loss_network_shape.features = readDimension(r, "loss network features", kMaxDimension);
  p.loss_network_shape.hidden = readDimension(r, "loss network hidden units", kMaxDimension);
  p.loss_network_shape.width = readDimension(r, "loss network width", kMaxWidth);
  std::uint64_t floats = 2ull * p.loss_network_shape.features * p.loss_network_shape.hidden * p.loss_network_shape.width + p.loss_network_shape.hidden;
  if (p.kind == NetworkKind::Style) {
    p.t_shape.features = readDimension(r, "transformation features", kMaxDimension);
    p.t_shape.hidden = readDimension(r, "transformation hidden units", kMaxDimension);
    p.t_shape.width = readDimension(r, "transformation width", kMaxWidth);
    const std::uint8_t residual = r.u8("transformation residual flag");
    if (residual > 1) r.fail("corrupt network file: residual flag " + std::to_string(residual));
    p.t_shape.residual = residual == 1;
    const std::uint64_t f = static_cast<std::uint64_t>(p.t_shape.features);
    const std::uint64_t h = static_cast<std::uint64_t>(p.t_shape.hidden);
    floats += (2 * f * h + h * h) * static_cast<std::uint64_t>(p.t_shape.width) + 2 * h + f;
  }
  if (p.loss_network_shape.width % 2 == 0 || (p.kind == NetworkKind::Style && p.t_shape.width % 2 == 0))
    r.fail("corrupt network file: convolution widths must be odd");
  // Before any network is allocated: the declared architecture must fit in the bytes that remain.
  const std::uint64_t weight_bytes = floats * bytesPerWeight(p.precision);
  if (weight_bytes > r.remaining())
    r.fail("truncated or corrupt network file: the architecture needs " + std::to_string(weight_bytes) +
           " bytes of weights, only " + std::to_string(r.remaining()) + " left");
}

void assignConv(ByteReader& r, std::vector<ByteReader::Tensor>& tensors, std::size_t& next, Conv1d<float>& conv) {
  for (Parameter<float>* param : conv.parameters()) {
    if (next >= tensors.size()) r.fail("network file: missing tensor " + param->name);
    ByteReader::Tensor& t = tensors[next++];
    if (t.name != param->name || t.value.rows() != param->value.rows() || t.value.cols() != param->value.cols())
      r.fail("network file: tensor '" + t.name + "' " + std::to_string(t.value.rows()) + " x " +
             std::to_string(t.value.cols()) + " where '" + param->name + "' " + std::to_string(param->value.rows()) +
             " x " + std::to_string(param->value.cols()) + " was expected");
    if (!t.value.allFinite()) r.fail("network file: tensor '" + t.name + "' has non-finite values");
    if (std::string problem = valuesProblem(t.name, t.value, kMaxWeightMagnitude); !problem.empty())
      r.fail("corrupt network file: " + problem);
    param->value = std::move(t.value);
    param->zeroGrad();
  }
}

Parsed parse(std::string_view bytes, const std::string& source, NetworkKind wanted) {
  ByteReader r(bytes.substr(0, bytes.size() >= kCrcBytes ? bytes.size() - kCrcBytes : 0), source);
  ByteReader header_reader(bytes, source);
  Parsed p;
  const Header header = readHeader(bytes, header_reader);
  p.version = header.version;
  p.kind = header.kind;
  if (p.kind != wanted)
    r.fail(std::string("this file holds ") + kindName(p.kind) + ", where " + kindName(wanted) + " was expected");
  r.take(kHeaderBytes, "header");
  readMetadata(r, p);
  p.precision = readWeightEncoding(r, p.version);
  readArchitecture(r, p);
  validateRepresentation(r, p);
  const std::uint32_t count = readCount(r, "tensor count", 12);
  if (count > 9 + kMaxStyleTargets) r.fail("corrupt network file: " + std::to_string(count) + " tensors");
  for (std::uint32_t i = 0; i < count; ++i) p.tensors.push_back(r.tensor(p.precision));
  if (r.remaining() != 0) r.fail("corrupt network file: " + std::to_string(r.remaining()) + " unread bytes");
  return p;
}

std::string readWholeFile(const std::filesystem::path& file) { return readFileBytes(file, kMaxFileBytes, "network file"); }

}  // namespace

std::string serialiseLossNetwork(const LossNetworkModel& model, WeightPrecision precision) {
  return serialise(NetworkKind::LossNetwork, model.normalisation, model.metadata, model.network, nullptr, precision,
                   kNetworkFormatVersion);
}

std::string serialiseLossNetworkFormat1(const LossNetworkModel& model) {
  return serialise(NetworkKind::LossNetwork, model.normalisation, model.metadata, model.network, nullptr,
                   WeightPrecision::F32, 1);
}

std::string serialiseStyleModel(const StyleModel& model, WeightPrecision precision) {
  if (model.transformation.shape().features != model.loss_network.shape().features)
    throw std::invalid_argument("StyleModel: transformation and loss network feature counts differ");
  return serialise(NetworkKind::Style, model.normalisation, model.metadata, model.loss_network, &model.transformation,
                   precision, kNetworkFormatVersion, model.style_targets);
}

void saveLossNetwork(const LossNetworkModel& model, const std::filesystem::path& file, WeightPrecision precision) {
  writeFileAtomically(file, serialiseLossNetwork(model, precision));
}

void saveStyleModel(const StyleModel& model, const std::filesystem::path& file, WeightPrecision precision) {
  writeFileAtomically(file, serialiseStyleModel(model, precision));
}

LossNetworkModel parseLossNetwork(std::string_view bytes, const std::string& source_name) {
  Parsed p = parse(bytes, source_name, NetworkKind::LossNetwork);
  ByteReader r(std::string_view(), source_name);  // for messages
  LossNetworkModel model{LossNetwork<float>(p.loss_network_shape), std::move(p.normalisation), std::move(p.metadata)};
  std::size_t next = 0;
  assignConv(r, p.tensors, next, model.network.encoder);
  assignConv(r, p.tensors, next, model.network.decoder);
  if (next != p.tensors.size()) r.fail("network file: unexpected extra tensors");
  return model;
}

StyleModel parseStyleModel(std::string_view bytes, const std::string& source_name) {
  Parsed p = parse(bytes, source_name, NetworkKind::Style);
  ByteReader r(std::string_view(), source_name);
  if (p.t_shape.features != p.loss_network_shape.features)
    r.fail("network file: transformation and loss network feature counts differ");
  StyleModel model{TransformationNetwork<float>(p.t_shape), LossNetwork<float>(p.loss_network_shape), std::move(p.normalisation),
                   std::move(p.metadata), {}};
  std::size_t next = 0;
  assignConv(r, p.tensors, next, model.transformation.conv1);
  assignConv(r, p.tensors, next, model.transformation.conv2);
  assignConv(r, p.tensors, next, model.transformation.conv3);
  assignConv(r, p.tensors, next, model.loss_network.encoder);
  assignConv(r, p.tensors, next, model.loss_network.decoder);
  const auto hidden = static_cast<Eigen::Index>(p.loss_network_shape.hidden);
  for (; next < p.tensors.size(); ++next) {
    ByteReader::Tensor& t = p.tensors[next];
    if (p.version < 3 || t.name.rfind(kStyleTargetPrefix, 0) != 0)
      r.fail("network file: unexpected extra tensor '" + t.name + "'");
    if (t.value.rows() != hidden || t.value.cols() != hidden || !t.value.allFinite())
      r.fail("network file: style target '" + t.name + "' must be a finite " + std::to_string(hidden) + " x " +
             std::to_string(hidden) + " matrix");
    if (std::string problem = valuesProblem(t.name, t.value, kMaxStyleTargetMagnitude); !problem.empty())
      r.fail("corrupt network file: " + problem);
    std::string label = t.name.substr(std::string_view(kStyleTargetPrefix).size());
    for (const StyleTarget& earlier : model.style_targets)
      if (earlier.label == label) r.fail("network file: style target '" + t.name + "' appears twice");
    model.style_targets.push_back({std::move(label), std::move(t.value)});
  }
  return model;
}

LossNetworkModel loadLossNetwork(const std::filesystem::path& file) {
  return parseLossNetwork(readWholeFile(file), file.string());
}

StyleModel loadStyleModel(const std::filesystem::path& file) { return parseStyleModel(readWholeFile(file), file.string()); }

NetworkFileInfo networkFileInfo(std::string_view bytes, const std::string& source_name) {
  ByteReader header_reader(bytes, source_name);
  const Header header = readHeader(bytes, header_reader);
  // Full validation (tensor names, shapes, finite weights), not just the header.
  const Parsed p = parse(bytes, source_name, header.kind);
  if (header.kind == NetworkKind::Style)
    parseStyleModel(bytes, source_name);
  else
    parseLossNetwork(bytes, source_name);
  return {p.version, p.kind, p.precision, bytes.size()};
}

NetworkFileInfo networkFileInfo(const std::filesystem::path& file) {
  return networkFileInfo(readWholeFile(file), file.string());
}

NetworkKind networkFileKind(const std::filesystem::path& file) { return networkFileInfo(file).kind; }

void checkCompatible(const RepresentationInfo& actual, const RepresentationInfo& expected, const std::string& file) {
  std::ostringstream differences;
  if (actual.feature_count != expected.feature_count)
    differences << " features " << actual.feature_count << " (expected " << expected.feature_count << ");";
  if (actual.joint_set != expected.joint_set) {
    differences << " joint set '" << actual.joint_set << "' (expected '" << expected.joint_set << "'";
    if (actual.joint_set == kCanonicalJointSetName && expected.joint_set == kRetargetedJointSetName)
      differences << ": trained before proportion retargeting, retrain it with this version";
    if (actual.joint_set == kProportionsJointSetName && expected.joint_set == kRetargetedJointSetName)
      differences << ": trained before rig canonicalisation, retrain it with this version";
    differences << ");";
  }
  if (std::abs(actual.fps - expected.fps) > 1e-6 * expected.fps)
    differences << " " << actual.fps << " fps (expected " << expected.fps << ");";
  if (std::abs(actual.reference_body_height_cm - expected.reference_body_height_cm) > 1e-6 * expected.reference_body_height_cm)
    differences << " reference height " << actual.reference_body_height_cm << " cm (expected "
                << expected.reference_body_height_cm << ");";
  const std::string text = differences.str();
  if (!text.empty()) throw InputError(file, 0, "network trained on another representation:" + text);
}

}  // namespace motionstyle::nn
