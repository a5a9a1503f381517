#include "nn/losses.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "nn/compute_pool.h"

namespace motionstyle::nn {
namespace {

void requireShape(const char* what, Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows,
                  Eigen::Index want_cols) {
  if (rows != want_rows || cols != want_cols)
    throw std::invalid_argument(std::string(what) + ": got " + std::to_string(rows) + " x " +
                                std::to_string(cols) + ", expected " + std::to_string(want_rows) +
                                " x " + std::to_string(want_cols));
}

template <typename S>
void requireGrad(const char* what, const Mat<S>* grad, const Mat<S>& input) {
  if (grad != nullptr) requireShape(what, grad->rows(), grad->cols(), input.rows(), input.cols());
}

// Frames per block of the per-frame constraint terms' parallel sums (a few hundred operations each).
constexpr long kFramesPerBlock = 512;

int windowCount(const char* what, const Mat<double>::Index cols, int frames) {
  if (frames < 1 || cols % frames != 0)
    throw std::invalid_argument(std::string(what) + ": columns are not a whole number of windows");
  return static_cast<int>(cols / frames);
}

// De-normalised view helpers: x = x_n * std + mean for one feature.
template <typename S>
struct Denormaliser {
  Vec<S> mean;
  Vec<S> std;
  explicit Denormaliser(const FeatureStatistics& n) {
    n.validate();
    mean = n.mean.cast<S>();
    std = n.std.cast<S>();
  }
  S value(const Mat<S>& xn, int feature, Eigen::Index t) const {
    return xn(feature, t) * std(feature) + mean(feature);
  }
  Eigen::Matrix<S, 3, 1> position(const Mat<S>& xn, int joint, Eigen::Index t) const {
    return {value(xn, 3 * joint, t), value(xn, 3 * joint + 1, t), value(xn, 3 * joint + 2, t)};
  }
};

// Adds g (a gradient wrt de-normalised joint position) into grad wrt normalised values.
template <typename S>
void addPositionGrad(Mat<S>& grad, const Vec<S>& std, int joint, Eigen::Index t,
                     const Eigen::Matrix<S, 3, 1>& g) {
  for (int a = 0; a < 3; ++a) grad(3 * joint + a, t) += g(a) * std(3 * joint + a);
}

}  // namespace

template <typename S>
S meanSquaredError(const Mat<S>& output, const Mat<S>& target, S weight, Mat<S>* grad) {
  requireShape("meanSquaredError", output.rows(), output.cols(), target.rows(), target.cols());
  requireGrad("meanSquaredError grad", grad, output);
  if (output.size() == 0) return S(0);
  const S count = static_cast<S>(output.size());
  const S scale = S(2) * weight / count;
  const double total = parallelSum(output.cols(), std::max<long>(1, kMinValuesPerPart / output.rows()), [&](int begin, int end) {
    const auto diff = output.middleCols(begin, end - begin) - target.middleCols(begin, end - begin);
    if (grad != nullptr) grad->middleCols(begin, end - begin) += scale * diff;
    return static_cast<double>(diff.squaredNorm());
  });
  return static_cast<S>(total / static_cast<double>(output.size()));
}

template <typename S>
S meanAbsoluteWeight(const std::vector<Parameter<S>*>& parameters, S weight) {
  Eigen::Index count = 0;
  S sum = 0;
  for (const Parameter<S>* p : parameters) {
    count += p->value.size();
    sum += p->value.cwiseAbs().sum();
  }
  if (count == 0) return S(0);
  const S scale = weight / static_cast<S>(count);
  for (Parameter<S>* p : parameters) {
    requireShape("meanAbsoluteWeight grad", p->grad.rows(), p->grad.cols(), p->value.rows(),
                 p->value.cols());
    p->grad += scale * p->value.unaryExpr([](S w) { return w > S(0) ? S(1) : (w < S(0) ? S(-1) : S(0)); });
  }
  return sum / static_cast<S>(count);
}

template <typename S>
Mat<S> gramMatrix(const Mat<S>& hidden) {
  if (hidden.cols() == 0) throw std::invalid_argument("gramMatrix: no frames");
  Mat<S> gram(hidden.rows(), hidden.rows());
  gram.noalias() = hidden * hidden.transpose();
  return gram / static_cast<S>(hidden.cols());
}

template <typename S>
S styleLoss(const Mat<S>& hidden, int frames, const std::vector<Mat<S>>& style_grams, S weight,
            Mat<S>* grad) {
  const int windows = windowCount("styleLoss", hidden.cols(), frames);
  requireGrad("styleLoss grad", grad, hidden);
  if (style_grams.size() != 1 && style_grams.size() != static_cast<std::size_t>(windows))
    throw std::invalid_argument("styleLoss: need 1 or " + std::to_string(windows) +
                                " style Gram matrices, got " + std::to_string(style_grams.size()));
  const Eigen::Index channels = hidden.rows();
  for (const Mat<S>& g : style_grams) requireShape("styleLoss Gram", g.rows(), g.cols(), channels, channels);
  const S entries = static_cast<S>(channels * channels) * static_cast<S>(windows);
  // Windows are independent (each its own Gram matrix and its own gradient columns), so they are
  // split over the compute pool; per-window sums are added in window order, so the result does not
  // depend on the thread count.
  std::vector<S> window_totals(static_cast<std::size_t>(windows), S(0));
  computePool().parallelRanges(windows, 1, 1, [&](int begin, int end) {
    for (int b = begin; b < end; ++b) {
      const auto h = hidden.middleCols(static_cast<Eigen::Index>(b) * frames, frames);
      const Mat<S>& target = style_grams.size() == 1 ? style_grams[0] : style_grams[static_cast<std::size_t>(b)];
      const Mat<S> diff = gramMatrix<S>(h) - target;
      window_totals[static_cast<std::size_t>(b)] = diff.squaredNorm();
      if (grad != nullptr) {
        // d/dh of sum (h h^T / n - G)^2 = 2 (D + D^T) h / n with D = diff, symmetric when G is.
        const Mat<S> sym = diff + diff.transpose();
        grad->middleCols(static_cast<Eigen::Index>(b) * frames, frames).noalias() +=
            (S(2) * weight / (entries * static_cast<S>(frames))) * (sym * h);
      }
    }
  });
  S total = 0;
  for (S window_total : window_totals) total += window_total;
  return total / entries;
}

template <typename S>
S footContactLoss(const Mat<S>& x_normalised, int frames, const Mat<S>& contacts,
                  const FeatureStatistics& normalisation, S weight, Mat<S>* grad) {
  using V3 = Eigen::Matrix<S, 3, 1>;
  const int windows = windowCount("footContactLoss", x_normalised.cols(), frames);
  requireShape("footContactLoss frames", x_normalised.rows(), x_normalised.cols(), kFeatureCount,
               x_normalised.cols());
  requireShape("footContactLoss contacts", contacts.rows(), contacts.cols(), kContactCount,
               x_normalised.cols());
  requireGrad("footContactLoss grad", grad, x_normalised);
  const Denormaliser<S> d(normalisation);

  Eigen::Index labelled = 0;
  for (int b = 0; b < windows; ++b)
    for (int t = 0; t + 1 < frames; ++t)
      for (int c = 0; c < kContactCount; ++c)
        if (contacts(c, static_cast<Eigen::Index>(b) * frames + t) > S(0.5)) ++labelled;
  if (labelled == 0) return S(0);

  const S scale = S(2) * weight / static_cast<S>(labelled);
  S total = 0;
  for (int b = 0; b < windows; ++b) {
    for (int t = 0; t + 1 < frames; ++t) {
      const Eigen::Index now = static_cast<Eigen::Index>(b) * frames + t;
      const S turn = d.value(x_normalised, kTurningVelocity, now);
      const S cos_w = std::cos(turn);
      const S sin_w = std::sin(turn);
      const V3 velocity(d.value(x_normalised, kSidewaysVelocity, now), S(0),
                        d.value(x_normalised, kForwardVelocity, now));
      for (int c = 0; c < kContactCount; ++c) {
        if (!(contacts(c, now) > S(0.5))) continue;
        const int joint = index(kContactJoint[static_cast<std::size_t>(c)]);
        const V3 p = d.position(x_normalised, joint, now);
        const V3 q = d.position(x_normalised, joint, now + 1);
        // R_y(w) q, right-handed about +Y.
        const V3 rotated(cos_w * q.x() + sin_w * q.z(), q.y(), -sin_w * q.x() + cos_w * q.z());
        const V3 disp = velocity + rotated - p;
        total += disp.squaredNorm();
        if (grad == nullptr) continue;
        const V3 g = scale * disp;  // d(weight * |d|^2 / n) / d(disp)
        (*grad)(kSidewaysVelocity, now) += g.x() * d.std(kSidewaysVelocity);
        (*grad)(kForwardVelocity, now) += g.z() * d.std(kForwardVelocity);
        // d(R q)/dw = (-sin q_x + cos q_z, 0, -cos q_x - sin q_z)
        const S d_turn = g.x() * (-sin_w * q.x() + cos_w * q.z()) + g.z() * (-cos_w * q.x() - sin_w * q.z());
        (*grad)(kTurningVelocity, now) += d_turn * d.std(kTurningVelocity);
        // d/dq = R^T g
        const V3 gq(cos_w * g.x() - sin_w * g.z(), g.y(), sin_w * g.x() + cos_w * g.z());
        addPositionGrad<S>(*grad, d.std, joint, now + 1, gq);
        addPositionGrad<S>(*grad, d.std, joint, now, -g);
      }
    }
  }
  return total / static_cast<S>(labelled);
}

template <typename S>
S boneLengthLoss(const Mat<S>& x_normalised, int frames, const Mat<S>& bone_lengths,
                 const FeatureStatistics& normalisation, S weight, Mat<S>* grad) {
  using V3 = Eigen::Matrix<S, 3, 1>;
  const int windows = windowCount("boneLengthLoss", x_normalised.cols(), frames);
  requireShape("boneLengthLoss frames", x_normalised.rows(), x_normalised.cols(), kFeatureCount,
               x_normalised.cols());
  requireShape("boneLengthLoss lengths", bone_lengths.rows(), bone_lengths.cols(), kBoneCount, windows);
  requireGrad("boneLengthLoss grad", grad, x_normalised);
  const Denormaliser<S> d(normalisation);
  const S count = static_cast<S>(kBoneCount) * static_cast<S>(x_normalised.cols());
  const S scale = S(2) * weight / count;
  const S min_length = S(1e-6);
  // Frames are independent (each writes only its own gradient column): blocks of them on the pool.
  const double total = parallelSum(x_normalised.cols(), kFramesPerBlock, [&](int begin, int end) {
    S sum = 0;
    for (Eigen::Index t = begin; t < end; ++t) {
      const Eigen::Index window = t / frames;
      for (int b = 0; b < kBoneCount; ++b) {
        const int child = b + 1;
        const int parent = kCanonicalParent[static_cast<std::size_t>(child)];
        const V3 u = d.position(x_normalised, child, t) - d.position(x_normalised, parent, t);
        const S length = u.norm();
        const S error = length - bone_lengths(b, window);
        sum += error * error;
        if (grad == nullptr || length < min_length) continue;
        const V3 g = (scale * error / length) * u;
        addPositionGrad<S>(*grad, d.std, child, t, g);
        addPositionGrad<S>(*grad, d.std, parent, t, -g);
      }
    }
    return static_cast<double>(sum);
  });
  return static_cast<S>(total / static_cast<double>(count));
}

template <typename S>
S trajectoryLoss(const Mat<S>& x_normalised, const Mat<S>& target_normalised,
                 const FeatureStatistics& normalisation, S weight, Mat<S>* grad) {
  requireShape("trajectoryLoss frames", x_normalised.rows(), x_normalised.cols(), kFeatureCount,
               x_normalised.cols());
  requireShape("trajectoryLoss target", target_normalised.rows(), target_normalised.cols(),
               kFeatureCount, x_normalised.cols());
  requireGrad("trajectoryLoss grad", grad, x_normalised);
  if (x_normalised.cols() == 0) return S(0);
  const Denormaliser<S> d(normalisation);
  const S count = static_cast<S>(x_normalised.cols());
  S total = 0;
  for (Eigen::Index t = 0; t < x_normalised.cols(); ++t) {
    for (int f : {kSidewaysVelocity, kForwardVelocity, kTurningVelocity}) {
      // The means cancel in the difference; only std matters.
      const S diff = (x_normalised(f, t) - target_normalised(f, t)) * d.std(f);
      total += diff * diff;
      if (grad != nullptr) (*grad)(f, t) += S(2) * weight / count * diff * d.std(f);
    }
  }
  return total / count;
}

#define MOTIONSTYLE_INSTANTIATE_LOSSES(S)                                                             \
  template S meanSquaredError<S>(const Mat<S>&, const Mat<S>&, S, Mat<S>*);                          \
  template S meanAbsoluteWeight<S>(const std::vector<Parameter<S>*>&, S);                            \
  template Mat<S> gramMatrix<S>(const Mat<S>&);                                                       \
  template S styleLoss<S>(const Mat<S>&, int, const std::vector<Mat<S>>&, S, Mat<S>*);               \
  template S footContactLoss<S>(const Mat<S>&, int, const Mat<S>&, const FeatureStatistics&, S, Mat<S>*); \
  template S boneLengthLoss<S>(const Mat<S>&, int, const Mat<S>&, const FeatureStatistics&, S, Mat<S>*);  \
  template S trajectoryLoss<S>(const Mat<S>&, const Mat<S>&, const FeatureStatistics&, S, Mat<S>*);

MOTIONSTYLE_INSTANTIATE_LOSSES(float)
MOTIONSTYLE_INSTANTIATE_LOSSES(double)
#undef MOTIONSTYLE_INSTANTIATE_LOSSES

}  // namespace motionstyle::nn
