#pragma once
// The temporal correlation of conv1d.h evaluated in the frequency domain (overlap-save), for long
// inputs: the same numbers as the direct product up to rounding, several times fewer multiplications.
//
// WHY. The direct evaluation costs K multiply-adds per (input channel, output channel, output frame).
// Cut the padded input into overlapping segments of N = L + K - 1 frames, each giving L output frames.
// In the real DFT of N points, correlating a segment with a kernel is a product per frequency, so the
// channel mixing at each of the H = floor(N/2) + 1 frequencies is ONE complex matrix product
// (out x in) x (in x segments). With Gauss's three-product complex multiplication that is 3H/L real
// multiply-adds per (channel pair, frame) instead of K: with K = 25 and N = 64 (L = 40), 2.5 instead
// of 25. The channel mixing runs on Eigen's GEMM kernel (forward: on kernel spectra packed once,
// packed_product.h); the transforms are batched real FFTs (real_fft.h),
// both split over the compute pool (compute_pool.h). The kernel's spectra are cached and recomputed
// only when its weights change, so a frozen network (the loss network during style training, any
// network at inference) pays once.
//
// MATHS (one channel pair; a segment s of N frames; a kernel w of K taps; 0 <= t < L):
//   y[t] = sum_k w[k] s[t + k]                                   the correlation of conv1d.h
//        = IDFT( C . DFT(s) )[t],   C(f) = sum_k w[k] e^{+2 pi i f k / N}   (conjugate kernel spectrum)
// exactly, because t + k <= L - 1 + K - 1 = N - 1 never wraps around. Its adjoints, also without wrap:
//   ds     = IDFT( conj(C) . DFT(dy) )      dy: the segment's L output gradients, zeros after; all N
//                                           frames of ds are ADDED into the input gradient (segments
//                                           overlap by K - 1 frames: overlap-add)
//   dw[k]  = IDFT( conj(DFT(dy)) . DFT(s) )[k],  k < K
// With channels, per frequency f: Y_f = C_f S_f,  dS_f = C_f^H dY_f,  dW_f = conj(dY_f) S_f^T.
// Storage: a real signal's spectrum is its H real parts, then its H imaginary parts (2H values).
//
// NUMERICS. Rounding only: ~1e-6 of the largest output in float, ~1e-14 in double. tests/unit/nn
// compare this path with the direct one and gradient-check it in double.
//
// Not thread-safe (scratch): one instance per layer and thread. Copies may run on different threads:
// they share the kernel spectra read-only, and setKernel() on a shared one makes its own.

#include <memory>
#include <vector>

#include "nn/packed_product.h"
#include "nn/real_fft.h"
#include "nn/tensor.h"

namespace motionstyle::nn {

// Segment length N (a power of two, >= 8) for a kernel of `width` taps: the smallest that gives at
// least 1.6 x width output frames per segment (L = N - width + 1). Longer segments cost fewer
// products per frame but more transform work; for width 25 this gives N = 64, L = 40, the measured
// optimum for the default networks (tests/bench/nn).
int defaultSpectralPoints(int width);

// Whether the spectral evaluation is expected to beat the direct product for `count` output frames:
// its per-frame saving in channel mixing, in * out * (K - 3H/L), must exceed twice its per-frame
// transform cost, (in + out) * 5 N log2(N) / L (one FFT per channel and segment, in multiply-add
// equivalents as measured against the GEMM), and the input must hold at least two segments.
// Always false when MOTIONSTYLE_NN_CONV=direct is set in the environment (read once).
bool spectralIsFaster(int in, int out, int width, long count);

// Which passes a SpectralCorrelation serves. ForwardOnly (inference: FastStylizer) keeps only the
// packed forward parts of the kernel spectra, 3/7 of the memory of both (a prepared style network
// held 120 MB with both).
enum class SpectralPasses { ForwardAndBackward, ForwardOnly };

template <typename S>
class SpectralCorrelation {
 public:
  // in, out >= 1; width odd >= 1; points (N) a power of two >= max(4, width). Throws
  // std::invalid_argument otherwise.
  SpectralCorrelation(int in, int out, int width, int points,
                      SpectralPasses passes = SpectralPasses::ForwardAndBackward);

  int inChannels() const { return in_; }
  int outChannels() const { return out_; }
  int width() const { return width_; }
  int block() const { return block_; }
  int points() const { return points_; }  // N = L + K - 1
  int bins() const { return bins_; }      // H = floor(N/2) + 1

  // Uses the kernel `weight` (out x (in*width), tap-major, tensor.h). Its spectra are recomputed only
  // when `weight` differs from the one of the previous call. Throws std::invalid_argument on a shape
  // mismatch. Copies share the kernel and its spectra until one of them is given another weight.
  void setKernel(const Mat<S>& weight);

  // out (out_ x count, column-major) = sum_k W_k * padded[:, j + k] for j in [0, count): the contract
  // of correlatePadded (conv1d.h). `padded` (in_ x available, column-major) is read as zero past
  // `available` frames. Keeps the input spectra for backward(). Needs setKernel() first.
  void forward(const S* padded, Eigen::Index available, Eigen::Index count, S* out);

  // Throws std::logic_error for a ForwardOnly instance.
  // grad_out: out_ x count, the gradient of the last forward()'s output (same count). ADDS dLoss/dW
  // into *weight_grad (out x (in*width)) when it is not null, and dLoss/dpadded into padded_grad
  // (in_ x (count + width - 1), column-major) when it is not null.
  void backward(const S* grad_out, Eigen::Index count, Mat<S>* weight_grad, S* padded_grad);

 private:
  Eigen::Index segmentCount(Eigen::Index count) const { return (count + block_ - 1) / block_; }
  // rows (j*channels .. +channels) of `segments` = frames j*L .. j*L + frames - 1 of `sequence`
  // (channels x available), zero past `available`; then spectra = their real DFTs (zero past `frames`).
  void transform(const S* sequence, Eigen::Index available, int channels, int frames, Eigen::Index segments,
                 Mat<S>& scratch, Mat<S>& spectra) const;

  // Part 0..3 (see kernel_spectra_) of C_f as an out x in matrix.
  Eigen::Map<const Mat<S>> kernelPart(int f, int part) const;

  int in_, out_, width_, block_, points_, bins_;
  SpectralPasses passes_;
  RealFft<S> fft_;
  struct Kernel {
    Mat<S> weight;   // the weight the cached spectra belong to
    // (out*in) x 4H: for frequency f, columns f, H+f, 2H+f, 3H+f hold Re C_f, Im C_f, Re + Im and
    // Re - Im (out x in each; the last two serve Gauss's three-product complex multiplication).
    // Empty for ForwardOnly, which needs only forward_parts.
    Mat<S> spectra;
    // forward()'s three parts (Re, Im, Re + Im) per frequency, index part * H + f, packed for the GEMM
    // kernel once per weight: a short clip's products would otherwise copy them every call.
    std::vector<PackedMatrix<S>> forward_parts;
  };
  // Shared by copies (a copy of a prepared layer costs no spectra: tens of MB in a stylizer), written
  // in place by setKernel() while this instance is its only owner, replaced otherwise.
  std::shared_ptr<Kernel> kernel_;
  Mat<S> input_spectra_;     // (in*segments) x 2H: column f is S_f, in x segments (kept for backward)
  Eigen::Index input_count_ = -1;  // count of the forward() the input spectra belong to
  // Scratch, reused across calls.
  Mat<S> segments_;
  Mat<S> product_spectra_;
  Mat<S> grad_spectra_;
  Mat<S> frames_;
  Mat<S> taps_;
};

}  // namespace motionstyle::nn
