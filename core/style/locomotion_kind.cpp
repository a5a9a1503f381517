#include "style/locomotion_kind.h"

#include <numbers>
#include <stdexcept>

#include "features/feature_layout.h"

namespace motionstyle::style {

std::string locomotionKind(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts) {
  if (features.rows() != kFeatureCount || features.cols() < 1)
    throw std::invalid_argument("locomotionKind: expected 66 x frames features with frames >= 1");
  const bool has_contacts = contacts.size() > 0;
  if (has_contacts && (contacts.rows() != kContactCount || contacts.cols() != features.cols()))
    throw std::invalid_argument("locomotionKind: contacts must be 4 x frames (the features') or empty");
  const double frames = static_cast<double>(features.cols());
  bool run = false;
  if (has_contacts) {
    Eigen::Index airborne = 0;
    for (Eigen::Index t = 0; t < contacts.cols(); ++t) airborne += (contacts.col(t).array() <= 0.5).all() ? 1 : 0;
    run = static_cast<double>(airborne) >= kRunFlightShare * frames;
  } else {
    run = features.row(kForwardVelocity).mean() * kDefaultFeatureFps >= kRunSpeedCmPerSecond;
  }
  if (run) return "run";
  const double turning = features.row(kTurningVelocity).mean() * kDefaultFeatureFps * 180.0 / std::numbers::pi;
  if (turning >= kTurnDegreesPerSecond) return "walk-turn-left";
  if (turning <= -kTurnDegreesPerSecond) return "walk-turn-right";
  return "walk";
}

bool isLocomotionKind(std::string_view kind) {
  for (std::string_view known : kLocomotionKinds)
    if (kind == known) return true;
  return false;
}

std::string locomotionKindList() {
  std::string list;
  for (std::size_t i = 0; i < kLocomotionKinds.size(); ++i) {
    if (i > 0) list += i + 1 == kLocomotionKinds.size() ? " or " : ", ";
    list += kLocomotionKinds[i];
  }
  return list;
}

void requireKindOrNone(const std::string& kind, std::string_view what) {
  if (!kind.empty() && !isLocomotionKind(kind))
    throw std::invalid_argument(std::string(what) + " '" + kind + "' is none of " + locomotionKindList());
}

std::string locomotionKindText(std::string_view kind) {
  if (kind == "walk-turn-left") return "walk turning left";
  if (kind == "walk-turn-right") return "walk turning right";
  return std::string(kind);
}

int styleTargetFor(const std::vector<nn::StyleTarget>& targets, const std::string& kind) {
  const auto labelled = [&](const std::string& label) {
    for (std::size_t i = 0; i < targets.size(); ++i)
      if (targets[i].label == label) return static_cast<int>(i);
    return -1;
  };
  int target = labelled(kind);
  if (target < 0 && kind.rfind("walk-turn", 0) == 0) target = labelled("walk");
  if (target < 0) target = labelled("");
  return target;
}

}  // namespace motionstyle::style
