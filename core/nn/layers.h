#pragma once
// The element-wise and temporal-resampling layers of the two networks (conv1d.h has the convolution).
// Batch layout and gradient conventions: tensor.h. Every forward() caches what its backward() needs.

#include <cstdint>
#include <random>

#include "nn/tensor.h"

namespace motionstyle::nn {

// y = max(x, 0). The gradient at exactly 0 is taken as 0.
template <typename S>
class Relu {
 public:
  static Mat<S> apply(const Mat<S>& x);
  Mat<S> forward(const Mat<S>& x);
  Mat<S> backward(const Mat<S>& grad_out) const;

 private:
  Mat<S> output_;
};

// Max-pooling by 2 over time (the paper's Psi): y[:, s] = max(x[:, 2s], x[:, 2s+1]) per channel.
// Windows must have an EVEN number of frames (std::invalid_argument otherwise), so that pairs never
// straddle two windows; the networks make odd clips even first (padToEvenFrames). The gradient goes
// to the argmax of each pair (the first frame on a tie).
template <typename S>
class MaxPool2 {
 public:
  static Mat<S> apply(const Mat<S>& x, int frames);
  Mat<S> forward(const Mat<S>& x, int frames);
  Mat<S> backward(const Mat<S>& grad_out) const;

 private:
  Eigen::Matrix<std::uint8_t, Eigen::Dynamic, Eigen::Dynamic> second_;  // 1 where x[:, 2s+1] won
};

// Average depooling by 2 (the paper's Psi-dagger): y[:, 2s] = y[:, 2s+1] = x[:, s], so the AVERAGE of
// each output pair equals the pooled value. This is the paper-consistent reading of "average
// depooling": it undoes the pooling's halving of the frame rate at the same scale, so
// Depool(H) - b0 in eq. 2 removes the encoder's bias exactly (Depool(H) - b0 = Depool(H - b0)).
// (The 2016 code instead halved each value at synthesis, which is the mean of its stochastic
// training-time depool; the factor of 2 is absorbed by the decoder weights, which we train ourselves,
// but would not match b0.) Stateless: the layer is linear.
template <typename S>
class AverageDepool2 {
 public:
  static Mat<S> apply(const Mat<S>& x);
  static Mat<S> backward(const Mat<S>& grad_out);
};

// y = x - b (b broadcast over time) with b a parameter OWNED ELSEWHERE: eq. 2 subtracts the encoder's
// bias b0, so the decoder's gradient flows into the encoder's bias. backward() adds -sum_t dy into
// shared->grad.
template <typename S>
class SubtractSharedBias {
 public:
  explicit SubtractSharedBias(Parameter<S>* shared = nullptr) : shared_(shared) {}
  Mat<S> apply(const Mat<S>& x) const;
  Mat<S> backward(const Mat<S>& grad_out, bool accumulate_parameter) const;

 private:
  Parameter<S>* shared_;
};

// Inverted dropout: each value is zeroed with probability `rate`, the kept ones scaled by
// 1 / (1 - rate), so the expectation is unchanged and inference is the identity. rate in [0, 1).
template <typename S>
class Dropout {
 public:
  Mat<S> forward(const Mat<S>& x, S rate, std::mt19937& rng);
  Mat<S> backward(const Mat<S>& grad_out) const;

 private:
  Mat<S> scale_;  // 0 or 1/(1-rate) per value
};

// Odd windows through max-pool and depool: an odd window is made even by REPEATING ITS LAST FRAME
// (like the paper pads short clips with their last frame), and the result is cropped back after the
// decoder. Both functions are identities for even frames.
template <typename S>
Mat<S> padToEvenFrames(const Mat<S>& x, int frames);
// Gradient of padToEvenFrames: the repeated frame's gradient is added to the last real frame.
template <typename S>
Mat<S> foldEvenPaddingGradient(const Mat<S>& grad_padded, int frames);
// Drops the repeated frame of each window (padded frames = frames + frames % 2).
template <typename S>
Mat<S> cropToFrames(const Mat<S>& x_padded, int frames);
// Gradient of cropToFrames: zero for the dropped frame.
template <typename S>
Mat<S> uncropGradient(const Mat<S>& grad, int frames);

inline int evenFrames(int frames) { return frames + frames % 2; }

}  // namespace motionstyle::nn
