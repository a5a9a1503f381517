#include "style/familiarity.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "style/stylizer.h"

namespace motionstyle::style {
namespace {

void requireFeatures(const Eigen::MatrixXd& features) {
  if (features.rows() != kFeatureCount || features.cols() < 1)
    throw std::invalid_argument("measureFamiliarity: expected 66 x frames (frames >= 1)");
}

}  // namespace

Familiarity familiarityFromReconstruction(const Eigen::MatrixXd& features, const Eigen::MatrixXd& reconstructed) {
  requireFeatures(features);
  if (reconstructed.rows() != features.rows() || reconstructed.cols() != features.cols())
    throw std::invalid_argument("familiarityFromReconstruction: the reconstruction must match the features' shape");
  Familiarity result;
  const Eigen::Index frames = features.cols();
  result.per_frame_cm.assign(static_cast<std::size_t>(frames), 0.0);
  for (Eigen::Index f = 0; f < frames; ++f) {
    double sum = 0.0;
    for (int c = 0; c < kCanonicalJointCount; ++c)
      sum += (reconstructed.col(f).segment<3>(3 * c) - features.col(f).segment<3>(3 * c)).norm();
    result.per_frame_cm[static_cast<std::size_t>(f)] = sum / kCanonicalJointCount;
  }
  double total = 0.0;
  for (double e : result.per_frame_cm) total += e;
  result.mean_cm = total / static_cast<double>(frames);
  // Worst one-second stretch (a running sum over a window of the representation's rate).
  const Eigen::Index window = std::min<Eigen::Index>(frames, static_cast<Eigen::Index>(kDefaultFeatureFps));
  double running = 0.0;
  for (Eigen::Index f = 0; f < frames; ++f) {
    running += result.per_frame_cm[static_cast<std::size_t>(f)];
    if (f >= window) running -= result.per_frame_cm[static_cast<std::size_t>(f - window)];
    if (f + 1 >= window) result.worst_second_cm = std::max(result.worst_second_cm, running / static_cast<double>(window));
  }
  result.level = familiarityLevel(result.mean_cm);
  return result;
}

Familiarity measureFamiliarity(const nn::LossNetworkModel& loss_network, const Eigen::MatrixXd& features) {
  requireFeatures(features);
  return familiarityFromReconstruction(features, projectFeatures(loss_network, features));
}

Familiarity measureFamiliarity(const nn::StyleModel& network, const Eigen::MatrixXd& features) {
  requireFeatures(features);
  return familiarityFromReconstruction(features, projectFeatures({network.loss_network, network.normalisation, {}}, features));
}

Familiarity measureFamiliarity(const Stylizer& stylizer, const Eigen::MatrixXd& features) {
  requireFeatures(features);
  return familiarityFromReconstruction(features, stylizer.projectFeatures(features));
}

FamiliarityLevel familiarityLevel(double mean_cm) {
  if (mean_cm <= kFamiliarMaxCm) return FamiliarityLevel::Familiar;
  if (mean_cm <= kUnusualMaxCm) return FamiliarityLevel::Unusual;
  return FamiliarityLevel::Far;
}

const char* familiarityName(FamiliarityLevel level) {
  switch (level) {
    case FamiliarityLevel::Familiar: return "familiar";
    case FamiliarityLevel::Unusual: return "unusual";
    case FamiliarityLevel::Far: return "far";
  }
  return "far";
}

std::string familiaritySummary(const Familiarity& familiarity) {
  char figure[32];
  std::snprintf(figure, sizeof figure, " (%.1f cm)", familiarity.mean_cm);
  const std::string head = std::string(familiarityName(familiarity.level)) + figure;
  switch (familiarity.level) {
    case FamiliarityLevel::Familiar: return head + ": like the motion the networks learnt from";
    case FamiliarityLevel::Unusual:
      return head + ": results usable; adapt the networks to clips like this one for better ones";
    case FamiliarityLevel::Far:
      return head + ": results will be weak; adapt the networks to clips like this one first";
  }
  return head;
}

}  // namespace motionstyle::style
