// The spectral (overlap-save) evaluation of the convolution: invalid use first, then agreement with
// the definition and with the direct path, then gradient checks of the spectral path in double.

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "conv_reference.h"
#include "gradient_check.h"
#include "nn/conv1d.h"
#include "nn/spectral_correlation.h"

namespace motionstyle::nn {
namespace {

using test::checkGradient;
using test::expectConvGradientsMatch;
using test::kGradientTolerance;
using test::MatD;
using test::naiveConv;
using test::randomConv;
using test::randomMatrix;

double relativeDifference(const MatD& a, const MatD& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, b.cwiseAbs().maxCoeff());
}

TEST(SpectralCorrelationInvalid, RejectsBadShapesAndOutOfOrderCalls) {
  EXPECT_THROW(SpectralCorrelation<double>(0, 2, 3, 8), std::invalid_argument);
  EXPECT_THROW(SpectralCorrelation<double>(2, 2, 4, 8), std::invalid_argument);  // even width
  EXPECT_THROW(SpectralCorrelation<double>(2, 2, 3, 0), std::invalid_argument);
  EXPECT_THROW(SpectralCorrelation<double>(2, 2, 3, 12), std::invalid_argument);  // not a power of two
  EXPECT_THROW(SpectralCorrelation<double>(2, 2, 9, 8), std::invalid_argument);   // shorter than the kernel
  SpectralCorrelation<double> spectral(2, 3, 3, 8);
  EXPECT_THROW(spectral.setKernel(MatD::Zero(3, 5)), std::invalid_argument);
  MatD padded = MatD::Zero(2, 20);
  MatD out(3, 18);
  EXPECT_THROW(spectral.forward(padded.data(), padded.cols(), 18, out.data()), std::logic_error);  // no kernel
  spectral.setKernel(MatD::Ones(3, 6));
  spectral.forward(padded.data(), padded.cols(), 18, out.data());
  MatD grad = MatD::Zero(3, 17);
  EXPECT_THROW(spectral.backward(grad.data(), 17, nullptr, nullptr), std::logic_error);  // other count
  MatD wrong_shape = MatD::Zero(3, 3);
  MatD grad_ok = MatD::Zero(3, 18);
  EXPECT_THROW(spectral.backward(grad_ok.data(), 18, &wrong_shape, nullptr), std::invalid_argument);
}

TEST(SpectralCorrelation, SegmentsAndCostModelFollowTheirDefinitions) {
  EXPECT_EQ(defaultSpectralPoints(25), 64);  // L = 40 output frames per segment for the default networks
  EXPECT_EQ(defaultSpectralPoints(13), 64);  // the polyphase decoder
  EXPECT_EQ(defaultSpectralPoints(3), 8);
  EXPECT_EQ(defaultSpectralPoints(1), 8);
  SpectralCorrelation<float> spectral(4, 4, 25, defaultSpectralPoints(25));
  EXPECT_EQ(spectral.points(), 64);
  EXPECT_EQ(spectral.block(), 40);
  EXPECT_EQ(spectral.bins(), 33);
  EXPECT_TRUE(spectralIsFaster(128, 128, 25, 16 * 240));
  EXPECT_TRUE(spectralIsFaster(66, 256, 25, 240));
  EXPECT_FALSE(spectralIsFaster(128, 128, 25, 60));  // shorter than two segments
  EXPECT_FALSE(spectralIsFaster(2, 3, 3, 100000));   // the transforms would cost more than they save
}

// Random shapes, including inputs shorter than one segment or than the kernel, lengths that are not
// a whole number of segments, several windows, width 1 and a block shorter than the kernel.
TEST(SpectralCorrelation, ForwardAndBackwardMatchTheDirectPathOverRandomShapes) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 16; ++trial) {
    const int in = 1 + static_cast<int>(rng() % 5);
    const int out = 1 + static_cast<int>(rng() % 6);
    const int width = 1 + 2 * static_cast<int>(rng() % 13);  // 1..25
    const int frames = 1 + static_cast<int>(rng() % 90);
    const int windows = 1 + static_cast<int>(rng() % 3);
    Conv1d<double> direct = randomConv(in, out, width, trial % 2 == 0, rng);
    direct.setAlgorithm(ConvAlgorithm::Direct);
    Conv1d<double> spectral = direct;
    spectral.setAlgorithm(ConvAlgorithm::Spectral);
    const MatD x = randomMatrix(in, windows * frames, rng);
    const MatD expected = naiveConv(direct, x, frames);
    EXPECT_LT(relativeDifference(spectral.apply(x, frames), expected), 1e-12) << "trial " << trial;
    EXPECT_LT(relativeDifference(spectral.forward(x, frames), expected), 1e-12) << "trial " << trial;

    const MatD r = randomMatrix(out, windows * frames, rng);
    direct.zeroGrad();
    spectral.zeroGrad();
    direct.forward(x, frames);
    const MatD dx_direct = direct.backward(r);
    const MatD dx_spectral = spectral.backward(r);
    EXPECT_LT(relativeDifference(dx_spectral, dx_direct), 1e-12) << "dx trial " << trial;
    EXPECT_LT(relativeDifference(spectral.weight.grad, direct.weight.grad), 1e-12) << "dW trial " << trial;
    if (direct.hasBias()) {
      EXPECT_LT(relativeDifference(spectral.bias.grad, direct.bias.grad), 1e-12);
    }
  }
}

TEST(SpectralCorrelation, FloatDefaultLayerAgreesWithTheDirectProductToRounding) {
  std::mt19937 rng(22);
  Conv1d<float> direct("t2", 128, 128, 25, true);
  direct.weight.value = randomMatrix(128, 128 * 25, rng, 0.05).cast<float>();
  direct.bias.value = randomMatrix(128, 1, rng).cast<float>();
  direct.setAlgorithm(ConvAlgorithm::Direct);
  Conv1d<float> spectral = direct;
  spectral.setAlgorithm(ConvAlgorithm::Spectral);
  const Mat<float> x = randomMatrix(128, 4 * 240, rng).cast<float>();
  // Relative to the largest entry, in double.
  auto difference = [](const Mat<float>& a, const Mat<float>& b) {
    return relativeDifference(a.cast<double>(), b.cast<double>());
  };
  EXPECT_LT(difference(spectral.forward(x, 240), direct.forward(x, 240)), 1e-5);
  const Mat<float> r = randomMatrix(128, 4 * 240, rng).cast<float>();
  direct.zeroGrad();
  spectral.zeroGrad();
  const Mat<float> dx_direct = direct.backward(r);
  const Mat<float> dx_spectral = spectral.backward(r);
  EXPECT_LT(difference(dx_spectral, dx_direct), 1e-5);
  EXPECT_LT(difference(spectral.weight.grad, direct.weight.grad), 1e-5);
}

// The kernel spectra are cached: a weight change (an optimiser step) must be seen by the next call.
// The inference-only layer (FastStylizer's): backward() refused, the forward pass the full layer's bit
// for bit, before and after a new kernel.
TEST(SpectralCorrelation, ForwardOnlyRefusesBackwardAndComputesTheSameForward) {
  std::mt19937 rng(29);
  SpectralCorrelation<double> full(3, 4, 5, 16), forward_only(3, 4, 5, 16, SpectralPasses::ForwardOnly);
  const MatD padded = randomMatrix(3, 64, rng);
  MatD expected(4, 60), out(4, 60);
  for (int kernel = 0; kernel < 2; ++kernel) {
    const MatD weight = randomMatrix(4, 15, rng);
    full.setKernel(weight);
    forward_only.setKernel(weight);
    full.forward(padded.data(), padded.cols(), 60, expected.data());
    forward_only.forward(padded.data(), padded.cols(), 60, out.data());
    EXPECT_EQ(out, expected);
  }
  MatD grad = MatD::Zero(4, 60);
  EXPECT_THROW(forward_only.backward(grad.data(), 60, nullptr, nullptr), std::logic_error);
  EXPECT_NO_THROW(full.backward(grad.data(), 60, nullptr, nullptr));
}

TEST(SpectralCorrelation, ChangedWeightsAreUsedByTheNextForward) {
  std::mt19937 rng(23);
  Conv1d<double> conv = randomConv(3, 4, 5, false, rng);
  conv.setAlgorithm(ConvAlgorithm::Spectral);
  const MatD x = randomMatrix(3, 50, rng);
  conv.forward(x, 50);
  conv.weight.value(2, 7) += 0.5;
  EXPECT_LT(relativeDifference(conv.forward(x, 50), naiveConv(conv, x, 50)), 1e-12);
}

// Copies share the prepared spectra (the stylizer's per-thread copies): a copy computes what the
// original does, and keeps its kernel when the original is given another (and the other way round).
TEST(SpectralCorrelation, ACopyKeepsItsKernelWhenTheOriginalGetsAnother) {
  std::mt19937 rng(26);
  const int in = 3, out = 4, width = 5, count = 70;
  const MatD first = randomMatrix(out, in * width, rng), second = randomMatrix(out, in * width, rng);
  const MatD padded = randomMatrix(in, count + width - 1, rng);
  const auto run = [&](SpectralCorrelation<double>& layer) {
    MatD y(out, count);
    layer.forward(padded.data(), padded.cols(), count, y.data());
    return y;
  };
  SpectralCorrelation<double> original(in, out, width, 16);
  original.setKernel(first);
  const MatD with_first = run(original);
  SpectralCorrelation<double> copy = original;
  EXPECT_EQ(run(copy), with_first);
  original.setKernel(second);
  const MatD with_second = run(original);
  EXPECT_GT((with_second - with_first).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_EQ(run(copy), with_first);
  copy.setKernel(second);
  EXPECT_EQ(run(copy), with_second);
  original.setKernel(first);
  EXPECT_EQ(run(original), with_first);
  EXPECT_EQ(run(copy), with_second);
}

TEST(SpectralCorrelationGradient, InputWeightsAndBiasOverRandomShapes) {
  std::mt19937 rng(24);
  for (int trial = 0; trial < 8; ++trial) {
    const int in = 1 + static_cast<int>(rng() % 4);
    const int out = 1 + static_cast<int>(rng() % 4);
    const int width = 1 + 2 * static_cast<int>(rng() % 6);
    const int frames = 1 + static_cast<int>(rng() % 30);
    const int windows = 1 + static_cast<int>(rng() % 3);
    Conv1d<double> conv = randomConv(in, out, width, true, rng);
    conv.setAlgorithm(ConvAlgorithm::Spectral);
    expectConvGradientsMatch(conv, frames, windows, 60, rng, trial);
  }
}

TEST(SpectralCorrelationGradient, HonoursTheRequestedGradients) {
  std::mt19937 rng(25);
  Conv1d<double> conv = randomConv(2, 3, 7, true, rng);
  conv.setAlgorithm(ConvAlgorithm::Spectral);
  const MatD x = randomMatrix(2, 40, rng);
  const MatD r = randomMatrix(3, 40, rng);
  conv.zeroGrad();
  conv.forward(x, 20);
  const MatD dx = conv.backward(r, Gradients::All);
  const MatD once = conv.weight.grad;
  EXPECT_EQ(conv.backward(r, Gradients::ParametersOnly).size(), 0);
  EXPECT_LT((conv.weight.grad - 2 * once).cwiseAbs().maxCoeff(), 1e-12);  // added, not overwritten
  const MatD twice = conv.weight.grad;
  EXPECT_LT(relativeDifference(conv.backward(r, Gradients::InputOnly), dx), 1e-14);
  EXPECT_EQ(conv.weight.grad, twice);  // untouched
}

}  // namespace
}  // namespace motionstyle::nn
