#pragma once
// Fast float32 inference: stylize(x) = project(T(x)) and project(x) = decode(encode(x)) for ONE clip of
// any length (features x frames, normalised), whole-clip and fully convolutional: no windows, so no
// seams, and exactly the reference forward pass (TransformationNetwork::apply, LossNetwork::project) up to
// float rounding, including the odd-length rule (last frame repeated through the pool, cropped after).
//
// Where the speed comes from (see tests/bench/nn for figures):
//  - every convolution is evaluated spectrally (spectral_correlation.h: overlap-save, ~5x fewer
//    multiplications at width 25) when the cost model expects it to be faster, with the kernels'
//    spectra computed once, here in the constructor; otherwise it is ONE matrix product over the whole
//    clip on a strided, zero-copy im2col view of a padded buffer (conv1d.h). Either way it writes
//    straight into the next layer's padded buffer, and bias, ReLU and max-pool follow on the slice;
//  - the two cores split every product by columns (compute_pool.h), one synchronisation per layer;
//  - the decoder is POLYPHASE: after average depooling, output frames 2s and 2s+1 only see pooled
//    frames s-6..s+6 (width 25), each through a kernel that sums pairs of taps. The two phase kernels
//    are stacked into one (2*features) x (hidden*13) kernel, a correlation of width 13 over the pooled
//    hidden units whose output is, column for column, the interleaved frames: half the
//    multiplications of the plain decoder and no depooled buffer;
//  - the decoder's "Depool(H) - b0" becomes "H - b0" before the product (depool repeats values);
//  - buffers persist across calls: same-length calls allocate nothing of ours.
// Not thread-safe (scratch buffers): use one instance per thread. A copy has its own scratch and shares
// the prepared kernel spectra (read-only here), so copying a prepared stylizer costs its weights'
// few MB, not the spectra's tens.

#include <functional>
#include <optional>

#include "nn/loss_network.h"
#include "nn/spectral_correlation.h"
#include "nn/transformation_network.h"

namespace motionstyle::nn {

class FastStylizer {
 public:
  // Projection only (no transformation network).
  explicit FastStylizer(const LossNetwork<float>& loss_network);
  // Style transfer: transformation then the loss network's projection. The feature counts must match
  // (std::invalid_argument otherwise).
  FastStylizer(const TransformationNetwork<float>& transformation, const LossNetwork<float>& loss_network);
  // The same on a projection prepared before (FastStylizer(loss_network)), sharing its kernel spectra
  // instead of preparing them again: styles trained against one loss network (every shipped one) hold
  // one copy of its spectra (about half of a prepared style's 60 MB), not one each. Results are bit for
  // bit the other constructor's. std::invalid_argument for mismatched feature counts or a `projection`
  // that has a transformation.
  FastStylizer(const TransformationNetwork<float>& transformation, const FastStylizer& projection);

  // x: features x frames (frames >= 1), normalised. out: features x frames. Throws
  // std::invalid_argument on a shape mismatch or if stylize() is called without a transformation.
  void stylize(const Mat<float>& x, Mat<float>& out);
  void project(const Mat<float>& x, Mat<float>& out);
  Mat<float> stylize(const Mat<float>& x);
  Mat<float> project(const Mat<float>& x);

  // The loss network's hidden units H = ReLU(maxpool(conv(x)) + b0) of x (features x frames,
  // normalised): hidden x evenFrames(frames)/2, as LossNetwork::encode up to float rounding.
  Mat<float> encode(const Mat<float>& x);
  // stylize(x) with `edit` given T(x)'s hidden units H (hidden x evenFrames(frames)/2) to change in
  // place before they are decoded: decode(edit(encode(T(x)))). What the style refinement runs in.
  using HiddenEdit = std::function<void(Mat<float>& hidden)>;
  void stylize(const Mat<float>& x, Mat<float>& out, const HiddenEdit& edit);

  // The decoder's two phase kernels stacked (tests compare them with the plain decoder).
  const Mat<float>& polyphaseKernel() const { return polyphase_; }

 private:
  struct Layer {
    Mat<float> weight;  // out x (in*width), tap-major
    Vec<float> bias;    // out (may be empty)
    int in = 0;
    int out = 0;
    int width = 1;
    // The spectral evaluation, holding this kernel's spectra (computed once) and its scratch.
    std::optional<SpectralCorrelation<float>> spectral;
  };
  static Layer makeLayer(Mat<float> weight, Vec<float> bias, int in, int out, int width);
  void addTransformation(const TransformationNetwork<float>& transformation);
  static Layer copyLayer(const Conv1d<float>& conv);
  // out (layer.out x count, column-major) = the correlation of `padded` (layer.in x available) with the
  // layer's kernel at output positions 0..count-1 (correlatePadded's contract), no bias. Spectral or
  // direct, whichever the cost model picks for `count`.
  static void correlate(Layer& layer, const float* padded, Eigen::Index available, int count, float* out);
  void buildPolyphase(const LossNetwork<float>& loss_network);
  // Copies x into the padded buffer encoder_input_; returns its frames.
  int loadEncoderInput(const Mat<float>& x);
  // The encoder and its pool on the padded buffer encoder_input_: pooled_ = H - b0.
  void encodePadded(int frames);
  // Runs the projection on the (even-length) padded buffer encoder_input_, writing `frames` columns;
  // `edit` (may be empty) changes the hidden units before the decoder.
  void projectPadded(int frames, Mat<float>& out, const HiddenEdit& edit = {});
  void convolve(Layer& layer, const Mat<float>& in, Mat<float>& out, int frames, bool relu);

  bool has_transformer_ = false;
  bool residual_ = false;
  Layer t1_, t2_, t3_, encoder_;
  int features_ = 0;
  int hidden_ = 0;
  Mat<float> polyphase_;    // (2*features) x (hidden*taps)
  Layer decoder_;           // polyphase_ as a width-phase_taps_ correlation over the pooled frames
  int phase_taps_ = 0;      // taps of each phase kernel (13 for width 25)
  int phase_left_ = 0;      // pooled frames of zero padding before the clip (6)
  int phase_right_ = 0;     // ... and after (6)
  Vec<float> encoder_bias_;

  // Scratch, reused across calls. Column-major, zero-padded by width/2 frames each side where a
  // convolution reads them.
  Mat<float> input_;         // features x (T + 2 pad)
  Mat<float> hidden1_;       // T's hidden layers, hidden_t x (T + 2 pad)
  Mat<float> hidden2_;
  Mat<float> encoder_input_; // features x (Te + 2 pad), Te = even length
  Mat<float> encoded_;       // hidden x Te (pre-pool)
  Mat<float> pooled_;        // hidden x (Te/2 + left + right), holds H - b0
  Mat<float> decoded_;       // features x Te when the clip is odd
};

}  // namespace motionstyle::nn
