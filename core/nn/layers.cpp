#include "nn/layers.h"

#include <stdexcept>
#include <string>

#include "nn/compute_pool.h"

namespace motionstyle::nn {
namespace {

void requireEvenFrames(const char* what, Eigen::Index cols, int frames) {
  if (frames < 2 || frames % 2 != 0 || cols % frames != 0)
    throw std::invalid_argument(std::string(what) + ": windows need an even number of frames (got " +
                                std::to_string(frames) + " frames, " + std::to_string(cols) +
                                " columns)");
}

void requireSameShape(const char* what, Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows,
                      Eigen::Index want_cols) {
  if (rows != want_rows || cols != want_cols)
    throw std::invalid_argument(std::string(what) + ": gradient is " + std::to_string(rows) + " x " +
                                std::to_string(cols) + ", expected " + std::to_string(want_rows) +
                                " x " + std::to_string(want_cols));
}

}  // namespace

template <typename S>
Mat<S> Relu<S>::apply(const Mat<S>& x) {
  Mat<S> y(x.rows(), x.cols());
  parallelItems(x.cols(), x.rows(), [&](int begin, int end) {
    y.middleCols(begin, end - begin) = x.middleCols(begin, end - begin).cwiseMax(S(0));
  });
  return y;
}

template <typename S>
Mat<S> Relu<S>::forward(const Mat<S>& x) {
  Mat<S> y(x.rows(), x.cols());
  output_.resize(x.rows(), x.cols());
  parallelItems(x.cols(), x.rows(), [&](int begin, int end) {
    y.middleCols(begin, end - begin) = x.middleCols(begin, end - begin).cwiseMax(S(0));
    output_.middleCols(begin, end - begin) = y.middleCols(begin, end - begin);
  });
  return y;
}

template <typename S>
Mat<S> Relu<S>::backward(const Mat<S>& grad_out) const {
  requireSameShape("Relu", grad_out.rows(), grad_out.cols(), output_.rows(), output_.cols());
  Mat<S> dx(grad_out.rows(), grad_out.cols());
  parallelItems(dx.cols(), dx.rows(), [&](int begin, int end) {
    dx.middleCols(begin, end - begin) = (output_.middleCols(begin, end - begin).array() > S(0))
                                            .select(grad_out.middleCols(begin, end - begin), S(0));
  });
  return dx;
}

template <typename S>
Mat<S> MaxPool2<S>::apply(const Mat<S>& x, int frames) {
  requireEvenFrames("MaxPool2", x.cols(), frames);
  Mat<S> y(x.rows(), x.cols() / 2);
  parallelItems(y.cols(), 2 * y.rows(), [&](int begin, int end) {
    for (Eigen::Index s = begin; s < end; ++s) y.col(s) = x.col(2 * s).cwiseMax(x.col(2 * s + 1));
  });
  return y;
}

template <typename S>
Mat<S> MaxPool2<S>::forward(const Mat<S>& x, int frames) {
  requireEvenFrames("MaxPool2", x.cols(), frames);
  Mat<S> y(x.rows(), x.cols() / 2);
  second_.resize(x.rows(), x.cols() / 2);
  parallelItems(y.cols(), 2 * y.rows(), [&](int begin, int end) {
    for (Eigen::Index s = begin; s < end; ++s) {
      for (Eigen::Index c = 0; c < x.rows(); ++c) {
        const S first = x(c, 2 * s);
        const S second = x(c, 2 * s + 1);
        const bool second_wins = second > first;
        second_(c, s) = second_wins ? 1 : 0;
        y(c, s) = second_wins ? second : first;
      }
    }
  });
  return y;
}

template <typename S>
Mat<S> MaxPool2<S>::backward(const Mat<S>& grad_out) const {
  requireSameShape("MaxPool2", grad_out.rows(), grad_out.cols(), second_.rows(), second_.cols());
  Mat<S> dx(grad_out.rows(), grad_out.cols() * 2);
  parallelItems(grad_out.cols(), 2 * grad_out.rows(), [&](int begin, int end) {
    for (Eigen::Index s = begin; s < end; ++s)
      for (Eigen::Index c = 0; c < grad_out.rows(); ++c) {
        const bool second_won = second_(c, s) != 0;
        dx(c, 2 * s) = second_won ? S(0) : grad_out(c, s);
        dx(c, 2 * s + 1) = second_won ? grad_out(c, s) : S(0);
      }
  });
  return dx;
}

template <typename S>
Mat<S> AverageDepool2<S>::apply(const Mat<S>& x) {
  Mat<S> y(x.rows(), x.cols() * 2);
  parallelItems(x.cols(), 2 * x.rows(), [&](int begin, int end) {
    for (Eigen::Index s = begin; s < end; ++s) {
      y.col(2 * s) = x.col(s);
      y.col(2 * s + 1) = x.col(s);
    }
  });
  return y;
}

template <typename S>
Mat<S> AverageDepool2<S>::backward(const Mat<S>& grad_out) {
  if (grad_out.cols() % 2 != 0)
    throw std::invalid_argument("AverageDepool2: gradient has an odd number of frames");
  Mat<S> dx(grad_out.rows(), grad_out.cols() / 2);
  parallelItems(dx.cols(), 2 * dx.rows(), [&](int begin, int end) {
    for (Eigen::Index s = begin; s < end; ++s) dx.col(s) = grad_out.col(2 * s) + grad_out.col(2 * s + 1);
  });
  return dx;
}

template <typename S>
Mat<S> SubtractSharedBias<S>::apply(const Mat<S>& x) const {
  if (shared_ == nullptr) throw std::logic_error("SubtractSharedBias: no bias bound");
  if (shared_->value.rows() != x.rows() || shared_->value.cols() != 1)
    throw std::invalid_argument("SubtractSharedBias: bias has " + std::to_string(shared_->value.rows()) +
                                " rows, input " + std::to_string(x.rows()) + " channels");
  return x.colwise() - shared_->value.col(0);
}

template <typename S>
Mat<S> SubtractSharedBias<S>::backward(const Mat<S>& grad_out, bool accumulate_parameter) const {
  if (shared_ == nullptr) throw std::logic_error("SubtractSharedBias: no bias bound");
  if (grad_out.rows() != shared_->value.rows())
    throw std::invalid_argument("SubtractSharedBias: gradient has the wrong channel count");
  if (accumulate_parameter) shared_->grad.col(0) -= grad_out.rowwise().sum();
  return grad_out;
}

template <typename S>
Mat<S> Dropout<S>::forward(const Mat<S>& x, S rate, std::mt19937& rng) {
  if (!(rate >= S(0) && rate < S(1))) throw std::invalid_argument("Dropout: rate must be in [0, 1)");
  const S keep_scale = S(1) / (S(1) - rate);
  // A threshold on the raw 32-bit draw keeps the mask identical on every standard library.
  const auto threshold = static_cast<std::uint64_t>(static_cast<double>(rate) * 4294967296.0);
  scale_.resize(x.rows(), x.cols());
  for (Eigen::Index i = 0; i < scale_.size(); ++i)
    scale_.data()[i] = static_cast<std::uint64_t>(rng()) < threshold ? S(0) : keep_scale;
  return x.cwiseProduct(scale_);
}

template <typename S>
Mat<S> Dropout<S>::backward(const Mat<S>& grad_out) const {
  requireSameShape("Dropout", grad_out.rows(), grad_out.cols(), scale_.rows(), scale_.cols());
  return grad_out.cwiseProduct(scale_);
}

template <typename S>
Mat<S> padToEvenFrames(const Mat<S>& x, int frames) {
  if (frames < 1 || x.cols() % frames != 0)
    throw std::invalid_argument("padToEvenFrames: columns are not a whole number of windows");
  if (frames % 2 == 0) return x;
  const Eigen::Index windows = x.cols() / frames;
  Mat<S> y(x.rows(), windows * (frames + 1));
  for (Eigen::Index b = 0; b < windows; ++b) {
    y.middleCols(b * (frames + 1), frames) = x.middleCols(b * frames, frames);
    y.col(b * (frames + 1) + frames) = x.col(b * frames + frames - 1);
  }
  return y;
}

template <typename S>
Mat<S> foldEvenPaddingGradient(const Mat<S>& grad_padded, int frames) {
  if (frames % 2 == 0) return grad_padded;
  const Eigen::Index windows = grad_padded.cols() / (frames + 1);
  Mat<S> dx(grad_padded.rows(), windows * frames);
  for (Eigen::Index b = 0; b < windows; ++b) {
    dx.middleCols(b * frames, frames) = grad_padded.middleCols(b * (frames + 1), frames);
    dx.col(b * frames + frames - 1) += grad_padded.col(b * (frames + 1) + frames);
  }
  return dx;
}

template <typename S>
Mat<S> cropToFrames(const Mat<S>& x_padded, int frames) {
  if (frames % 2 == 0) return x_padded;
  const Eigen::Index windows = x_padded.cols() / (frames + 1);
  Mat<S> y(x_padded.rows(), windows * frames);
  for (Eigen::Index b = 0; b < windows; ++b)
    y.middleCols(b * frames, frames) = x_padded.middleCols(b * (frames + 1), frames);
  return y;
}

template <typename S>
Mat<S> uncropGradient(const Mat<S>& grad, int frames) {
  if (frames % 2 == 0) return grad;
  const Eigen::Index windows = grad.cols() / frames;
  Mat<S> dx = Mat<S>::Zero(grad.rows(), windows * (frames + 1));
  for (Eigen::Index b = 0; b < windows; ++b)
    dx.middleCols(b * (frames + 1), frames) = grad.middleCols(b * frames, frames);
  return dx;
}

#define MOTIONSTYLE_INSTANTIATE_LAYERS(S)                               \
  template class Relu<S>;                                               \
  template class MaxPool2<S>;                                           \
  template class AverageDepool2<S>;                                     \
  template class SubtractSharedBias<S>;                                 \
  template class Dropout<S>;                                            \
  template Mat<S> padToEvenFrames<S>(const Mat<S>&, int);               \
  template Mat<S> foldEvenPaddingGradient<S>(const Mat<S>&, int);       \
  template Mat<S> cropToFrames<S>(const Mat<S>&, int);                  \
  template Mat<S> uncropGradient<S>(const Mat<S>&, int);

MOTIONSTYLE_INSTANTIATE_LAYERS(float)
MOTIONSTYLE_INSTANTIATE_LAYERS(double)
#undef MOTIONSTYLE_INSTANTIATE_LAYERS

}  // namespace motionstyle::nn
