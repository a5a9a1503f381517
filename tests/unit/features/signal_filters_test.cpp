// Signal helpers of the representation (signal_filters.h): Gaussian smoothing against a direct clamped
// convolution, the alternation filter, the quantile and the median.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "features/signal_filters.h"

namespace motionstyle {
namespace {

// The definition, term by term: output t = sum over k of w(k) * signal(clamp(t + k)), w normalised.
Eigen::MatrixXd directGaussian(const Eigen::MatrixXd& signal, double sigma) {
  const auto radius = static_cast<Eigen::Index>(std::ceil(3.0 * sigma));
  auto weight = [&](Eigen::Index k) {
    const double x = static_cast<double>(k) / sigma;
    return std::exp(-0.5 * x * x);
  };
  double total = 0.0;
  for (Eigen::Index k = -radius; k <= radius; ++k) total += weight(k);
  Eigen::MatrixXd result = Eigen::MatrixXd::Zero(signal.rows(), signal.cols());
  for (Eigen::Index t = 0; t < signal.rows(); ++t)
    for (Eigen::Index k = -radius; k <= radius; ++k)
      result.row(t) += weight(k) / total * signal.row(std::clamp<Eigen::Index>(t + k, 0, signal.rows() - 1));
  return result;
}

Eigen::MatrixXd randomSignal(Eigen::Index frames, Eigen::Index columns, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> value(-50.0, 50.0);
  Eigen::MatrixXd signal(frames, columns);
  for (Eigen::Index i = 0; i < signal.size(); ++i) signal.data()[i] = value(rng);
  return signal;
}

TEST(GaussianSmoothRows, LeavesTheSignalAloneWithoutSmoothingOrFrames) {
  const Eigen::MatrixXd signal = randomSignal(9, 2, 1);
  EXPECT_EQ(gaussianSmoothRows(signal, 0.0), signal);
  EXPECT_EQ(gaussianSmoothRows(signal, -3.0), signal);
  const Eigen::MatrixXd one_frame = randomSignal(1, 3, 2);
  EXPECT_EQ(gaussianSmoothRows(one_frame, 5.0), one_frame);
}

TEST(GaussianSmoothRows, EqualsTheDirectClampedConvolution) {
  // Clips shorter than the kernel (every tap clamps), around a block of 8, and long; both sigmas of
  // the representation and a fractional one.
  for (const Eigen::Index frames : {2, 7, 8, 9, 61, 300})
    for (const double sigma : {3.0, 20.0, 2.5}) {
      const Eigen::MatrixXd signal = randomSignal(frames, 2, static_cast<unsigned>(frames));
      const Eigen::MatrixXd smoothed = gaussianSmoothRows(signal, sigma);
      ASSERT_EQ(smoothed.rows(), frames);
      ASSERT_EQ(smoothed.cols(), 2);
      EXPECT_LT((smoothed - directGaussian(signal, sigma)).cwiseAbs().maxCoeff(), 1e-12)
          << frames << " frames, sigma " << sigma;
    }
}

TEST(GaussianSmoothRows, KeepsConstantsAndLinesAwayFromTheEdges) {
  const Eigen::MatrixXd constant = Eigen::MatrixXd::Constant(50, 3, 4.25);
  EXPECT_LT((gaussianSmoothRows(constant, 20.0) - constant).cwiseAbs().maxCoeff(), 1e-12);
  Eigen::MatrixXd line(200, 1);
  for (Eigen::Index t = 0; t < 200; ++t) line(t, 0) = 0.5 * static_cast<double>(t) - 7.0;
  const Eigen::MatrixXd smoothed = gaussianSmoothRows(line, 3.0);  // symmetric kernel: lines pass through
  EXPECT_LT((smoothed.middleRows(10, 180) - line.middleRows(10, 180)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(RemoveFrameAlternation, LeavesClipsOfFewerThanThreeFramesAlone) {
  for (int frames : {0, 1, 2}) {
    Eigen::MatrixXd features = Eigen::MatrixXd::Random(66, frames);
    const Eigen::MatrixXd before = features;
    removeFrameAlternation(features);
    EXPECT_EQ(features, before) << frames << " frames";
  }
}

// y_t = (x_{t-1} + 2 x_t + x_{t+1}) / 4, edges clamped: gain cos^2(pi f / fps) inside the clip.
TEST(RemoveFrameAlternation, CancelsTheAlternationAndScalesEachFrequencyByItsGain) {
  constexpr int kFrames = 120;
  constexpr double kPi = 3.14159265358979323846, kFps = 60.0, kHz = 5.0;
  Eigen::MatrixXd features(3, kFrames);
  for (int t = 0; t < kFrames; ++t) {
    features(0, t) = (t % 2 == 0 ? 1.0 : -1.0) * 2.5;                  // the Nyquist frequency
    features(1, t) = std::sin(2.0 * kPi * kHz * t / kFps + 0.3);       // 5 Hz
    features(2, t) = 0.5 * t - 3.0;                                    // a line
  }
  const Eigen::MatrixXd before = features;
  removeFrameAlternation(features);
  const double gain = std::pow(std::cos(kPi * kHz / kFps), 2);
  for (int t = 1; t + 1 < kFrames; ++t) {
    EXPECT_NEAR(features(0, t), 0.0, 1e-12) << t;
    EXPECT_NEAR(features(1, t), gain * before(1, t), 1e-12) << t;
    EXPECT_NEAR(features(2, t), before(2, t), 1e-12) << t;
  }
  // The edges repeat the first and last frames.
  EXPECT_NEAR(features(2, 0), (3.0 * before(2, 0) + before(2, 1)) / 4.0, 1e-12);
  EXPECT_NEAR(features(2, kFrames - 1), (3.0 * before(2, kFrames - 1) + before(2, kFrames - 2)) / 4.0, 1e-12);
  Eigen::MatrixXd constant = Eigen::MatrixXd::Constant(66, 7, -1.75);
  removeFrameAlternation(constant);
  EXPECT_EQ(constant, Eigen::MatrixXd::Constant(66, 7, -1.75));
}

TEST(Median, PicksTheMiddleValueAndTheUpperOfTwo) {
  EXPECT_EQ(median({}), 0.0);
  EXPECT_EQ(median({5, 1, 4, 2, 3}), 3.0);
  EXPECT_EQ(median({4, 1, 3, 2}), 3.0);  // rank size / 2 of 1 2 3 4
}

TEST(Quantile, PicksTheRankedValue) {
  EXPECT_EQ(quantile(Eigen::VectorXd(), 0.5), 0.0);
  Eigen::VectorXd values(5);
  values << 5, 1, 4, 2, 3;
  EXPECT_EQ(quantile(values, 0.0), 1.0);
  EXPECT_EQ(quantile(values, 0.5), 3.0);
  EXPECT_EQ(quantile(values, 1.0), 5.0);
  EXPECT_EQ(quantile(values, 7.0), 5.0);  // clamped to [0, 1]
}

TEST(Smoothstep, RisesFromZeroToOneWithFlatEnds) {
  EXPECT_EQ(smoothstep(-3.0), 0.0);
  EXPECT_EQ(smoothstep(0.0), 0.0);
  EXPECT_EQ(smoothstep(1.0), 1.0);
  EXPECT_EQ(smoothstep(2.0), 1.0);
  EXPECT_DOUBLE_EQ(smoothstep(0.5), 0.5);
  EXPECT_DOUBLE_EQ(smoothstep(0.25), 1.0 - smoothstep(0.75));  // symmetric about the middle
  EXPECT_LT(smoothstep(1e-3), 1e-5);                             // flat at the ends
  for (double x = 0.0; x < 1.0; x += 0.05) EXPECT_LT(smoothstep(x), smoothstep(x + 0.05)) << x;
}

}  // namespace
}  // namespace motionstyle
