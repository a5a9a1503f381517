#include "style/style_refinement.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "features/feature_layout.h"
#include "features/proportions.h"
#include "features/signal_filters.h"
#include "nn/losses.h"
#include "style/cancellation.h"
#include "style/hidden_style_descent.h"

namespace motionstyle::style {

void StyleRefinement::validate() const {
  if (iterations < 0 || iterations > kMaxIterations)
    throw std::invalid_argument("refinement iterations must be in [0, " + std::to_string(kMaxIterations) + "]");
  if (!std::isfinite(learning_rate) || learning_rate <= 0)
    throw std::invalid_argument("refinement learning rate must be > 0");
  if (!std::isfinite(content_weight) || !std::isfinite(style_weight) || content_weight < 0 || style_weight < 0 ||
      content_weight + style_weight <= 0)
    throw std::invalid_argument("refinement weights must be finite, >= 0 and not both 0");
  if (!(converged_fraction >= 0.0 && converged_fraction < 1.0))
    throw std::invalid_argument("refinement converged fraction must be in [0, 1)");
}

std::vector<float> transformationShare(const Eigen::MatrixXd& content, Eigen::Index columns) {
  if (content.rows() != kFeatureCount || content.cols() < 1 || columns < 0)
    throw std::invalid_argument("transformationShare: expected 66 x frames features and columns >= 0");
  const double leg = referenceProportions().legLength();
  const Eigen::Index last = content.cols() - 1;
  const int hips_height = 3 * static_cast<int>(CanonicalJoint::Hips) + 1;
  std::vector<float> share(static_cast<std::size_t>(columns));
  for (Eigen::Index k = 0; k < columns; ++k) {
    const double hips = 0.5 * (content(hips_height, std::min(2 * k, last)) + content(hips_height, std::min(2 * k + 1, last)));
    share[static_cast<std::size_t>(k)] =
        static_cast<float>(smoothstep((hips / leg - kCrouchedHipRatio) / (kUprightHipRatio - kCrouchedHipRatio)));
  }
  return share;
}

int nearestStyleTarget(const std::vector<nn::StyleTarget>& targets, const nn::Mat<float>& hidden) {
  if (targets.empty()) return -1;
  const nn::Mat<float> gram = nn::gramMatrix(hidden);
  int nearest = -1;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (targets[i].gram.rows() != gram.rows() || targets[i].gram.cols() != gram.cols())
      throw std::invalid_argument("nearestStyleTarget: a target is not hidden x hidden");
    const double distance = static_cast<double>((targets[i].gram - gram).squaredNorm());
    if (distance < best) {
      best = distance;
      nearest = static_cast<int>(i);
    }
  }
  return nearest;
}

int refineHiddenUnits(nn::Mat<float>& hidden, const nn::Mat<float>& content_hidden, const nn::Mat<float>& target,
                      const StyleRefinement& refinement, const std::atomic<bool>* cancel) {
  refinement.validate();
  if (content_hidden.rows() != hidden.rows() || content_hidden.cols() != hidden.cols() ||
      target.rows() != hidden.rows() || target.cols() != hidden.rows())
    throw std::invalid_argument("refineHiddenUnits: content hidden x frames as the hidden units, the target hidden x hidden");
  if (refinement.iterations == 0) return 0;
  HiddenStyleDescent descent(hidden, content_hidden, target, refinement.content_weight, refinement.style_weight,
                             refinement.learning_rate);
  constexpr int span = StyleRefinement::kConvergenceSteps;
  std::vector<double> objective;  // before each step: its size is the steps run
  objective.reserve(static_cast<std::size_t>(refinement.iterations));
  while (objective.size() < static_cast<std::size_t>(refinement.iterations)) {
    throwIfCancelled(cancel);
    objective.push_back(descent.step());
    const std::size_t now = objective.size() - 1;
    if (now >= span && objective[now - span] - objective[now] < refinement.converged_fraction * objective[now - span])
      break;
  }
  hidden = descent.value();
  return static_cast<int>(objective.size());
}

}  // namespace motionstyle::style
