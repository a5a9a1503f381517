// Layers: invalid input first, then forward definitions against naive loops, then gradient checks.

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "conv_reference.h"
#include "gradient_check.h"
#include "nn/conv1d.h"
#include "nn/init.h"
#include "nn/layers.h"

namespace motionstyle::nn {
namespace {

using test::checkGradient;
using test::expectConvGradientsMatch;
using test::naiveConv;
using test::randomConv;
using test::kGradientTolerance;
using test::MatD;
using test::randomMatrix;

TEST(Conv1dInvalid, RejectsBadConstructionAndShapes) {
  EXPECT_THROW(Conv1d<double>("even", 3, 4, 4, true), std::invalid_argument);
  EXPECT_THROW(Conv1d<double>("zero", 0, 4, 3, true), std::invalid_argument);
  Conv1d<double> conv("c", 3, 4, 3, true);
  EXPECT_THROW(conv.apply(MatD::Zero(2, 10), 5), std::invalid_argument);  // wrong channels
  EXPECT_THROW(conv.apply(MatD::Zero(3, 10), 4), std::invalid_argument);  // not whole windows
  EXPECT_THROW(conv.apply(MatD::Zero(3, 10), 0), std::invalid_argument);
  EXPECT_THROW(conv.backward(MatD::Zero(4, 10)), std::logic_error);       // before forward
  conv.forward(MatD::Zero(3, 10), 5);
  EXPECT_THROW(conv.backward(MatD::Zero(3, 10)), std::invalid_argument);  // wrong channels
  EXPECT_THROW(conv.backward(MatD::Zero(4, 5)), std::invalid_argument);   // other batch
}

TEST(LayersInvalid, RejectsOddPoolingAndMismatchedGradients) {
  EXPECT_THROW(MaxPool2<double>::apply(MatD::Zero(2, 6), 3), std::invalid_argument);
  MaxPool2<double> pool;
  pool.forward(MatD::Zero(2, 8), 4);
  EXPECT_THROW(pool.backward(MatD::Zero(2, 3)), std::invalid_argument);
  Relu<double> relu;
  relu.forward(MatD::Zero(2, 4));
  EXPECT_THROW(relu.backward(MatD::Zero(3, 4)), std::invalid_argument);
  EXPECT_THROW(AverageDepool2<double>::backward(MatD::Zero(2, 3)), std::invalid_argument);
  Parameter<double> bias;
  bias.resize(3, 1);
  SubtractSharedBias<double> subtract(&bias);
  EXPECT_THROW(subtract.apply(MatD::Zero(2, 4)), std::invalid_argument);
  EXPECT_THROW(SubtractSharedBias<double>().apply(MatD::Zero(3, 4)), std::logic_error);
  Dropout<double> dropout;
  std::mt19937 rng(1);
  EXPECT_THROW(dropout.forward(MatD::Zero(2, 2), 1.0, rng), std::invalid_argument);
  EXPECT_THROW(padToEvenFrames<double>(MatD::Zero(2, 7), 3), std::invalid_argument);
}

TEST(Conv1d, MatchesNaiveLoopsOverRandomShapesWithoutMixingWindows) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 12; ++trial) {
    const int in = 1 + static_cast<int>(rng() % 5);
    const int out = 1 + static_cast<int>(rng() % 6);
    const int width = 1 + 2 * static_cast<int>(rng() % 4);  // 1..7
    const int frames = 1 + static_cast<int>(rng() % 9);    // may be shorter than the kernel
    const int windows = 1 + static_cast<int>(rng() % 3);
    Conv1d<double> conv = randomConv(in, out, width, trial % 2 == 0, rng);
    const MatD x = randomMatrix(in, windows * frames, rng);
    const MatD expected = naiveConv(conv, x, frames);
    EXPECT_LT((conv.apply(x, frames) - expected).cwiseAbs().maxCoeff(), 1e-12) << "trial " << trial;
    EXPECT_LT((conv.forward(x, frames) - expected).cwiseAbs().maxCoeff(), 1e-12) << "trial " << trial;
  }
}

TEST(Conv1d, LargeBatchUsesThePoolAndStillMatches) {
  std::mt19937 rng(5);
  Conv1d<double> conv = randomConv(6, 7, 5, true, rng);
  const MatD x = randomMatrix(6, 4 * 150, rng);
  EXPECT_LT((conv.apply(x, 150) - naiveConv(conv, x, 150)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(Conv1dGradient, InputWeightsAndBiasOverRandomShapes) {
  std::mt19937 rng(12);
  for (int trial = 0; trial < 10; ++trial) {
    const int in = 1 + static_cast<int>(rng() % 4);
    const int out = 1 + static_cast<int>(rng() % 4);
    const int width = 1 + 2 * static_cast<int>(rng() % 3);
    const int frames = 1 + static_cast<int>(rng() % 7);
    const int windows = 1 + static_cast<int>(rng() % 3);
    Conv1d<double> conv = randomConv(in, out, width, true, rng);
    expectConvGradientsMatch(conv, frames, windows, 0, rng, trial);
  }
}

TEST(Conv1dGradient, AccumulatesAndHonoursTheRequestedGradients) {
  std::mt19937 rng(13);
  Conv1d<double> conv = randomConv(2, 3, 3, true, rng);
  const MatD x = randomMatrix(2, 8, rng);
  const MatD r = randomMatrix(3, 8, rng);
  conv.zeroGrad();
  conv.forward(x, 4);
  conv.backward(r, Gradients::All);
  const MatD once = conv.weight.grad;
  EXPECT_EQ(conv.backward(r, Gradients::ParametersOnly).size(), 0);
  EXPECT_LT((conv.weight.grad - 2 * once).cwiseAbs().maxCoeff(), 1e-12);  // added, not overwritten
  const MatD twice = conv.weight.grad;
  conv.backward(r, Gradients::InputOnly);
  EXPECT_EQ(conv.weight.grad, twice);  // untouched
  conv.zeroGrad();
  EXPECT_EQ(conv.weight.grad.cwiseAbs().maxCoeff(), 0.0);
}

TEST(LayerForward, PoolDepoolAndBiasFollowTheirDefinitions) {
  MatD x(1, 4);
  x << 1, 3, -2, -5;
  const MatD pooled = MaxPool2<double>::apply(x, 4);
  EXPECT_EQ(pooled(0, 0), 3);
  EXPECT_EQ(pooled(0, 1), -2);
  const MatD depooled = AverageDepool2<double>::apply(pooled);
  ASSERT_EQ(depooled.cols(), 4);
  // Average depooling: each pair averages to the pooled value.
  EXPECT_EQ(depooled(0, 0), 3);
  EXPECT_EQ(depooled(0, 1), 3);
  EXPECT_EQ(depooled(0, 2), -2);
  EXPECT_EQ(depooled(0, 3), -2);
  EXPECT_EQ(Relu<double>::apply(x)(0, 2), 0);
}

TEST(LayerGradient, ReluPoolDepoolBiasDropoutPadding) {
  std::mt19937 rng(21);
  for (int trial = 0; trial < 5; ++trial) {
    const int channels = 1 + static_cast<int>(rng() % 4);
    const int frames = 2 * (1 + static_cast<int>(rng() % 4));
    const int windows = 1 + static_cast<int>(rng() % 3);
    const Eigen::Index n = static_cast<Eigen::Index>(windows) * frames;
    MatD x = randomMatrix(channels, n, rng);
    {
      Relu<double> relu;
      const MatD r = randomMatrix(channels, n, rng);
      relu.forward(x);
      auto loss = [&] { return Relu<double>::apply(x).cwiseProduct(r).sum(); };
      EXPECT_LT(checkGradient(x, relu.backward(r), loss, 0, rng).max_error, kGradientTolerance);
    }
    {
      MaxPool2<double> pool;
      const MatD r = randomMatrix(channels, n / 2, rng);
      pool.forward(x, frames);
      auto loss = [&] { return MaxPool2<double>::apply(x, frames).cwiseProduct(r).sum(); };
      EXPECT_LT(checkGradient(x, pool.backward(r), loss, 0, rng).max_error, kGradientTolerance);
    }
    {
      const MatD r = randomMatrix(channels, 2 * n, rng);
      auto loss = [&] { return AverageDepool2<double>::apply(x).cwiseProduct(r).sum(); };
      EXPECT_LT(checkGradient(x, AverageDepool2<double>::backward(r), loss, 0, rng).max_error,
                kGradientTolerance);
    }
    {
      Parameter<double> bias;
      bias.resize(channels, 1);
      bias.value = randomMatrix(channels, 1, rng);
      SubtractSharedBias<double> subtract(&bias);
      const MatD r = randomMatrix(channels, n, rng);
      auto loss = [&] { return subtract.apply(x).cwiseProduct(r).sum(); };
      const MatD dx = subtract.backward(r, true);
      EXPECT_LT(checkGradient(x, dx, loss, 0, rng).max_error, kGradientTolerance);
      const MatD db = bias.grad;
      EXPECT_LT(checkGradient(bias.value, db, loss, 0, rng).max_error, kGradientTolerance);
    }
    {
      Dropout<double> dropout;
      std::mt19937 mask_rng(99);
      const MatD r = randomMatrix(channels, n, rng);
      const MatD y = dropout.forward(x, 0.25, mask_rng);
      const MatD dx = dropout.backward(r);
      // Linear in x with a fixed mask: y / x is the per-entry scale, which backward must reuse.
      EXPECT_LT((dx - r.cwiseProduct(y.cwiseQuotient(x))).cwiseAbs().maxCoeff(), 1e-12);
    }
    {
      const int odd = frames - 1 > 0 ? frames - 1 : 1;
      MatD xo = randomMatrix(channels, static_cast<Eigen::Index>(windows) * odd, rng);
      const MatD r = randomMatrix(channels, static_cast<Eigen::Index>(windows) * evenFrames(odd), rng);
      auto loss = [&] { return padToEvenFrames(xo, odd).cwiseProduct(r).sum(); };
      EXPECT_LT(checkGradient(xo, foldEvenPaddingGradient(r, odd), loss, 0, rng).max_error,
                kGradientTolerance);
      MatD xp = randomMatrix(channels, static_cast<Eigen::Index>(windows) * evenFrames(odd), rng);
      const MatD rc = randomMatrix(channels, static_cast<Eigen::Index>(windows) * odd, rng);
      auto crop_loss = [&] { return cropToFrames(xp, odd).cwiseProduct(rc).sum(); };
      EXPECT_LT(checkGradient(xp, uncropGradient(rc, odd), crop_loss, 0, rng).max_error,
                kGradientTolerance);
    }
  }
}

TEST(Dropout, IsDeterministicInTheSeedAndKeepsTheExpectation) {
  std::mt19937 a(3);
  std::mt19937 b(3);
  Dropout<double> first;
  Dropout<double> second;
  const MatD ones = MatD::Ones(50, 200);
  const MatD ya = first.forward(ones, 0.25, a);
  EXPECT_EQ(ya, second.forward(ones, 0.25, b));
  EXPECT_NEAR(ya.mean(), 1.0, 0.03);
  const double dropped = static_cast<double>((ya.array() == 0.0).count()) / static_cast<double>(ya.size());
  EXPECT_NEAR(dropped, 0.25, 0.02);
}

TEST(Init, SameSeedGivesIdenticalWeightsAndSchemesHaveTheirBounds) {
  Conv1d<float> a("a", 66, 128, 25, true);
  Conv1d<float> b("b", 66, 128, 25, true);
  std::mt19937 ra(7);
  std::mt19937 rb(7);
  initialiseConv(a, InitScheme::HeUniform, ra);
  initialiseConv(b, InitScheme::HeUniform, rb);
  EXPECT_EQ(a.weight.value, b.weight.value);
  const float he = std::sqrt(6.0f / (66.0f * 25.0f));
  EXPECT_LE(a.weight.value.cwiseAbs().maxCoeff(), he);
  EXPECT_GT(a.weight.value.cwiseAbs().maxCoeff(), 0.9f * he);
  std::mt19937 rc(8);
  initialiseConv(b, InitScheme::HeUniform, rc);
  EXPECT_NE(a.weight.value, b.weight.value);
}

}  // namespace
}  // namespace motionstyle::nn
