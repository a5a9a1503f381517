#include "features/signal_filters.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace motionstyle {

Eigen::MatrixXd gaussianSmoothRows(const Eigen::MatrixXd& signal, double sigma_frames) {
  if (sigma_frames <= 0.0 || signal.rows() < 2) return signal;
  const auto radius = static_cast<Eigen::Index>(std::ceil(3.0 * sigma_frames));
  Eigen::VectorXd kernel(2 * radius + 1);
  for (Eigen::Index k = -radius; k <= radius; ++k) {
    const double x = static_cast<double>(k) / sigma_frames;
    kernel[k + radius] = std::exp(-0.5 * x * x);
  }
  kernel /= kernel.sum();
  const Eigen::Index frames = signal.rows();
  Eigen::MatrixXd smoothed = Eigen::MatrixXd::Zero(frames, signal.cols());
  for (Eigen::Index t = 0; t < frames; ++t) {
    for (Eigen::Index k = -radius; k <= radius; ++k) {
      const Eigen::Index source = std::clamp<Eigen::Index>(t + k, 0, frames - 1);
      smoothed.row(t) += kernel[k + radius] * signal.row(source);
    }
  }
  return smoothed;
}

double quantile(const Eigen::VectorXd& values, double q) {
  if (values.size() == 0) return 0.0;
  std::vector<double> sorted(values.data(), values.data() + values.size());
  const auto rank = static_cast<std::ptrdiff_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(sorted.size() - 1));
  std::nth_element(sorted.begin(), sorted.begin() + rank, sorted.end());
  return sorted[static_cast<size_t>(rank)];
}

}  // namespace motionstyle
