#include "nn/adam.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "nn/compute_pool.h"

namespace motionstyle::nn {

void AdamOptions::validate() const {
  const bool ok = std::isfinite(learning_rate) && learning_rate > 0.0 && std::isfinite(beta1) &&
                  beta1 >= 0.0 && beta1 < 1.0 && std::isfinite(beta2) && beta2 >= 0.0 && beta2 < 1.0 &&
                  std::isfinite(epsilon) && epsilon > 0.0 && std::isfinite(gradient_clip) && gradient_clip >= 0.0 &&
                  clip_warmup_steps >= 0;
  if (!ok)
    throw std::invalid_argument("AdamOptions: need lr > 0, 0 <= beta1, beta2 < 1, eps > 0, gradient_clip >= 0 and "
                                "clip_warmup_steps >= 0");
}

template <typename S>
Adam<S>::Adam(std::vector<Parameter<S>*> parameters, AdamOptions options)
    : parameters_(std::move(parameters)), options_(options) {
  options_.validate();
  for (const Parameter<S>* p : parameters_) {
    if (p == nullptr) throw std::invalid_argument("Adam: null parameter");
    first_moment_.push_back(Mat<S>::Zero(p->value.rows(), p->value.cols()));
    second_moment_.push_back(Mat<S>::Zero(p->value.rows(), p->value.cols()));
  }
}

template <typename S>
void Adam<S>::setLearningRate(double learning_rate) {
  AdamOptions changed = options_;
  changed.learning_rate = learning_rate;
  changed.validate();
  options_ = changed;
}

template <typename S>
void Adam<S>::restore(long steps, std::vector<Mat<S>> first, std::vector<Mat<S>> second) {
  if (steps < 0 || first.size() != parameters_.size() || second.size() != parameters_.size())
    throw std::invalid_argument("optimiser state: wrong number of moments");
  for (std::size_t i = 0; i < parameters_.size(); ++i) {
    const Mat<S>& value = parameters_[i]->value;
    if (first[i].rows() != value.rows() || first[i].cols() != value.cols() || second[i].rows() != value.rows() ||
        second[i].cols() != value.cols())
      throw std::invalid_argument("optimiser state: moment shapes differ from parameter " + parameters_[i]->name);
  }
  steps_ = steps;
  first_moment_ = std::move(first);
  second_moment_ = std::move(second);
}

template <typename S>
void Adam<S>::step() {
  // v^ of the moments as they stand (before this step's gradient), for the outlier clipping.
  const bool clipping = options_.gradient_clip > 0.0 && steps_ >= std::max(1L, options_.clip_warmup_steps);
  const double previous_correction2 = 1.0 - std::pow(options_.beta2, static_cast<double>(steps_));
  clipped_in_last_step_ = 0;
  ++steps_;
  const double correction1 = 1.0 - std::pow(options_.beta1, static_cast<double>(steps_));
  const double correction2 = 1.0 - std::pow(options_.beta2, static_cast<double>(steps_));
  const S b1 = static_cast<S>(options_.beta1);
  const S b2 = static_cast<S>(options_.beta2);
  const S step_size = static_cast<S>(options_.learning_rate / correction1);
  const S inv_sqrt_c2 = static_cast<S>(1.0 / std::sqrt(correction2));
  const S eps = static_cast<S>(options_.epsilon);
  for (std::size_t i = 0; i < parameters_.size(); ++i) {
    Parameter<S>& p = *parameters_[i];
    if (p.grad.rows() != p.value.rows() || p.grad.cols() != p.value.cols() ||
        first_moment_[i].rows() != p.value.rows() || first_moment_[i].cols() != p.value.cols())
      throw std::invalid_argument("Adam: parameter " + p.name + " changed shape");
    Mat<S>& first = first_moment_[i];
    Mat<S>& second = second_moment_[i];
    const long block = std::max<long>(1, kMinValuesPerPart / std::max<Eigen::Index>(1, p.value.rows()));
    S scale = S(1);
    if (clipping) {
      const double second_sum = parallelSum(second.cols(), block, [&](int begin, int end) {
        return static_cast<double>(second.middleCols(begin, end - begin).sum());
      });
      const double grad_squares = parallelSum(p.grad.cols(), block, [&](int begin, int end) {
        return static_cast<double>(p.grad.middleCols(begin, end - begin).squaredNorm());
      });
      const double expected = std::sqrt(second_sum / previous_correction2);
      const double norm = std::sqrt(grad_squares);
      const double bound = options_.gradient_clip * expected;
      if (expected > 0.0 && norm > bound) {
        scale = static_cast<S>(bound / norm);
        ++clipped_in_last_step_;
      }
    }
    parallelItems(p.value.cols(), p.value.rows(), [&](int begin, int end) {
      auto m = first.middleCols(begin, end - begin);
      auto v = second.middleCols(begin, end - begin);
      const auto g = p.grad.middleCols(begin, end - begin);
      m = b1 * m + ((S(1) - b1) * scale) * g;
      v = b2 * v + ((S(1) - b2) * scale * scale) * g.cwiseAbs2();
      p.value.middleCols(begin, end - begin).array() -= step_size * m.array() / (v.array().sqrt() * inv_sqrt_c2 + eps);
    });
  }
}

template <typename S>
void Adam<S>::zeroGrad() {
  for (Parameter<S>* p : parameters_) p->zeroGrad();
}

template class Adam<float>;
template class Adam<double>;

}  // namespace motionstyle::nn
