#include "nn/conv1d.h"

#include <stdexcept>

#include "nn/compute_pool.h"

namespace motionstyle::nn {
namespace {

// Below this many output columns per thread, splitting costs more than it saves.
constexpr int kMinColumnsPerThread = 48;

// Copies the valid outputs (window b, frame t at padded-output column b*(frames+pad) + t) into a
// compact out x (B*frames) matrix, adding `bias` (out x 1) to every column when it is not null.
template <typename S>
Mat<S> compactWindows(const Eigen::Ref<const Mat<S>>& full, int windows, int frames, int pad,
                      const Mat<S>* bias = nullptr) {
  Mat<S> out(full.rows(), static_cast<Eigen::Index>(windows) * frames);
  parallelItems(windows, full.rows() * frames, [&](int begin, int end) {
    for (Eigen::Index b = begin; b < end; ++b) {
      auto window = out.middleCols(b * frames, frames);
      window = full.middleCols(b * (frames + pad), frames);
      if (bias != nullptr) window.colwise() += bias->col(0);
    }
  });
  return out;
}

// Adds the sum over columns of `grad` (rows x cols) into `sum` (rows x 1), rows split over the pool;
// each row's columns are added in column order, so no split changes a bit.
template <typename S>
void addRowSums(const Mat<S>& grad, Mat<S>& sum) {
  parallelItems(grad.rows(), grad.cols(), [&](int begin, int end) {
    Vec<S> rows = Vec<S>::Zero(end - begin);
    for (Eigen::Index c = 0; c < grad.cols(); ++c) rows += grad.col(c).segment(begin, end - begin);
    sum.col(0).segment(begin, end - begin) += rows;
  });
}

}  // namespace

int checkBatch(const char* what, Eigen::Index rows, Eigen::Index cols, int channels, int frames) {
  if (frames < 1) throw std::invalid_argument(std::string(what) + ": frames per window must be >= 1");
  if (rows != channels)
    throw std::invalid_argument(std::string(what) + ": expected " + std::to_string(channels) +
                                " channels, got " + std::to_string(rows));
  if (cols < frames || cols % frames != 0)
    throw std::invalid_argument(std::string(what) + ": " + std::to_string(cols) +
                                " columns is not a whole number of windows of " +
                                std::to_string(frames) + " frames");
  return static_cast<int>(cols / frames);
}

template <typename S>
void correlatePadded(const Mat<S>& weight, const S* padded, Eigen::Index channels, int width, S* out,
                     Eigen::Index count, bool parallel) {
  const Eigen::Index rows = weight.rows();
  auto range = [&](int begin, int end) {
    Eigen::Map<Mat<S>> y(out + rows * begin, rows, end - begin);
    y.noalias() = weight * slidingColumns(padded + channels * begin, channels, width, end - begin);
  };
  if (parallel)
    computePool().parallelRanges(static_cast<int>(count), 1, kMinColumnsPerThread, range);
  else
    range(0, static_cast<int>(count));
}

template <typename S>
void padWindows(const Mat<S>& x, int frames, int pad, Mat<S>& padded) {
  const Eigen::Index windows = x.cols() / frames;
  padded.resize(x.rows(), pad + windows * (frames + pad));
  padded.leftCols(pad).setZero();
  parallelItems(windows, x.rows() * (frames + pad), [&](int begin, int end) {
    for (Eigen::Index b = begin; b < end; ++b) {
      padded.middleCols(pad + b * (frames + pad), frames) = x.middleCols(b * frames, frames);
      padded.middleCols(pad + b * (frames + pad) + frames, pad).setZero();
    }
  });
}

template <typename S>
Conv1d<S>::Conv1d(const std::string& name, int in_channels, int out_channels, int width, bool has_bias)
    : in_(in_channels), out_(out_channels), width_(width), has_bias_(has_bias) {
  if (in_channels < 1 || out_channels < 1)
    throw std::invalid_argument("Conv1d " + name + ": channel counts must be >= 1");
  if (width < 1 || width % 2 == 0)
    throw std::invalid_argument("Conv1d " + name + ": width must be odd and >= 1, got " +
                                std::to_string(width));
  weight.name = name + ".weight";
  weight.resize(out_channels, static_cast<Eigen::Index>(in_channels) * width);
  bias.name = name + ".bias";
  if (has_bias) bias.resize(out_channels, 1);
}

template <typename S>
bool Conv1d<S>::useSpectral(Eigen::Index count) const {
  switch (algorithm_) {
    case ConvAlgorithm::Direct: return false;
    case ConvAlgorithm::Spectral: return true;
    case ConvAlgorithm::Automatic: break;
  }
  return spectralIsFaster(in_, out_, width_, static_cast<long>(count));
}

template <typename S>
Mat<S> Conv1d<S>::run(const Mat<S>& padded, int windows, int frames, SpectralCorrelation<S>* spectral) const {
  const int pad = width_ / 2;
  const Eigen::Index count = static_cast<Eigen::Index>(windows) * (frames + pad) - pad;
  Mat<S> full(out_, count);
  if (spectral != nullptr) {
    spectral->setKernel(weight.value);
    spectral->forward(padded.data(), padded.cols(), count, full.data());
  } else {
    correlatePadded(weight.value, padded.data(), in_, width_, full.data(), count);
  }
  return compactWindows<S>(full, windows, frames, pad, has_bias_ ? &bias.value : nullptr);
}

template <typename S>
Mat<S> Conv1d<S>::apply(const Mat<S>& x, int frames) const {
  const int windows = checkBatch(weight.name.c_str(), x.rows(), x.cols(), in_, frames);
  Mat<S> padded;
  padWindows(x, frames, width_ / 2, padded);
  const Eigen::Index count = static_cast<Eigen::Index>(windows) * (frames + width_ / 2) - width_ / 2;
  if (!useSpectral(count)) return run(padded, windows, frames, nullptr);
  // A const call keeps no state: its own spectra (the kernel's are recomputed, a small share of a
  // batch long enough for the spectral path).
  SpectralCorrelation<S> spectral(in_, out_, width_, defaultSpectralPoints(width_));
  return run(padded, windows, frames, &spectral);
}

template <typename S>
Mat<S> Conv1d<S>::forward(const Mat<S>& x, int frames) {
  windows_ = checkBatch(weight.name.c_str(), x.rows(), x.cols(), in_, frames);
  frames_ = frames;
  padWindows(x, frames, width_ / 2, padded_input_);
  const Eigen::Index count = static_cast<Eigen::Index>(windows_) * (frames + width_ / 2) - width_ / 2;
  spectral_forward_ = useSpectral(count);
  if (spectral_forward_ && !spectral_) spectral_.emplace(in_, out_, width_, defaultSpectralPoints(width_));
  return run(padded_input_, windows_, frames_, spectral_forward_ ? &*spectral_ : nullptr);
}

template <typename S>
Mat<S> Conv1d<S>::backward(const Mat<S>& grad_out, Gradients wanted) {
  if (frames_ == 0) throw std::logic_error("Conv1d " + weight.name + ": backward() before forward()");
  checkBatch(weight.name.c_str(), grad_out.rows(), grad_out.cols(), out_, frames_);
  if (grad_out.cols() != static_cast<Eigen::Index>(windows_) * frames_)
    throw std::invalid_argument("Conv1d " + weight.name + ": gradient batch differs from forward()");
  const int pad = width_ / 2;
  const Eigen::Index count = static_cast<Eigen::Index>(windows_) * (frames_ + pad) - pad;
  Mat<S> padded_grad;  // dY in the padded layout: zero in the gaps, so gap outputs contribute nothing
  padWindows(grad_out, frames_, pad, padded_grad);

  if (spectral_forward_) {
    // dY at every output position of the padded sequence starts `pad` columns into padded_grad; the
    // input gradient comes back at every position of the padded input.
    Mat<S> padded_input_grad;
    if (wanted != Gradients::ParametersOnly) {
      padded_input_grad.resize(in_, count + width_ - 1);
      parallelItems(padded_input_grad.cols(), in_, [&](int begin, int end) {
        padded_input_grad.middleCols(begin, end - begin).setZero();
      });
    }
    spectral_->backward(padded_grad.data() + static_cast<Eigen::Index>(pad) * out_, count,
                        wanted != Gradients::InputOnly ? &weight.grad : nullptr,
                        wanted != Gradients::ParametersOnly ? padded_input_grad.data() : nullptr);
    if (wanted != Gradients::InputOnly && has_bias_) addRowSums(grad_out, bias.grad);
    if (wanted == Gradients::ParametersOnly) return Mat<S>();
    return compactWindows<S>(padded_input_grad.middleCols(pad, count), windows_, frames_, pad);
  }

  if (wanted != Gradients::InputOnly) {
    const auto dy = padded_grad.middleCols(pad, count);
    const auto columns = slidingColumns(padded_input_.data(), in_, width_, count);
    Mat<S>& dw = weight.grad;
    computePool().parallelRanges(static_cast<int>(dw.cols()), 1, 64, [&](int begin, int end) {
      dw.middleCols(begin, end - begin).noalias() +=
          dy * columns.middleRows(begin, end - begin).transpose();
    });
    if (has_bias_) addRowSums(grad_out, bias.grad);
  }
  if (wanted == Gradients::ParametersOnly) return Mat<S>();

  // dx[t] = sum_k W_k^T dy[t + K/2 - k]: a correlation of dY with the kernel flipped in time and
  // transposed per tap (block i of `flipped` is W_{K-1-i}^T).
  Mat<S> flipped(in_, static_cast<Eigen::Index>(out_) * width_);
  for (int i = 0; i < width_; ++i)
    flipped.middleCols(static_cast<Eigen::Index>(i) * out_, out_) =
        weight.value.middleCols(static_cast<Eigen::Index>(width_ - 1 - i) * in_, in_).transpose();
  Mat<S> full(in_, count);
  correlatePadded(flipped, padded_grad.data(), out_, width_, full.data(), count);
  return compactWindows<S>(full, windows_, frames_, pad);
}

template <typename S>
void Conv1d<S>::zeroGrad() {
  weight.zeroGrad();
  if (has_bias_) bias.zeroGrad();
}

template <typename S>
std::vector<Parameter<S>*> Conv1d<S>::parameters() {
  if (has_bias_) return {&weight, &bias};
  return {&weight};
}

template class Conv1d<float>;
template class Conv1d<double>;
template void correlatePadded<float>(const Mat<float>&, const float*, Eigen::Index, int, float*,
                                     Eigen::Index, bool);
template void correlatePadded<double>(const Mat<double>&, const double*, Eigen::Index, int, double*,
                                      Eigen::Index, bool);
template void padWindows<float>(const Mat<float>&, int, int, Mat<float>&);
template void padWindows<double>(const Mat<double>&, int, int, Mat<double>&);

}  // namespace motionstyle::nn
