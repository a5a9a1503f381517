#include "nn/fast_stylizer.h"

#include <stdexcept>
#include <string>

#include "nn/compute_pool.h"

namespace motionstyle::nn {
namespace {

// Columns per thread below which splitting a product is not worth a synchronisation.
constexpr int kMinColumnsPerThread = 32;

int floorDiv(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

// Resizes to rows x cols filled with zeros, but only when the shape changes: the zero padding columns
// are never written afterwards, so a same-shape call needs no clearing and no allocation.
void ensureZeroed(Mat<float>& m, Eigen::Index rows, Eigen::Index cols) {
  if (m.rows() != rows || m.cols() != cols) m.setZero(rows, cols);
}

void requireClip(const Mat<float>& x, int features) {
  if (x.rows() != features || x.cols() < 1)
    throw std::invalid_argument("FastStylizer: expected a clip of " + std::to_string(features) +
                                " x frames (frames >= 1), got " + std::to_string(x.rows()) + " x " +
                                std::to_string(x.cols()));
}

}  // namespace

FastStylizer::Layer FastStylizer::makeLayer(Mat<float> weight, Vec<float> bias, int in, int out, int width) {
  Layer layer;
  layer.weight = std::move(weight);
  layer.bias = std::move(bias);
  layer.in = in;
  layer.out = out;
  layer.width = width;
  layer.spectral.emplace(in, out, width, defaultSpectralPoints(width), SpectralPasses::ForwardOnly);
  layer.spectral->setKernel(layer.weight);
  return layer;
}

FastStylizer::Layer FastStylizer::copyLayer(const Conv1d<float>& conv) {
  return makeLayer(conv.weight.value, conv.hasBias() ? Vec<float>(conv.bias.value.col(0)) : Vec<float>(),
                   conv.inChannels(), conv.outChannels(), conv.width());
}

void FastStylizer::correlate(Layer& layer, const float* padded, Eigen::Index available, int count, float* out) {
  if (spectralIsFaster(layer.in, layer.out, layer.width, count)) {
    layer.spectral->forward(padded, available, count, out);
    return;
  }
  computePool().parallelRanges(count, 1, kMinColumnsPerThread, [&](int begin, int end) {
    Eigen::Map<Mat<float>> y(out + static_cast<Eigen::Index>(layer.out) * begin, layer.out, end - begin);
    y.noalias() = layer.weight * slidingColumns(padded + static_cast<Eigen::Index>(layer.in) * begin, layer.in,
                                                layer.width, end - begin);
  });
}

FastStylizer::FastStylizer(const LossNetwork<float>& loss_network) {
  features_ = loss_network.shape().features;
  hidden_ = loss_network.shape().hidden;
  encoder_ = copyLayer(loss_network.encoder);
  encoder_bias_ = encoder_.bias;
  buildPolyphase(loss_network);
}

FastStylizer::FastStylizer(const TransformationNetwork<float>& transformation, const LossNetwork<float>& loss_network)
    : FastStylizer(loss_network) {
  addTransformation(transformation);
}

FastStylizer::FastStylizer(const TransformationNetwork<float>& transformation, const FastStylizer& projection)
    : FastStylizer(projection) {  // a copy shares the prepared spectra (the layers' SpectralCorrelation)
  if (projection.has_transformer_)
    throw std::invalid_argument("FastStylizer: the projection to build on already has a transformation network");
  addTransformation(transformation);
}

void FastStylizer::addTransformation(const TransformationNetwork<float>& transformation) {
  if (transformation.shape().features != features_)
    throw std::invalid_argument("FastStylizer: the transformation network has " +
                                std::to_string(transformation.shape().features) +
                                " features, the loss network " + std::to_string(features_));
  has_transformer_ = true;
  residual_ = transformation.shape().residual;
  t1_ = copyLayer(transformation.conv1);
  t2_ = copyLayer(transformation.conv2);
  t3_ = copyLayer(transformation.conv3);
}

void FastStylizer::buildPolyphase(const LossNetwork<float>& loss_network) {
  // Output frame t = 2s + phase reads depooled frame u = t + k - pad = 2 * pooled + (u mod 2), so tap k
  // lands on pooled frame s + floorDiv(phase + k - pad, 2). Taps landing on the same pooled frame add.
  const int width = loss_network.decoder.width();
  const int pad = width / 2;
  const int first = floorDiv(-pad, 2);
  const int last = floorDiv(1 + pad, 2);
  phase_taps_ = last - first + 1;
  phase_left_ = -first;
  phase_right_ = last;
  const Mat<float>& w = loss_network.decoder.weight.value;  // features x (hidden * width)
  polyphase_.setZero(2 * features_, static_cast<Eigen::Index>(hidden_) * phase_taps_);
  for (int phase = 0; phase < 2; ++phase)
    for (int k = 0; k < width; ++k) {
      const int m = floorDiv(phase + k - pad, 2) - first;
      polyphase_.block(static_cast<Eigen::Index>(phase) * features_, static_cast<Eigen::Index>(m) * hidden_,
                       features_, hidden_) += w.middleCols(static_cast<Eigen::Index>(k) * hidden_, hidden_);
    }
  decoder_ = makeLayer(polyphase_, Vec<float>(), hidden_, 2 * features_, phase_taps_);
}

void FastStylizer::convolve(Layer& layer, const Mat<float>& in, Mat<float>& out, int frames, bool relu) {
  // `in` is padded by layer.width/2; `out` by its own consumer's padding (its extra columns / 2).
  const Eigen::Index out_pad = (out.cols() - frames) / 2;
  float* destination = out.data() + out.rows() * out_pad;
  correlate(layer, in.data(), in.cols(), frames, destination);
  computePool().parallelRanges(frames, 1, kMinColumnsPerThread, [&](int begin, int end) {
    Eigen::Map<Mat<float>> y(destination + out.rows() * begin, layer.out, end - begin);
    if (layer.bias.size() > 0) y.colwise() += layer.bias;
    if (relu) y = y.cwiseMax(0.0f);
  });
}

void FastStylizer::encodePadded(int frames) {
  const int even = frames + frames % 2;
  const int pooled = even / 2;
  const Eigen::Index enc_pad = encoder_.width / 2;
  if (frames % 2 == 1) encoder_input_.col(enc_pad + frames) = encoder_input_.col(enc_pad + frames - 1);

  // Encoder (eq. 1) + max-pool + ReLU, then "- b0" for the decoder (eq. 2), per column range.
  ensureZeroed(encoded_, hidden_, even);
  ensureZeroed(pooled_, hidden_, pooled + phase_left_ + phase_right_);
  correlate(encoder_, encoder_input_.data(), encoder_input_.cols(), even, encoded_.data());
  computePool().parallelRanges(even, 2, 2 * kMinColumnsPerThread, [&](int begin, int end) {
    for (int s = begin / 2; s < end / 2; ++s)
      pooled_.col(phase_left_ + s) =
          (encoded_.col(2 * s).cwiseMax(encoded_.col(2 * s + 1)) + encoder_bias_).cwiseMax(0.0f) - encoder_bias_;
  });
}

void FastStylizer::projectPadded(int frames, Mat<float>& out, const HiddenEdit& edit) {
  const int even = frames + frames % 2;
  const int pooled = even / 2;
  encodePadded(frames);
  if (edit) {
    Mat<float> hidden = pooled_.middleCols(phase_left_, pooled).colwise() + encoder_bias_;
    edit(hidden);
    if (hidden.rows() != hidden_ || hidden.cols() != pooled)
      throw std::invalid_argument("FastStylizer: the hidden-unit edit changed their shape");
    pooled_.middleCols(phase_left_, pooled) = hidden.colwise() - encoder_bias_;
  }

  // Polyphase decoder: column s of the (2*features) x pooled product is frames 2s and 2s+1.
  out.resize(features_, frames);
  float* destination = out.data();
  if (frames % 2 == 1) {
    if (decoded_.rows() != features_ || decoded_.cols() != even) decoded_.resize(features_, even);
    destination = decoded_.data();
  }
  correlate(decoder_, pooled_.data(), pooled_.cols(), pooled, destination);
  if (frames % 2 == 1) out = decoded_.leftCols(frames);
}

int FastStylizer::loadEncoderInput(const Mat<float>& x) {
  requireClip(x, features_);
  const int frames = static_cast<int>(x.cols());
  const Eigen::Index enc_pad = encoder_.width / 2;
  ensureZeroed(encoder_input_, features_, frames + frames % 2 + 2 * enc_pad);
  encoder_input_.middleCols(enc_pad, frames) = x;
  return frames;
}

void FastStylizer::project(const Mat<float>& x, Mat<float>& out) { projectPadded(loadEncoderInput(x), out); }

void FastStylizer::stylize(const Mat<float>& x, Mat<float>& out, const HiddenEdit& edit) {
  if (!has_transformer_) throw std::invalid_argument("FastStylizer: stylize() needs a transformation network");
  requireClip(x, features_);
  const int frames = static_cast<int>(x.cols());
  ensureZeroed(input_, features_, frames + 2 * (t1_.width / 2));
  ensureZeroed(hidden1_, t1_.out, frames + 2 * (t2_.width / 2));
  ensureZeroed(hidden2_, t2_.out, frames + 2 * (t3_.width / 2));
  const Eigen::Index enc_pad = encoder_.width / 2;
  ensureZeroed(encoder_input_, features_, frames + frames % 2 + 2 * enc_pad);
  input_.middleCols(t1_.width / 2, frames) = x;
  convolve(t1_, input_, hidden1_, frames, true);
  convolve(t2_, hidden1_, hidden2_, frames, true);
  // The encoder input has an extra column for odd clips: write T's output at its padding offset.
  float* t_output = encoder_input_.data() + features_ * enc_pad;
  correlate(t3_, hidden2_.data(), hidden2_.cols(), frames, t_output);
  computePool().parallelRanges(frames, 1, kMinColumnsPerThread, [&](int begin, int end) {
    Eigen::Map<Mat<float>> y(t_output + static_cast<Eigen::Index>(features_) * begin, features_, end - begin);
    y.colwise() += t3_.bias;
    if (residual_) y += x.middleCols(begin, end - begin);
  });
  projectPadded(frames, out, edit);
}

void FastStylizer::stylize(const Mat<float>& x, Mat<float>& out) { stylize(x, out, HiddenEdit{}); }

Mat<float> FastStylizer::encode(const Mat<float>& x) {
  const int frames = loadEncoderInput(x);
  encodePadded(frames);
  return pooled_.middleCols(phase_left_, (frames + frames % 2) / 2).colwise() + encoder_bias_;
}

Mat<float> FastStylizer::stylize(const Mat<float>& x) {
  Mat<float> out;
  stylize(x, out);
  return out;
}

Mat<float> FastStylizer::project(const Mat<float>& x) {
  Mat<float> out;
  project(x, out);
  return out;
}

}  // namespace motionstyle::nn
