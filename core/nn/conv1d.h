#pragma once
// Temporal 1-D convolution ("same" padding) over a batch of windows, as ONE matrix product per pass.
//
// Definition (cross-correlation, as in every deep-learning framework):
//   y[o, t] = b[o] + sum_{c, k} W(o, k*in + c) * x[c, t + k - K/2]
// with x = 0 outside the window (K/2 zeros each side of EACH window), K odd, so the output has the
// input's length.
//
// How it is one product: the batch is copied into a PADDED layout: K/2 zero columns, then every
// window followed by K/2 zero columns. In that column-major buffer, the im2col column of a frame (its
// K neighbours stacked, tap-major) is a contiguous run of in*K values, and consecutive frames start
// `in` values apart: the whole im2col matrix is a strided Map over the buffer (overlapping columns,
// no copy). Y = W * im2col is then one GEMM over all B*(T+K/2) - K/2 positions; the K/2 positions in
// each gap between windows are computed and discarded (5% extra work at T = 240, K = 25).
// The backward pass uses the same trick twice: dX is the correlation of the padded dY with the
// flipped, transposed kernel, and dW = dY * im2col^T. Products are split by columns over the compute
// pool (compute_pool.h).
//
// For long inputs the same correlation is evaluated in the frequency domain instead
// (spectral_correlation.h: overlap-save, ~5x fewer multiplications at width 25), with identical
// results up to rounding. ConvAlgorithm::Automatic picks it from a cost model (spectralIsFaster);
// tests force either path to compare them and gradient-check both.

#include <optional>
#include <string>
#include <vector>

#include "nn/spectral_correlation.h"
#include "nn/tensor.h"

namespace motionstyle::nn {

// The im2col view of a padded sequence, without copying: column j stacks frames j..j+width-1 of the
// buffer starting at `first_frame` (each frame `channels` values), i.e. the receptive field of output
// frame j. Read-only; the buffer must hold count + width - 1 frames.
template <typename S>
using SlidingColumns = Eigen::Map<const Mat<S>, Eigen::Unaligned, Eigen::OuterStride<>>;

template <typename S>
SlidingColumns<S> slidingColumns(const S* first_frame, Eigen::Index channels, int width,
                                 Eigen::Index count) {
  return SlidingColumns<S>(first_frame, channels * width, count, Eigen::OuterStride<>(channels));
}

// out (weight.rows() x count, column-major, may not alias the input) = weight * slidingColumns(...):
// the correlation of a padded sequence with a tap-major kernel. Split by columns over the compute pool
// when `parallel` and the work is large enough.
template <typename S>
void correlatePadded(const Mat<S>& weight, const S* padded, Eigen::Index channels, int width, S* out,
                     Eigen::Index count, bool parallel = true);

// Copies x (channels x B*frames) into `padded` (channels x (pad + B*(frames + pad))): pad zero columns
// first, then each window followed by pad zero columns.
template <typename S>
void padWindows(const Mat<S>& x, int frames, int pad, Mat<S>& padded);

// Which gradients a backward pass computes. InputOnly serves frozen networks (the loss network while
// training the transformation network); ParametersOnly serves a first layer whose input is data.
enum class Gradients { All, InputOnly, ParametersOnly };

// How a convolution evaluates its products: the direct strided product, the spectral (overlap-save)
// evaluation, or whichever the cost model expects to be faster for the batch at hand.
enum class ConvAlgorithm { Automatic, Direct, Spectral };

template <typename S>
class Conv1d {
 public:
  Conv1d() = default;
  // width must be odd and >= 1, channel counts >= 1; throws std::invalid_argument otherwise.
  // Parameters start at zero: see init.h for the random initialisations.
  Conv1d(const std::string& name, int in_channels, int out_channels, int width, bool has_bias);

  int inChannels() const { return in_; }
  int outChannels() const { return out_; }
  int width() const { return width_; }
  bool hasBias() const { return has_bias_; }

  // y = conv(x), no cache (inference). x: in x (B*frames). Throws std::invalid_argument on a shape
  // mismatch.
  Mat<S> apply(const Mat<S>& x, int frames) const;
  // Same, caching the padded input for backward().
  Mat<S> forward(const Mat<S>& x, int frames);
  // grad_out: out x (B*frames) of the last forward(). Adds into weight.grad / bias.grad unless
  // InputOnly; returns dLoss/dx (in x B*frames), or an empty matrix when ParametersOnly.
  Mat<S> backward(const Mat<S>& grad_out, Gradients wanted = Gradients::All);

  void zeroGrad();
  std::vector<Parameter<S>*> parameters();

  void setAlgorithm(ConvAlgorithm algorithm) { algorithm_ = algorithm; }
  ConvAlgorithm algorithm() const { return algorithm_; }

  Parameter<S> weight;  // out x (in*width), tap-major (tensor.h)
  Parameter<S> bias;    // out x 1, or 0 x 0 without bias

 private:
  // The padded batch through the product (direct, or `spectral` when not null), then bias.
  Mat<S> run(const Mat<S>& padded, int windows, int frames, SpectralCorrelation<S>* spectral) const;
  bool useSpectral(Eigen::Index count) const;

  int in_ = 0;
  int out_ = 0;
  int width_ = 1;
  bool has_bias_ = false;
  ConvAlgorithm algorithm_ = ConvAlgorithm::Automatic;
  Mat<S> padded_input_;  // cache of the last forward()
  int frames_ = 0;
  int windows_ = 0;
  // The spectral evaluation of forward()/backward(): kernel spectra cached across calls while the
  // weights stay the same, the last forward()'s input spectra for backward().
  std::optional<SpectralCorrelation<S>> spectral_;
  bool spectral_forward_ = false;  // whether the last forward() used spectral_
};

}  // namespace motionstyle::nn
