// The PyTorch reference check (issue 14, in the spirit of llm.c): one training batch through the
// transformation network T and the frozen loss network L, compared with an independent PyTorch
// implementation of the same formulas (tests/peer/dump_reference.py, which wrote
// tests/data/nn_reference.txt and documents its format and definitions).
//
// Contract: with the file's weights and inputs, the C++ reproduces PyTorch's L(I), Gram(L(S)), T(I),
// L(T(I)), the five unweighted eq. 10 terms and their weighted total, and d total / d parameter for
// every parameter of T, each entry within kRelativeTolerance of the reference:
//     |cpp - torch| <= kRelativeTolerance * max(|torch|, kScaleFloor * max_i |torch_i|)
// (the floor compares entries near zero, where sums cancel, at the scale of their tensor).
// Why: the gradient checks (losses_test, networks_test) prove that backward matches forward; only a
// second implementation shows that forward computes the paper's networks and losses.
// Both sides run in float64 on identical inputs; observed differences are ~1e-15 relative
// (docs/decisions.md), so 1e-9 leaves room for summation order, FFTs and other libms while a real
// error (a wrong weight, sign, normalisation or joint) moves values by far more.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "nn/loss_network.h"
#include "nn/transformation_objective.h"
#include "nn/transformation_network.h"
#include "test_paths.h"

namespace motionstyle::nn {
namespace {

using MatD = Mat<double>;

constexpr double kRelativeTolerance = 1e-9;
constexpr double kScaleFloor = 1e-3;
constexpr const char* kRegenerate = "/usr/bin/python3 tests/peer/dump_reference.py tests/data/nn_reference.txt";

// One record of the file: dims (row-major, last index fastest) and the values.
struct ReferenceTensor {
  std::vector<int> dims;
  std::vector<double> values;
};

// Reads the format documented in dump_reference.py; throws std::runtime_error naming the line.
std::map<std::string, ReferenceTensor> readReference(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path.string() + " (regenerate: " + kRegenerate + ")");
  std::map<std::string, ReferenceTensor> tensors;
  std::string line;
  int line_number = 0;
  auto fail = [&](const std::string& why) {
    throw std::runtime_error(path.string() + ":" + std::to_string(line_number) + ": " + why);
  };
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream header(line);
    std::string keyword, name;
    int rank = -1;
    if (!(header >> keyword >> name >> rank) || keyword != "tensor" || rank < 0)
      fail("expected 'tensor NAME RANK DIMS...'");
    ReferenceTensor t;
    std::size_t count = 1;
    for (int i = 0; i < rank; ++i) {
      int d = 0;
      if (!(header >> d) || d < 1) fail("bad dimension of " + name);
      t.dims.push_back(d);
      count *= static_cast<std::size_t>(d);
    }
    t.values.reserve(count);
    while (t.values.size() < count) {
      if (!std::getline(in, line)) fail(name + ": file ends after " + std::to_string(t.values.size()) + " values");
      ++line_number;
      const char* p = line.c_str();
      char* end = nullptr;
      for (double v = std::strtod(p, &end); end != p; v = std::strtod(p, &end)) {  // exact round trip
        t.values.push_back(v);
        p = end;
      }
      while (*p == ' ') ++p;
      if (*p != '\0') fail(name + ": not a number: " + std::string(p));
    }
    if (t.values.size() != count) fail(name + ": too many values");
    if (!tensors.emplace(name, std::move(t)).second) fail("duplicate tensor " + name);
  }
  return tensors;
}

// "name[i][j][k]" for a flat row-major index.
std::string indexName(const std::string& name, const std::vector<int>& dims, std::size_t flat) {
  std::vector<std::size_t> index(dims.size());
  for (std::size_t a = dims.size(); a-- > 0;) {
    index[a] = flat % static_cast<std::size_t>(dims[a]);
    flat /= static_cast<std::size_t>(dims[a]);
  }
  std::string text = name;
  for (std::size_t i : index) text += "[" + std::to_string(i) + "]";
  return text;
}

class PyTorchReference : public ::testing::TestWithParam<ConvAlgorithm> {
 protected:
  static void SetUpTestSuite() {
    try {
      file_ = new auto(readReference(test::fixture("nn_reference.txt")));
    } catch (const std::exception& error) {
      load_error_ = error.what();
    }
  }
  static void TearDownTestSuite() {
    delete file_;
    file_ = nullptr;
  }

  static const ReferenceTensor& tensor(const std::string& name) {
    const auto found = file_->find(name);
    if (found == file_->end()) throw std::runtime_error("nn_reference.txt has no tensor " + name);
    return found->second;
  }
  static const ReferenceTensor& tensor(const std::string& name, const std::vector<int>& dims) {
    const ReferenceTensor& t = tensor(name);
    if (t.dims != dims) throw std::runtime_error("nn_reference.txt: " + name + " has unexpected dimensions");
    return t;
  }
  double scalar(const std::string& name) const { return tensor(name, {}).values[0]; }
  int config(const std::string& name) const { return static_cast<int>(scalar("config." + name)); }

  // [B, C, T] -> C x (B*T) (tensor.h's batch layout).
  MatD batch(const std::string& name, int channels, int frames) const {
    const int windows = config("windows");
    const ReferenceTensor& t = tensor(name, {windows, channels, frames});
    MatD m(channels, windows * frames);
    for (int b = 0; b < windows; ++b)
      for (int c = 0; c < channels; ++c)
        for (int f = 0; f < frames; ++f)
          m(c, b * frames + f) = t.values[static_cast<std::size_t>((b * channels + c) * frames + f)];
    return m;
  }
  // [out, in, tap] -> W(o, tap*in + c) (tensor.h's tap-major convolution weight).
  static void loadConv(Conv1d<double>& conv, const ReferenceTensor& weight, const ReferenceTensor& bias) {
    const int out = conv.outChannels(), in = conv.inChannels(), width = conv.width();
    for (int o = 0; o < out; ++o) {
      for (int c = 0; c < in; ++c)
        for (int k = 0; k < width; ++k)
          conv.weight.value(o, k * in + c) = weight.values[static_cast<std::size_t>((o * in + c) * width + k)];
      conv.bias.value(o, 0) = bias.values[static_cast<std::size_t>(o)];
    }
    conv.setAlgorithm(GetParam());
  }
  std::vector<std::pair<const char*, Conv1d<double>*>> transformerLayers() {
    return {{"conv1", &transformer_.conv1}, {"conv2", &transformer_.conv2}, {"conv3", &transformer_.conv3}};
  }
  void loadNetworks() {
    const int width = config("width");
    transformer_ = TransformationNetwork<double>({config("features"), config("t_hidden"), width, config("residual") != 0});
    loss_network_ = LossNetwork<double>({config("features"), config("ae_hidden"), width});
    for (const auto& [layer, conv] : transformerLayers()) {
      const std::string prefix = std::string("transformer.") + layer;
      loadConv(*conv, tensor(prefix + ".weight", {conv->outChannels(), conv->inChannels(), width}),
               tensor(prefix + ".bias", {conv->outChannels()}));
    }
    const Conv1d<double>& encoder = loss_network_.encoder;
    loadConv(loss_network_.encoder,
             tensor("loss_network.encoder.weight", {encoder.outChannels(), encoder.inChannels(), width}),
             tensor("loss_network.encoder.bias", {encoder.outChannels()}));
  }

  void SetUp() override {
    ASSERT_NE(file_, nullptr) << load_error_;
    loadNetworks();
    const int frames = config("frames"), windows = config("windows");
    for (auto [name, target] : {std::pair{"normalisation.mean", &normalisation_.mean},
                                std::pair{"normalisation.std", &normalisation_.std}})
      *target = Eigen::Map<const Eigen::VectorXd>(tensor(name, {kFeatureCount}).values.data(), kFeatureCount);
    weights_ = {scalar("weights.content"), scalar("weights.style"), scalar("weights.foot"), scalar("weights.bone"),
                scalar("weights.trajectory")};
    batch_.frames = frames;
    batch_.content = batch("input.content", kFeatureCount, frames);
    batch_.contacts = batch("input.contacts", kContactCount, frames);
    const ReferenceTensor& lengths = tensor("input.bone_lengths", {windows, kBoneCount});
    batch_.bone_lengths.resize(kBoneCount, windows);
    for (int b = 0; b < windows; ++b)
      for (int i = 0; i < kBoneCount; ++i)
        batch_.bone_lengths(i, b) = lengths.values[static_cast<std::size_t>(b * kBoneCount + i)];
    const int style_frames = config("style_frames");
    const ReferenceTensor& style = tensor("input.style_clip", {kFeatureCount, style_frames});
    style_clip_ = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        style.values.data(), kFeatureCount, style_frames);
    // The training pipeline's own targets (transformation_objective.h), compared with the reference in their own test.
    batch_.content_hidden = contentHidden(loss_network_, batch_.content, frames);
    batch_.style_grams = {styleGram(loss_network_, style_clip_)};
  }

  // Compares `actual(flat index)` with the reference tensor `name`, entry by entry; names the first
  // mismatching entries by index. Prints the largest relative difference (for docs/decisions.md).
  void expectMatches(const std::string& name, const std::function<double(std::size_t)>& actual) const {
    const ReferenceTensor& reference = tensor(name);
    double scale = 0;
    for (double v : reference.values) scale = std::max(scale, std::abs(v));
    const double floor = std::max(kScaleFloor * scale, 1e-300);
    double worst = 0;
    int mismatches = 0;
    for (std::size_t i = 0; i < reference.values.size(); ++i) {
      const double want = reference.values[i], got = actual(i);
      const double error = std::abs(got - want) / std::max(std::abs(want), floor);
      worst = std::max(worst, std::isnan(error) ? std::numeric_limits<double>::infinity() : error);
      if (!(error <= kRelativeTolerance) && ++mismatches <= 5)
        ADD_FAILURE() << indexName(name, reference.dims, i) << ": C++ " << got << ", PyTorch " << want
                      << " (relative difference " << error << " > " << kRelativeTolerance << ")";
    }
    EXPECT_EQ(mismatches, 0) << name << ": " << mismatches << " of " << reference.values.size()
                             << " entries differ; if the C++ definition changed on purpose, change the peer "
                             << "and regenerate: " << kRegenerate;
    std::printf("  %-44s %5zu values, max relative difference %.2e\n", name.c_str(), reference.values.size(), worst);
  }
  // A C++ batch matrix C x (B*T) against a [B, C, T] reference.
  void expectBatchMatches(const std::string& name, const MatD& m, int frames) const {
    const auto channels = static_cast<std::size_t>(m.rows());
    const auto t = static_cast<std::size_t>(frames);
    ASSERT_EQ(m.cols() % frames, 0);
    expectMatches(name, [&](std::size_t i) {
      const std::size_t b = i / (channels * t), c = (i / t) % channels, f = i % t;
      return m(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(b * t + f));
    });
  }
  void expectTermsMatch(const ObjectiveTerms& terms) const {
    const std::map<std::string, double> values = {{"content", terms.content}, {"style", terms.style},
                                                  {"foot", terms.foot},       {"bone", terms.bone},
                                                  {"trajectory", terms.trajectory}, {"total", terms.total}};
    for (const auto& [term, value] : values)
      expectMatches("expected.terms." + term, [&value](std::size_t) { return value; });
  }

  static inline const std::map<std::string, ReferenceTensor>* file_ = nullptr;
  static inline std::string load_error_;
  TransformationNetwork<double> transformer_;
  LossNetwork<double> loss_network_;
  FeatureStatistics normalisation_;
  LossWeights weights_;
  StyleBatch<double> batch_;
  MatD style_clip_;
};

TEST_P(PyTorchReference, LossNetworkTargets) {
  expectBatchMatches("expected.content_hidden", batch_.content_hidden, batch_.frames / 2);
  const MatD& gram = batch_.style_grams[0];
  expectMatches("expected.style_gram", [&](std::size_t i) {
    return gram(static_cast<Eigen::Index>(i) / gram.cols(), static_cast<Eigen::Index>(i) % gram.cols());
  });
}

TEST_P(PyTorchReference, ForwardOutput) {
  const MatD output = transformer_.apply(batch_.content, batch_.frames);
  expectBatchMatches("expected.output", output, batch_.frames);
  expectBatchMatches("expected.output_hidden", loss_network_.encode(output, batch_.frames), batch_.frames / 2);
  // The training pass's forward (with caches) is the same function.
  expectBatchMatches("expected.output", transformer_.forward(batch_.content, batch_.frames), batch_.frames);
}

TEST_P(PyTorchReference, LossTerms) {
  expectTermsMatch(evaluateObjective(transformer_, loss_network_, batch_, normalisation_, weights_));
}

TEST_P(PyTorchReference, ParameterGradients) {
  transformer_.zeroGrad();
  const ObjectiveTerms terms = accumulateObjective(transformer_, loss_network_, batch_, normalisation_, weights_);
  expectTermsMatch(terms);
  const int width = config("width");
  for (const auto& [layer, conv] : transformerLayers()) {
    const int in = conv->inChannels();
    const MatD& weight_grad = conv->weight.grad;
    expectMatches(std::string("expected.grad.transformer.") + layer + ".weight", [&](std::size_t i) {  // [out, in, tap]
      const auto o = static_cast<Eigen::Index>(i / static_cast<std::size_t>(in * width));
      const auto c = static_cast<Eigen::Index>((i / static_cast<std::size_t>(width)) % static_cast<std::size_t>(in));
      const auto k = static_cast<Eigen::Index>(i % static_cast<std::size_t>(width));
      return weight_grad(o, k * in + c);
    });
    const MatD& bias_grad = conv->bias.grad;
    expectMatches(std::string("expected.grad.transformer.") + layer + ".bias",
                  [&](std::size_t i) { return bias_grad(static_cast<Eigen::Index>(i), 0); });
  }
  // The loss network is frozen: accumulateObjective must leave its gradients alone.
  EXPECT_EQ(loss_network_.encoder.weight.grad.cwiseAbs().maxCoeff(), 0.0);
}

INSTANTIATE_TEST_SUITE_P(Conv, PyTorchReference,
                         ::testing::Values(ConvAlgorithm::Direct, ConvAlgorithm::Spectral),
                         [](const ::testing::TestParamInfo<ConvAlgorithm>& algorithm) {
                           return std::string(algorithm.param == ConvAlgorithm::Direct ? "Direct" : "Spectral");
                         });

}  // namespace
}  // namespace motionstyle::nn
