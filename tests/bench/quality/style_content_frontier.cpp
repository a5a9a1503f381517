// style_content_frontier.h: the Lagrangian per clip by L-BFGS, mu by the secant method.
#include "style_content_frontier.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

namespace motionstyle::bench {
namespace {

// The Lagrangian at hidden units X (hidden x T), mean((X - H)^2) + lambda * mean((X X^T / T - G_s)^2), and
// its gradient in X when `gradient` is not null:
//   2 (X - H) / (C T) + 4 lambda (Gram(X) - G_s) X / (T C^2).
double lagrangian(const FrontierClip& clip, double lambda, const Eigen::Ref<const Eigen::MatrixXd>& x,
                  Eigen::MatrixXd* gradient) {
  const Eigen::Index c = x.rows(), t = x.cols();
  const Eigen::MatrixXd gram_error = x * x.transpose() / static_cast<double>(t) - clip.style_gram;
  const Eigen::MatrixXd content_error = x - clip.hidden;
  const double ct = static_cast<double>(c * t), cc = static_cast<double>(c * c);
  if (gradient != nullptr) {
    *gradient = (2.0 / ct) * content_error;
    gradient->noalias() += (4.0 * lambda / (static_cast<double>(t) * cc)) * gram_error * x;
  }
  return content_error.squaredNorm() / ct + lambda * gram_error.squaredNorm() / cc;
}

// lagrangian() of the hidden units themselves (FrontierSpace::HiddenUnits).
class ClipLagrangian final : public ceres::FirstOrderFunction {
 public:
  ClipLagrangian(const FrontierClip& clip, double lambda) : clip_(clip), lambda_(lambda) {}
  int NumParameters() const override { return static_cast<int>(clip_.hidden.size()); }
  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    const Eigen::Map<const Eigen::MatrixXd> x(parameters, clip_.hidden.rows(), clip_.hidden.cols());
    Eigen::MatrixXd grad;
    *cost = lagrangian(clip_, lambda_, x, gradient != nullptr ? &grad : nullptr);
    if (gradient != nullptr) Eigen::Map<Eigen::MatrixXd>(gradient, x.rows(), x.cols()) = grad;
    return true;
  }

 private:
  const FrontierClip& clip_;
  double lambda_;
};

// lagrangian() of H' = enc(X) as a function of the normalised motion X (features x frames), its gradient
// through the encoder (nn::LossNetwork::encodeBackward; float, as the networks run).
class MotionLagrangian final : public ceres::FirstOrderFunction {
 public:
  MotionLagrangian(const FrontierClip& clip, double lambda) : clip_(clip), lambda_(lambda), encoder_(*clip.encoder) {}
  int NumParameters() const override { return static_cast<int>(clip_.features.size()); }
  bool Evaluate(const double* parameters, double* cost, double* gradient) const override {
    const Eigen::Map<const Eigen::MatrixXd> x(parameters, clip_.features.rows(), clip_.features.cols());
    const Eigen::MatrixXd h =
        encoder_.encodeForward(x.cast<float>(), static_cast<int>(clip_.features.cols())).cast<double>();
    Eigen::MatrixXd grad_hidden;
    *cost = lagrangian(clip_, lambda_, h, gradient != nullptr ? &grad_hidden : nullptr);
    if (gradient != nullptr)
      Eigen::Map<Eigen::MatrixXd>(gradient, x.rows(), x.cols()) =
          encoder_.encodeBackward(grad_hidden.cast<float>()).cast<double>();
    return true;
  }

 private:
  const FrontierClip& clip_;
  double lambda_;
  mutable nn::LossNetwork<float> encoder_;  // its own forward caches
};

double styleDistance(const FrontierClip& clip, const Eigen::MatrixXd& x) {
  const double c = static_cast<double>(clip.hidden.rows());
  return (x * x.transpose() / static_cast<double>(x.cols()) - clip.style_gram).squaredNorm() / (c * c);
}

// Solves every clip at mu from `solutions` (updated in place); the set's mean ratio and content.
FrontierPoint solveAt(const std::vector<FrontierClip>& clips, const std::vector<double>& style_before, double mu,
                      FrontierSpace space, std::vector<Eigen::MatrixXd>& solutions) {
  std::vector<double> ratio(clips.size()), content(clips.size());
  const auto solveRange = [&](std::size_t begin, std::size_t step) {
    for (std::size_t i = begin; i < clips.size(); i += step) {
      const double lambda = mu / style_before[i];
      const bool motions = space == FrontierSpace::Motions;
      ceres::GradientProblem problem(motions ? static_cast<ceres::FirstOrderFunction*>(new MotionLagrangian(clips[i], lambda))
                                             : new ClipLagrangian(clips[i], lambda));
      ceres::GradientProblemSolver::Options options;
      options.max_num_iterations = 300;
      options.function_tolerance = motions ? 1e-7 : 1e-10;  // float encoder: its cost is good to about 1e-7
      options.logging_type = ceres::SILENT;
      ceres::GradientProblemSolver::Summary summary;
      ceres::Solve(options, problem, solutions[i].data(), &summary);
      const Eigen::MatrixXd hidden =
          motions ? clips[i].encoder->encode(solutions[i].cast<float>(), static_cast<int>(solutions[i].cols())).cast<double>()
                  : solutions[i];
      ratio[i] = styleDistance(clips[i], hidden) / style_before[i];
      content[i] = (hidden - clips[i].hidden).squaredNorm() / static_cast<double>(clips[i].hidden.size());
    }
  };
  const std::size_t threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (std::size_t k = 1; k < threads; ++k) pool.emplace_back(solveRange, k, threads);
  solveRange(0, threads);
  for (std::thread& thread : pool) thread.join();
  FrontierPoint point;
  point.mu = mu;
  point.mean_style_ratio = 0.0;
  for (std::size_t i = 0; i < clips.size(); ++i) {
    point.mean_style_ratio += ratio[i] / static_cast<double>(clips.size());
    point.mean_content_distance += content[i] / static_cast<double>(clips.size());
  }
  point.solves = static_cast<int>(clips.size());
  return point;
}

}  // namespace

FrontierPoint leastContentAtStyleRatio(const std::vector<FrontierClip>& clips, double wanted_ratio, FrontierSpace space) {
  if (clips.empty()) throw std::invalid_argument("leastContentAtStyleRatio: no clips");
  if (!(wanted_ratio > 0.0 && wanted_ratio < 1.0))
    throw std::invalid_argument("leastContentAtStyleRatio: the wanted style ratio must be in (0, 1)");
  std::vector<double> style_before;
  std::vector<Eigen::MatrixXd> solutions;
  for (const FrontierClip& clip : clips) {
    const Eigen::Index c = clip.hidden.rows();
    if (c == 0 || clip.hidden.cols() == 0 || clip.style_gram.rows() != c || clip.style_gram.cols() != c)
      throw std::invalid_argument("leastContentAtStyleRatio: a clip's hidden units and style Gram matrix disagree");
    style_before.push_back(styleDistance(clip, clip.hidden));
    if (!(style_before.back() > 0.0))
      throw std::invalid_argument("leastContentAtStyleRatio: a clip already has its style (style distance 0)");
    if (space == FrontierSpace::Motions && (clip.encoder == nullptr || clip.features.cols() == 0))
      throw std::invalid_argument("leastContentAtStyleRatio: the motion frontier needs each clip's encoder and features");
    solutions.push_back(space == FrontierSpace::Motions ? clip.features : clip.hidden);
  }
  // Secant steps on f(log mu) = log(mean ratio) - log(wanted), each at most a factor 30 in mu.
  double log_mu = std::log(0.01);
  FrontierPoint point = solveAt(clips, style_before, std::exp(log_mu), space, solutions);
  int solves = point.solves;
  double previous_log_mu = log_mu, previous_f = std::log(point.mean_style_ratio / wanted_ratio);
  log_mu += previous_f > 0.0 ? std::log(4.0) : -std::log(4.0);
  FrontierPoint best = point;
  for (int step = 0; step < 14; ++step) {
    point = solveAt(clips, style_before, std::exp(log_mu), space, solutions);
    solves += point.solves;
    const double f = std::log(point.mean_style_ratio / wanted_ratio);
    if (std::abs(f) < std::abs(std::log(best.mean_style_ratio / wanted_ratio))) best = point;
    if (std::abs(f) < 0.005) break;
    double next = f == previous_f ? log_mu + (f > 0.0 ? 1.0 : -1.0)
                                  : log_mu - f * (log_mu - previous_log_mu) / (f - previous_f);
    next = std::clamp(next, log_mu - std::log(30.0), log_mu + std::log(30.0));
    previous_log_mu = log_mu;
    previous_f = f;
    log_mu = next;
  }
  best.solves = solves;
  return best;
}

}  // namespace motionstyle::bench
