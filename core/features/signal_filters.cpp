#include "features/signal_filters.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace motionstyle {

Eigen::MatrixXd gaussianSmoothRows(const Eigen::MatrixXd& signal, double sigma_frames) {
  if (sigma_frames <= 0.0 || signal.rows() < 2) return signal;
  const auto radius = static_cast<Eigen::Index>(std::ceil(3.0 * sigma_frames));
  const Eigen::Index taps = 2 * radius + 1;
  std::vector<double> kernel(static_cast<size_t>(taps));
  double kernel_sum = 0.0;
  for (Eigen::Index k = -radius; k <= radius; ++k) {
    const double x = static_cast<double>(k) / sigma_frames;
    kernel[static_cast<size_t>(k + radius)] = std::exp(-0.5 * x * x);
    kernel_sum += kernel[static_cast<size_t>(k + radius)];
  }
  for (double& weight : kernel) weight /= kernel_sum;

  // Each column (contiguous, the matrix being column-major) is copied once with `radius` repeats of its
  // first and last values on either side, so that the convolution needs no clamping. Outputs are then
  // computed a block of kBlock frames at a time, the block's sums held in registers while the taps are
  // added in order k = -radius .. radius (the same order for every frame), each tap one vector
  // multiply-add over the block.
  constexpr int kBlock = 8;
  using Block = Eigen::Array<double, kBlock, 1>;
  const Eigen::Index frames = signal.rows();
  Eigen::MatrixXd smoothed(frames, signal.cols());
  std::vector<double> padded(static_cast<size_t>(frames + 2 * radius + kBlock), 0.0);  // + kBlock: last block's reads
  for (Eigen::Index column = 0; column < signal.cols(); ++column) {
    const double* in = signal.col(column).data();
    std::fill_n(padded.begin(), radius, in[0]);
    std::copy_n(in, frames, padded.begin() + radius);
    std::fill_n(padded.begin() + radius + frames, radius, in[frames - 1]);
    double* out = smoothed.col(column).data();
    for (Eigen::Index first = 0; first < frames; first += kBlock) {
      Block sums = Block::Zero();
      const double* window = padded.data() + first;
      for (Eigen::Index k = 0; k < taps; ++k) sums += kernel[static_cast<size_t>(k)] * Eigen::Map<const Block>(window + k);
      std::copy_n(sums.data(), std::min<Eigen::Index>(kBlock, frames - first), out + first);
    }
  }
  return smoothed;
}

void removeFrameAlternation(Eigen::MatrixXd& features) {
  const Eigen::Index frames = features.cols();
  if (frames < 3) return;
  Eigen::VectorXd previous = features.col(0);  // x_{t-1} before this column was overwritten
  for (Eigen::Index t = 0; t < frames; ++t) {
    const Eigen::VectorXd current = features.col(t);
    const Eigen::Index next = std::min(t + 1, frames - 1);
    features.col(t) = 0.25 * (previous + features.col(next)) + 0.5 * current;
    previous = current;
  }
}

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

double quantile(const Eigen::VectorXd& values, double q) {
  if (values.size() == 0) return 0.0;
  std::vector<double> sorted(values.data(), values.data() + values.size());
  const auto rank = static_cast<std::ptrdiff_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(sorted.size() - 1));
  std::nth_element(sorted.begin(), sorted.begin() + rank, sorted.end());
  return sorted[static_cast<size_t>(rank)];
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace motionstyle
