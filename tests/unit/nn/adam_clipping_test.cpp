// nn::Adam's outlier clipping (AdamOptions::gradient_clip): invalid options first, then its
// properties: ordinary gradients pass untouched, an outlier batch is cut to k x the expected norm
// before it reaches the moments, it is off by default and during the warm-up, and a restored
// optimiser clips exactly as the original.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "nn/adam.h"

namespace motionstyle::nn {
namespace {

Mat<double> gaussian(Eigen::Index rows, Eigen::Index cols, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Mat<double> m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = n(rng);
  return m;
}

AdamOptions clipping(double k, long warmup = 20) {
  AdamOptions options;
  options.learning_rate = 1e-3;
  options.gradient_clip = k;
  options.clip_warmup_steps = warmup;
  return options;
}

TEST(AdamClippingInvalid, RejectsNegativeOrNonFiniteSettings) {
  Parameter<double> p;
  p.resize(2, 2);
  EXPECT_THROW(Adam<double>({&p}, clipping(-1.0)), std::invalid_argument);
  EXPECT_THROW(Adam<double>({&p}, clipping(std::nan(""))), std::invalid_argument);
  EXPECT_THROW(Adam<double>({&p}, clipping(3.0, -1)), std::invalid_argument);
}

TEST(AdamClipping, OrdinaryGradientsPassAndAnOutlierIsCutToKTimesTheExpectedNorm) {
  std::mt19937 rng(41);
  Parameter<double> p;
  p.resize(64, 32);
  Adam<double> adam({&p}, clipping(3.0));
  for (int step = 0; step < 200; ++step) {  // unit-variance gradients: norm ~ sqrt(2048) = E[norm]
    p.grad = gaussian(64, 32, rng);
    adam.step();
    EXPECT_EQ(adam.clippedInLastStep(), 0) << "step " << step;
  }
  const double v_before = adam.secondMoments()[0].sum();
  p.grad = 1000.0 * gaussian(64, 32, rng);  // one outlier batch
  adam.step();
  EXPECT_EQ(adam.clippedInLastStep(), 1);
  // v = b2 v + (1 - b2) g'^2 with |g'|^2 = k^2 E|g|^2 = k^2 sum v^, v^ = v / (1 - b2^t): v grows by at most
  // 1 + (1 - b2) k^2 / (1 - b2^t), 5 % at t = 200 (the raw batch would have multiplied it by ~5,500).
  const double growth = adam.secondMoments()[0].sum() / v_before;
  const double bound = 1.0 + 0.001 * 9.0 / (1.0 - std::pow(0.999, 200));
  EXPECT_GT(growth, 1.0);
  EXPECT_LE(growth, bound);
}

TEST(AdamClipping, IsOffByDefaultAndDuringTheWarmUp) {
  std::mt19937 rng(42);
  Parameter<double> clipped, plain;
  clipped.resize(8, 8);
  plain.resize(8, 8);
  Adam<double> with(std::vector<Parameter<double>*>{&clipped}, clipping(3.0, 50));
  Adam<double> without(std::vector<Parameter<double>*>{&plain}, AdamOptions{1e-3});
  for (int step = 0; step < 50; ++step) {  // outliers inside the warm-up are not clipped
    const Mat<double> g = (step == 30 ? 1000.0 : 1.0) * gaussian(8, 8, rng);
    clipped.grad = g;
    plain.grad = g;
    with.step();
    without.step();
    EXPECT_EQ(with.clippedInLastStep(), 0);
  }
  EXPECT_EQ(clipped.value, plain.value);
  const Mat<double> outlier = 1000.0 * gaussian(8, 8, rng);
  clipped.grad = outlier;
  plain.grad = outlier;
  with.step();
  without.step();
  EXPECT_EQ(with.clippedInLastStep(), 1);
  EXPECT_EQ(without.clippedInLastStep(), 0);
  EXPECT_NE(clipped.value, plain.value);
}

TEST(AdamClipping, RestoredOptimiserClipsExactlyAsTheOriginal) {
  std::mt19937 rng(43);
  Parameter<double> a, b;
  a.resize(16, 4);
  b.resize(16, 4);
  Adam<double> original(std::vector<Parameter<double>*>{&a}, clipping(2.0, 5));
  for (int step = 0; step < 30; ++step) {
    a.grad = gaussian(16, 4, rng);
    original.step();
  }
  b.value = a.value;
  Adam<double> restored(std::vector<Parameter<double>*>{&b}, clipping(2.0, 5));
  restored.restore(original.stepCount(), original.firstMoments(), original.secondMoments());
  for (int step = 0; step < 10; ++step) {
    const Mat<double> g = (step % 3 == 0 ? 50.0 : 1.0) * gaussian(16, 4, rng);
    a.grad = g;
    b.grad = g;
    original.step();
    restored.step();
    EXPECT_EQ(original.clippedInLastStep(), restored.clippedInLastStep());
  }
  EXPECT_EQ(a.value, b.value);
}

}  // namespace
}  // namespace motionstyle::nn
