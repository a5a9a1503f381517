#include "nn/real_fft.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "nn/compute_pool.h"

namespace motionstyle::nn {
namespace {

// Rows transformed together: 2 x (N/2) x 256 values stay in L1/L2 through all the butterflies.
constexpr Eigen::Index kChunkRows = 256;
constexpr int kMinRowsPerThread = 512;

}  // namespace

template <typename S>
RealFft<S>::RealFft(int points) : points_(points), half_(points / 2) {
  if (points < 4 || (points & (points - 1)) != 0)
    throw std::invalid_argument("RealFft: the length must be a power of two >= 4, got " + std::to_string(points));
  int bits = 0;
  while ((1 << bits) < half_) ++bits;
  reversed_.resize(static_cast<std::size_t>(half_));
  for (int m = 0; m < half_; ++m) {
    int r = 0;
    for (int b = 0; b < bits; ++b)
      if ((m >> b) & 1) r |= 1 << (bits - 1 - b);
    reversed_[static_cast<std::size_t>(m)] = r;
  }
  for (int j = 0; j < std::max(1, half_ / 2); ++j) {
    const double angle = 2.0 * std::numbers::pi * j / half_;
    twiddle_cos_.push_back(static_cast<S>(std::cos(angle)));
    twiddle_sin_.push_back(static_cast<S>(std::sin(angle)));
  }
  for (int k = 0; k <= half_; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / points;
    // Exact at k = 0 and k = N/2, so that those bins' imaginary parts come out exactly zero.
    split_cos_.push_back(static_cast<S>(k == 0 ? 1.0 : k == half_ ? -1.0 : std::cos(angle)));
    split_sin_.push_back(static_cast<S>(k == 0 || k == half_ ? 0.0 : std::sin(angle)));
  }
}

template <typename S>
void RealFft<S>::transformChunk(S* re, S* im, Eigen::Index chunk, int sign) const {
  for (int length = 2; length <= half_; length *= 2) {
    const int span = length / 2;
    const int step = half_ / length;
    for (int group = 0; group < half_; group += length)
      for (int j = 0; j < span; ++j) {
        const S wr = twiddle_cos_[static_cast<std::size_t>(j * step)];
        const S wi = static_cast<S>(sign) * twiddle_sin_[static_cast<std::size_t>(j * step)];
        S* __restrict ar = re + (group + j) * kChunkRows;
        S* __restrict ai = im + (group + j) * kChunkRows;
        S* __restrict br = re + (group + j + span) * kChunkRows;
        S* __restrict bi = im + (group + j + span) * kChunkRows;
        for (Eigen::Index i = 0; i < chunk; ++i) {
          const S tr = br[i] * wr - bi[i] * wi;
          const S ti = br[i] * wi + bi[i] * wr;
          br[i] = ar[i] - tr;
          bi[i] = ai[i] - ti;
          ar[i] += tr;
          ai[i] += ti;
        }
      }
  }
}

template <typename S>
void RealFft<S>::forward(const S* in, Eigen::Index in_stride, int samples, Eigen::Index rows, S* out,
                         Eigen::Index out_stride) const {
  if (samples < 0 || samples > points_)
    throw std::invalid_argument("RealFft::forward: " + std::to_string(samples) + " samples for " +
                                std::to_string(points_) + " points");
  const Eigen::Index bins = half_ + 1;
  computePool().parallelRanges(static_cast<int>(rows), 1, kMinRowsPerThread, [&](int begin, int end) {
    std::vector<S> re(static_cast<std::size_t>(half_ * kChunkRows)), im(re.size());
    for (Eigen::Index first = begin; first < end; first += kChunkRows) {
      const Eigen::Index chunk = std::min<Eigen::Index>(kChunkRows, end - first);
      // z[m] = x[2m] + i x[2m+1], stored in bit-reversed order for the decimation-in-time butterflies.
      for (int m = 0; m < half_; ++m) {
        S* dr = re.data() + reversed_[static_cast<std::size_t>(m)] * kChunkRows;
        S* di = im.data() + reversed_[static_cast<std::size_t>(m)] * kChunkRows;
        const int even = 2 * m, odd = 2 * m + 1;
        for (Eigen::Index i = 0; i < chunk; ++i) {
          dr[i] = even < samples ? in[even * in_stride + first + i] : S(0);
          di[i] = odd < samples ? in[odd * in_stride + first + i] : S(0);
        }
      }
      transformChunk(re.data(), im.data(), chunk, -1);
      // X[k] = E[k] + W^k O[k], W^k = cos - i sin.
      for (int k = 0; k <= half_; ++k) {
        const S* ar = re.data() + (k % half_) * kChunkRows;
        const S* ai = im.data() + (k % half_) * kChunkRows;
        const S* br = re.data() + ((half_ - k) % half_) * kChunkRows;
        const S* bi = im.data() + ((half_ - k) % half_) * kChunkRows;
        const S wr = split_cos_[static_cast<std::size_t>(k)], wi = -split_sin_[static_cast<std::size_t>(k)];
        S* xr = out + k * out_stride + first;
        S* xi = out + (bins + k) * out_stride + first;
        for (Eigen::Index i = 0; i < chunk; ++i) {
          const S er = S(0.5) * (ar[i] + br[i]), ei = S(0.5) * (ai[i] - bi[i]);
          const S orr = S(0.5) * (ai[i] + bi[i]), oi = S(-0.5) * (ar[i] - br[i]);
          xr[i] = er + wr * orr - wi * oi;
          xi[i] = ei + wr * oi + wi * orr;
        }
        if (k == 0 || k == half_)
          for (Eigen::Index i = 0; i < chunk; ++i) xi[i] = S(0);
      }
    }
  });
}

template <typename S>
void RealFft<S>::inverse(const S* spectra, Eigen::Index spectra_stride, Eigen::Index rows, int samples, S* out,
                         Eigen::Index out_stride) const {
  if (samples < 0 || samples > points_)
    throw std::invalid_argument("RealFft::inverse: " + std::to_string(samples) + " samples for " +
                                std::to_string(points_) + " points");
  const Eigen::Index bins = half_ + 1;
  const S scale = S(1) / static_cast<S>(half_);
  computePool().parallelRanges(static_cast<int>(rows), 1, kMinRowsPerThread, [&](int begin, int end) {
    std::vector<S> re(static_cast<std::size_t>(half_ * kChunkRows)), im(re.size());
    for (Eigen::Index first = begin; first < end; first += kChunkRows) {
      const Eigen::Index chunk = std::min<Eigen::Index>(kChunkRows, end - first);
      // Z[k] = E[k] + i O[k] with E = (X[k] + conj X[N/2-k]) / 2, O = (X[k] - conj X[N/2-k]) conj(W^k) / 2.
      for (int k = 0; k < half_; ++k) {
        const int other = half_ - k;  // 1..N/2
        const S* ar = spectra + k * spectra_stride + first;
        const S* ai = spectra + (bins + k) * spectra_stride + first;
        const S* br = spectra + other * spectra_stride + first;
        const S* bi = spectra + (bins + other) * spectra_stride + first;
        const bool a_real = k == 0, b_real = other == half_;  // bins 0 and N/2: imaginary part zero
        const S c = split_cos_[static_cast<std::size_t>(k)], s = split_sin_[static_cast<std::size_t>(k)];
        S* zr = re.data() + reversed_[static_cast<std::size_t>(k)] * kChunkRows;
        S* zi = im.data() + reversed_[static_cast<std::size_t>(k)] * kChunkRows;
        for (Eigen::Index i = 0; i < chunk; ++i) {
          const S xai = a_real ? S(0) : ai[i], xbi = b_real ? S(0) : bi[i];
          const S er = S(0.5) * (ar[i] + br[i]), ei = S(0.5) * (xai - xbi);
          const S dr = S(0.5) * (ar[i] - br[i]), di = S(0.5) * (xai + xbi);
          const S orr = dr * c - di * s, oi = dr * s + di * c;
          zr[i] = er - oi;
          zi[i] = ei + orr;
        }
      }
      transformChunk(re.data(), im.data(), chunk, +1);
      for (int m = 0; m < half_; ++m) {
        const int even = 2 * m, odd = 2 * m + 1;
        const S* zr = re.data() + m * kChunkRows;
        const S* zi = im.data() + m * kChunkRows;
        if (even < samples)
          for (Eigen::Index i = 0; i < chunk; ++i) out[even * out_stride + first + i] = zr[i] * scale;
        if (odd < samples)
          for (Eigen::Index i = 0; i < chunk; ++i) out[odd * out_stride + first + i] = zi[i] * scale;
      }
    }
  });
}

template class RealFft<float>;
template class RealFft<double>;

}  // namespace motionstyle::nn
