#pragma once
// Central-difference gradient checking in double precision for the nn tests.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <vector>

#include "nn/tensor.h"

namespace motionstyle::nn::test {

using MatD = Mat<double>;

inline MatD randomMatrix(Eigen::Index rows, Eigen::Index cols, std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  MatD m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = u(rng);
  return m;
}

// Relative error of an analytic derivative against a numeric one. Entries where both are tiny are
// compared at an absolute scale of `floor` (the central difference's own round-off is ~1e-10).
inline double relativeError(double analytic, double numeric, double floor = 1e-4) {
  return std::abs(analytic - numeric) / std::max({std::abs(analytic), std::abs(numeric), floor});
}

constexpr double kGradientTolerance = 1e-5;

struct GradientCheck {
  double max_error = 0;
  int checked = 0;
};

// Checks `analytic` = d loss / d x on up to `samples` entries of x (all when samples <= 0 or x is
// small), perturbing x in place and restoring it. Five-point central differences (error O(h^4)) allow
// a step large enough that the losses' own round-off (sums over thousands of products, values up to
// ~1e3 for the cm^2 terms) stays far below the tolerance. ReLU and max-pool are piecewise linear:
// when a stencil straddles a kink the estimate is wrong although the analytic gradient is exact at
// the point, so an entry that fails at step h is retried at h/10 and h/100 (a kink at distance d
// stops mattering once 2h < d); the best agreement counts.
inline GradientCheck checkGradient(MatD& x, const MatD& analytic, const std::function<double()>& loss,
                                   int samples, std::mt19937& rng, double h = 1e-4) {
  EXPECT_EQ(x.rows(), analytic.rows());
  EXPECT_EQ(x.cols(), analytic.cols());
  std::vector<Eigen::Index> entries;
  if (samples <= 0 || x.size() <= samples) {
    for (Eigen::Index i = 0; i < x.size(); ++i) entries.push_back(i);
  } else {
    std::uniform_int_distribution<Eigen::Index> pick(0, x.size() - 1);
    for (int s = 0; s < samples; ++s) entries.push_back(pick(rng));
  }
  GradientCheck result;
  for (Eigen::Index i : entries) {
    const double saved = x.data()[i];
    auto at = [&](double offset) {
      x.data()[i] = saved + offset;
      return loss();
    };
    double numeric = 0;
    double error = 0;
    for (double step : {h, h / 10, h / 100}) {
      const double estimate = (8.0 * (at(step) - at(-step)) - (at(2 * step) - at(-2 * step))) / (12.0 * step);
      const double estimate_error = relativeError(analytic.data()[i], estimate);
      if (step == h || estimate_error < error) {
        numeric = estimate;
        error = estimate_error;
      }
      if (error < kGradientTolerance / 10) break;
    }
    x.data()[i] = saved;
    if (std::getenv("NN_GRADCHECK_VERBOSE") != nullptr && error > 1e-6)
      std::printf("entry %ld analytic %.12g numeric %.12g error %.3g\n", static_cast<long>(i),
                  analytic.data()[i], numeric, error);
    result.max_error = std::max(result.max_error, error);
    ++result.checked;
  }
  if (std::getenv("NN_GRADCHECK_VERBOSE") != nullptr)
    std::printf("gradient check: %d entries, max relative error %.3g\n", result.checked, result.max_error);
  return result;
}

}  // namespace motionstyle::nn::test
