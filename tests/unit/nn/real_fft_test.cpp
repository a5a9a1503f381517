// The batched real FFT: invalid use first, then both directions against the DFT's definition (in
// double, over lengths, row counts that cross the chunk and thread splits, and zero-padded inputs),
// the round trip, and the float error.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "gradient_check.h"
#include "nn/real_fft.h"

namespace motionstyle::nn {
namespace {

using test::MatD;
using test::randomMatrix;

// X[k] = sum_{n < samples} x[r, n] e^{-2 pi i k n / N}, k = 0..N/2, as [Re | Im].
MatD naiveForward(const MatD& x, int samples, int points) {
  const int bins = points / 2 + 1;
  MatD spectra = MatD::Zero(x.rows(), 2 * bins);
  for (Eigen::Index r = 0; r < x.rows(); ++r)
    for (int k = 0; k < bins; ++k)
      for (int n = 0; n < samples; ++n) {
        const double angle = 2.0 * std::numbers::pi * k * n / points;
        spectra(r, k) += x(r, n) * std::cos(angle);
        spectra(r, bins + k) -= x(r, n) * std::sin(angle);
      }
  return spectra;
}

// x[n] = (1/N) sum_{k < N} X[k] e^{+2 pi i k n / N} for the Hermitian extension of bins 0..N/2, whose
// bins 0 and N/2 count as real.
MatD naiveInverse(const MatD& spectra, int samples, int points) {
  const int bins = points / 2 + 1;
  MatD x = MatD::Zero(spectra.rows(), samples);
  for (Eigen::Index r = 0; r < spectra.rows(); ++r)
    for (int n = 0; n < samples; ++n)
      for (int k = 0; k < points; ++k) {
        const int bin = k < bins ? k : points - k;
        const double re = spectra(r, bin);
        double im = (bin == 0 || 2 * bin == points) ? 0.0 : spectra(r, bins + bin);
        if (k >= bins) im = -im;  // X[N - k] = conj X[k]
        const double angle = 2.0 * std::numbers::pi * k * n / points;
        x(r, n) += (re * std::cos(angle) - im * std::sin(angle)) / points;
      }
  return x;
}

double maxRelative(const MatD& a, const MatD& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(1e-300, b.cwiseAbs().maxCoeff());
}

TEST(RealFftInvalid, RejectsLengthsThatAreNotPowersOfTwoAndTooManySamples) {
  EXPECT_THROW(RealFft<double>(0), std::invalid_argument);
  EXPECT_THROW(RealFft<double>(2), std::invalid_argument);
  EXPECT_THROW(RealFft<double>(12), std::invalid_argument);
  RealFft<double> fft(8);
  MatD x = MatD::Zero(3, 9), out(3, 10);
  EXPECT_THROW(fft.forward(x.data(), 3, 9, 3, out.data(), 3), std::invalid_argument);
  EXPECT_THROW(fft.inverse(out.data(), 3, 3, 9, x.data(), 3), std::invalid_argument);
  EXPECT_THROW(fft.forward(x.data(), 3, -1, 3, out.data(), 3), std::invalid_argument);
}

TEST(RealFft, ForwardAndInverseFollowTheDefinitions) {
  std::mt19937 rng(31);
  for (int points : {4, 8, 16, 64, 128}) {
    RealFft<double> fft(points);
    ASSERT_EQ(fft.bins(), points / 2 + 1);
    for (Eigen::Index rows : {1, 7, 300, 1100}) {  // one row, a partial chunk, several chunks and threads
      const int samples = points - static_cast<int>(rng() % (points / 2 + 1));  // zero-padded tails too
      const MatD x = randomMatrix(rows, samples, rng);
      MatD spectra(rows, 2 * fft.bins());
      fft.forward(x.data(), rows, samples, rows, spectra.data(), rows);
      EXPECT_LT(maxRelative(spectra, naiveForward(x, samples, points)), 1e-13) << points << " x " << rows;

      MatD arbitrary = randomMatrix(rows, 2 * fft.bins(), rng);  // incl. nonzero Im at bins 0 and N/2
      const int wanted = 1 + static_cast<int>(rng() % points);
      MatD back(rows, wanted);
      fft.inverse(arbitrary.data(), rows, rows, wanted, back.data(), rows);
      EXPECT_LT(maxRelative(back, naiveInverse(arbitrary, wanted, points)), 1e-13) << points << " x " << rows;
    }
  }
}

TEST(RealFft, InverseUndoesForwardAndStridesAreHonoured) {
  std::mt19937 rng(32);
  RealFft<double> fft(64);
  // Signals are rows 5..204 of a taller matrix, spectra go into a taller one: strides != rows.
  const MatD tall = randomMatrix(260, 64, rng);
  MatD spectra = MatD::Zero(230, 2 * 33);
  fft.forward(tall.data() + 5, tall.rows(), 64, 200, spectra.data() + 3, spectra.rows());
  MatD back = MatD::Zero(210, 64);
  fft.inverse(spectra.data() + 3, spectra.rows(), 200, 64, back.data(), back.rows());
  EXPECT_LT(maxRelative(back.topRows(200), tall.middleRows(5, 200)), 1e-14);
  EXPECT_EQ(back.bottomRows(10).cwiseAbs().maxCoeff(), 0.0);  // rows past `rows` untouched
}

TEST(RealFft, FloatErrorIsRoundingOnly) {
  std::mt19937 rng(33);
  RealFft<float> fft(64);
  const MatD x = randomMatrix(500, 64, rng);
  Mat<float> xf = x.cast<float>(), spectra(500, 66);
  fft.forward(xf.data(), 500, 64, 500, spectra.data(), 500);
  EXPECT_LT(maxRelative(spectra.cast<double>(), naiveForward(x, 64, 64)), 2e-6);
}

}  // namespace
}  // namespace motionstyle::nn
