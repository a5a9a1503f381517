#pragma once
// Tensor conventions shared by every layer of the networks (core/nn).
//
// SEQUENCES. A sequence is a matrix channels x time, column-major: each column is one frame.
// BATCHES. A batch of B windows of equal length T is ONE matrix channels x (B*T): window b occupies
// columns [b*T, (b+1)*T). Every layer takes the frames per window T beside the matrix; the windows
// never mix (a convolution pads each window with its own zeros, a max-pool never pairs frames of two
// windows). A single clip of any length is simply B = 1.
//
// CONVOLUTION WEIGHTS. A temporal convolution with `in` input channels, `out` output channels and an
// odd width K is stored as a matrix out x (in*K), TAP-MAJOR: W(o, k*in + c) is the weight from input
// channel c at time offset k - K/2 to output channel o (the w[o][c][k] of a PyTorch Conv1d). Tap-major
// makes the im2col column of frame t the K consecutive input frames t-K/2..t+K/2 stacked, which in a
// column-major buffer are already contiguous: a convolution over a whole batch is one matrix product
// with a strided view of the (zero-padded) input, with no im2col copy (see conv1d.h).
//
// GRADIENTS. Layers follow the llm.c convention: forward() caches what backward() needs; backward()
// returns the gradient with respect to the layer input and ADDS into its parameters' gradients, which
// the training loop zeroes explicitly (zeroGrad) once per step.
//
// SCALARS. Layers are templates on the scalar type, explicitly instantiated for float (training and
// inference speed) and double (gradient checks, reference forward pass).

#include <Eigen/Core>
#include <string>

namespace motionstyle::nn {

template <typename S>
using Mat = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
template <typename S>
using Vec = Eigen::Matrix<S, Eigen::Dynamic, 1>;

// A trainable tensor and its accumulated gradient (same shape). Biases are out x 1 matrices.
template <typename S>
struct Parameter {
  std::string name;  // for messages and the network file, e.g. "encoder.weight"
  Mat<S> value;
  Mat<S> grad;

  void resize(Eigen::Index rows, Eigen::Index cols) {
    value.setZero(rows, cols);
    grad.setZero(rows, cols);
  }
  void zeroGrad() { grad.setZero(value.rows(), value.cols()); }
};

// Throws std::invalid_argument unless `x` is channels x (B*frames) for some B >= 1 and frames >= 1.
// Returns B. `what` names the caller for the message.
int checkBatch(const char* what, Eigen::Index rows, Eigen::Index cols, int channels, int frames);

}  // namespace motionstyle::nn
