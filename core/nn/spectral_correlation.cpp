#include "nn/spectral_correlation.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "nn/compute_pool.h"

namespace motionstyle::nn {
namespace {

// Parallel splits: a range of segments or rows must be worth a thread; frequencies are few and each
// is a whole matrix product.
constexpr int kMinSegmentsPerThread = 4;
constexpr int kMinBinsPerThread = 2;
constexpr int kMinRowsPerThread = 256;

// True for the frequencies whose spectrum of a real signal is real: DC and, for even N, Nyquist.
bool isRealBin(int f, int points) { return f == 0 || 2 * f == points; }

// a == b (same shape), compared by column ranges on the pool: a frozen network's kernels are
// compared at every forward pass.
template <typename S>
bool sameValues(const Mat<S>& a, const Mat<S>& b) {
  std::atomic<bool> same = true;
  parallelItems(a.cols(), a.rows(), [&](int begin, int end) {
    if (same.load(std::memory_order_relaxed) && a.middleCols(begin, end - begin) != b.middleCols(begin, end - begin))
      same = false;
  });
  return same;
}

template <typename S>
using ConstMap = Eigen::Map<const Mat<S>>;
template <typename S>
using MutableMap = Eigen::Map<Mat<S>>;

}  // namespace

int defaultSpectralPoints(int width) {
  const int wanted = width - 1 + (16 * width + 9) / 10;  // K - 1 + ceil(1.6 K)
  int points = 8;
  while (points < wanted) points *= 2;
  return points;
}

bool spectralEnabled() {
  // Read once: MOTIONSTYLE_NN_CONV=direct turns the spectral path off everywhere (to compare results
  // or speed); anything else keeps the cost model.
  static const bool enabled = [] {
    const char* env = std::getenv("MOTIONSTYLE_NN_CONV");
    return env == nullptr || std::string(env) != "direct";
  }();
  return enabled;
}

bool spectralIsFaster(int in, int out, int width, long count) {
  if (!spectralEnabled()) return false;
  const int points = defaultSpectralPoints(width);
  const double block = points - width + 1;
  const double bins = points / 2 + 1;
  const double mixing_saving = static_cast<double>(in) * out * (width - 3.0 * bins / block);
  const double transform_cost = static_cast<double>(in + out) * 5.0 * points * std::log2(points) / block;
  return count >= 2L * static_cast<long>(block) && mixing_saving > 2.0 * transform_cost;
}

namespace {

int checkedPoints(int in, int out, int width, int points) {
  if (in < 1 || out < 1 || width < 1 || width % 2 == 0 || points < std::max(4, width) || (points & (points - 1)) != 0)
    throw std::invalid_argument("SpectralCorrelation: channels must be >= 1, the width odd and the segment length a "
                                "power of two >= the width, got in " + std::to_string(in) + ", out " +
                                std::to_string(out) + ", width " + std::to_string(width) + ", points " +
                                std::to_string(points));
  return points;
}

}  // namespace

template <typename S>
SpectralCorrelation<S>::SpectralCorrelation(int in, int out, int width, int points, SpectralPasses passes)
    : in_(in),
      out_(out),
      width_(width),
      block_(checkedPoints(in, out, width, points) - width + 1),
      points_(points),
      bins_(points / 2 + 1),
      passes_(passes),
      fft_(points) {}

template <typename S>
void SpectralCorrelation<S>::setKernel(const Mat<S>& weight) {
  if (weight.rows() != out_ || weight.cols() != static_cast<Eigen::Index>(in_) * width_)
    throw std::invalid_argument("SpectralCorrelation: kernel is " + std::to_string(weight.rows()) + " x " +
                                std::to_string(weight.cols()) + ", expected " + std::to_string(out_) + " x " +
                                std::to_string(in_ * width_));
  if (kernel_ && kernel_->weight.size() == weight.size() && sameValues(kernel_->weight, weight)) return;
  if (!kernel_ || kernel_.use_count() > 1) kernel_ = std::make_shared<Kernel>();  // copies keep theirs
  Mat<S>& spectra = kernel_->spectra;
  Mat<S>& kept = kernel_->weight;
  kept.resize(weight.rows(), weight.cols());
  parallelItems(weight.cols(), weight.rows(), [&](int begin, int end) {
    kept.middleCols(begin, end - begin) = weight.middleCols(begin, end - begin);
  });
  // Tap-major storage makes the weight an (out*in) x K matrix whose row o + c*out holds w[o][c][.].
  const ConstMap<S> taps(weight.data(), static_cast<Eigen::Index>(out_) * in_, width_);
  spectra.resize(taps.rows(), 4 * bins_);
  fft_.forward(taps.data(), taps.rows(), width_, taps.rows(), spectra.data(), spectra.rows());
  computePool().parallelRanges(static_cast<int>(taps.rows()), 1, kMinRowsPerThread, [&](int begin, int end) {
    auto rows = spectra.middleRows(begin, end - begin);
    rows.middleCols(bins_, bins_) = -rows.middleCols(bins_, bins_);  // the conjugate: correlation, not convolution
    rows.middleCols(2 * bins_, bins_) = rows.leftCols(bins_) + rows.middleCols(bins_, bins_);
    rows.rightCols(bins_) = rows.leftCols(bins_) - rows.middleCols(bins_, bins_);
  });
  kernel_->forward_parts.resize(3 * static_cast<std::size_t>(bins_));
  computePool().parallelRanges(3 * bins_, 1, kMinBinsPerThread, [&](int begin, int end) {
    for (int index = begin; index < end; ++index)
      kernel_->forward_parts[index].pack(spectra.col(index).data(), out_, in_);
  });
  if (passes_ == SpectralPasses::ForwardOnly) spectra = Mat<S>();  // backward() is refused
}

template <typename S>
Eigen::Map<const Mat<S>> SpectralCorrelation<S>::kernelPart(int f, int part) const {
  return Eigen::Map<const Mat<S>>(kernel_->spectra.col(part * bins_ + f).data(), out_, in_);
}

template <typename S>
void SpectralCorrelation<S>::transform(const S* sequence, Eigen::Index available, int channels, int frames,
                                       Eigen::Index segments, Mat<S>& scratch, Mat<S>& spectra) const {
  scratch.resize(channels * segments, frames);
  spectra.resize(channels * segments, 2 * bins_);
  computePool().parallelRanges(static_cast<int>(segments), 1, kMinSegmentsPerThread, [&](int begin, int end) {
    for (int j = begin; j < end; ++j) {
      const Eigen::Index start = static_cast<Eigen::Index>(j) * block_;
      const Eigen::Index present = std::clamp<Eigen::Index>(available - start, 0, frames);
      auto rows = scratch.middleRows(static_cast<Eigen::Index>(j) * channels, channels);
      rows.leftCols(present) = ConstMap<S>(sequence + start * channels, channels, present);
      rows.rightCols(frames - present).setZero();
    }
  });
  fft_.forward(scratch.data(), scratch.rows(), frames, scratch.rows(), spectra.data(), spectra.rows());
}

template <typename S>
void SpectralCorrelation<S>::forward(const S* padded, Eigen::Index available, Eigen::Index count, S* out) {
  if (!kernel_) throw std::logic_error("SpectralCorrelation: forward() before setKernel()");
  const Eigen::Index segments = segmentCount(count);
  transform(padded, available, in_, points_, segments, segments_, input_spectra_);
  input_count_ = count;

  // Y_f = C_f S_f with Gauss's three real products: Yr = CrSr - CiSi, Yi = (Cr + Ci)(Sr + Si) - CrSr - CiSi.
  product_spectra_.resize(out_ * segments, 2 * bins_);
  const std::vector<PackedMatrix<S>>& parts = kernel_->forward_parts;
  computePool().parallelRanges(bins_, 1, kMinBinsPerThread, [&](int begin, int end) {
    Mat<S> ci_si(out_, segments), s_sum(in_, segments);
    typename PackedMatrix<S>::Scratch scratch;
    for (int f = begin; f < end; ++f) {
      const S* sr = input_spectra_.col(f).data();
      const S* si = input_spectra_.col(bins_ + f).data();
      S* yr_data = product_spectra_.col(f).data();
      MutableMap<S> yr(yr_data, out_, segments), yi(product_spectra_.col(bins_ + f).data(), out_, segments);
      parts[f].multiplyInto(sr, in_, segments, yr_data, out_, scratch);
      if (isRealBin(f, points_)) {
        yi.setZero();
        continue;
      }
      parts[bins_ + f].multiplyInto(si, in_, segments, ci_si.data(), out_, scratch);
      s_sum = ConstMap<S>(sr, in_, segments) + ConstMap<S>(si, in_, segments);
      parts[2 * bins_ + f].multiplyInto(s_sum.data(), in_, segments, yi.data(), out_, scratch);
      yi -= yr + ci_si;
      yr -= ci_si;
    }
  });

  frames_.resize(out_ * segments, block_);
  fft_.inverse(product_spectra_.data(), product_spectra_.rows(), frames_.rows(), block_, frames_.data(), frames_.rows());
  computePool().parallelRanges(static_cast<int>(segments), 1, kMinSegmentsPerThread, [&](int begin, int end) {
    for (int j = begin; j < end; ++j) {
      const Eigen::Index start = static_cast<Eigen::Index>(j) * block_;
      const Eigen::Index length = std::min<Eigen::Index>(block_, count - start);
      MutableMap<S>(out + start * out_, out_, length) =
          frames_.block(static_cast<Eigen::Index>(j) * out_, 0, out_, length);
    }
  });
}

template <typename S>
void SpectralCorrelation<S>::backward(const S* grad_out, Eigen::Index count, Mat<S>* weight_grad, S* padded_grad) {
  if (passes_ == SpectralPasses::ForwardOnly)
    throw std::logic_error("SpectralCorrelation: backward() of an instance made for the forward pass only");
  if (count != input_count_)
    throw std::logic_error("SpectralCorrelation: backward() over " + std::to_string(count) +
                           " outputs, the last forward() had " + std::to_string(input_count_));
  const Eigen::Index segments = segmentCount(count);
  transform(grad_out, count, out_, block_, segments, segments_, grad_spectra_);

  if (weight_grad != nullptr) {
    if (weight_grad->rows() != out_ || weight_grad->cols() != static_cast<Eigen::Index>(in_) * width_)
      throw std::invalid_argument("SpectralCorrelation: weight gradient has the wrong shape");
    // dW_f = conj(dY_f) S_f^T, out x in, stored like the kernel spectra; Gauss's three products:
    // Rr = dYr Sr^T + dYi Si^T, Ri = (dYr - dYi)(Sr + Si)^T - dYr Sr^T + dYi Si^T.
    product_spectra_.resize(static_cast<Eigen::Index>(out_) * in_, 2 * bins_);
    computePool().parallelRanges(bins_, 1, kMinBinsPerThread, [&](int begin, int end) {
      Mat<S> di_si(out_, in_), d_difference(out_, segments), s_sum(in_, segments);
      for (int f = begin; f < end; ++f) {
        const ConstMap<S> dr(grad_spectra_.col(f).data(), out_, segments),
            di(grad_spectra_.col(bins_ + f).data(), out_, segments);
        const ConstMap<S> sr(input_spectra_.col(f).data(), in_, segments),
            si(input_spectra_.col(bins_ + f).data(), in_, segments);
        MutableMap<S> rr(product_spectra_.col(f).data(), out_, in_), ri(product_spectra_.col(bins_ + f).data(), out_, in_);
        rr.noalias() = dr * sr.transpose();
        if (isRealBin(f, points_)) {
          ri.setZero();
          continue;
        }
        di_si.noalias() = di * si.transpose();
        d_difference = dr - di;
        s_sum = sr + si;
        ri.noalias() = d_difference * s_sum.transpose();
        ri += di_si - rr;
        rr += di_si;
      }
    });
    taps_.resize(product_spectra_.rows(), width_);
    fft_.inverse(product_spectra_.data(), product_spectra_.rows(), taps_.rows(), width_, taps_.data(), taps_.rows());
    MutableMap<S> weight_taps(weight_grad->data(), taps_.rows(), width_);
    parallelItems(width_, taps_.rows(), [&](int begin, int end) {
      weight_taps.middleCols(begin, end - begin) += taps_.middleCols(begin, end - begin);
    });
  }

  if (padded_grad != nullptr) {
    // dS_f = C_f^H dY_f, in x segments; Gauss's three products:
    // dSr = Cr^T dYr + Ci^T dYi, dSi = (Cr - Ci)^T (dYr + dYi) - Cr^T dYr + Ci^T dYi.
    product_spectra_.resize(in_ * segments, 2 * bins_);
    computePool().parallelRanges(bins_, 1, kMinBinsPerThread, [&](int begin, int end) {
      Mat<S> ci_di(in_, segments), d_sum(out_, segments);
      for (int f = begin; f < end; ++f) {
        const ConstMap<S> cr = kernelPart(f, 0), ci = kernelPart(f, 1), c_difference = kernelPart(f, 3);
        const ConstMap<S> dr(grad_spectra_.col(f).data(), out_, segments),
            di(grad_spectra_.col(bins_ + f).data(), out_, segments);
        MutableMap<S> gr(product_spectra_.col(f).data(), in_, segments),
            gi(product_spectra_.col(bins_ + f).data(), in_, segments);
        gr.noalias() = cr.transpose() * dr;
        if (isRealBin(f, points_)) {
          gi.setZero();
          continue;
        }
        ci_di.noalias() = ci.transpose() * di;
        d_sum = dr + di;
        gi.noalias() = c_difference.transpose() * d_sum;
        gi += ci_di - gr;
        gr += ci_di;
      }
    });
    frames_.resize(in_ * segments, points_);
    fft_.inverse(product_spectra_.data(), product_spectra_.rows(), frames_.rows(), points_, frames_.data(), frames_.rows());
    // Overlap-add. Neighbouring segments share K - 1 frames, so the pool splits the channels: each
    // part adds every segment of its own rows, in segment order.
    const Eigen::Index total = count + width_ - 1;
    parallelItems(in_, total, [&](int begin, int end) {
      MutableMap<S> grad(padded_grad, in_, total);
      for (Eigen::Index j = 0; j < segments; ++j) {
        const Eigen::Index start = j * block_;
        const Eigen::Index length = std::min<Eigen::Index>(points_, total - start);
        grad.block(begin, start, end - begin, length) += frames_.block(j * in_ + begin, 0, end - begin, length);
      }
    });
  }
}

template class SpectralCorrelation<float>;
template class SpectralCorrelation<double>;

}  // namespace motionstyle::nn
