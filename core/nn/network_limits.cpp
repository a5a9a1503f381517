#include "nn/network_limits.h"

#include <limits>
#include <cmath>
#include <sstream>

namespace motionstyle::nn {
namespace {

// "<field> = <value> is outside <range>" when value is not within [low, high] (NaN never is).
std::string outside(const std::string& field, double value, double low, double high, const char* range) {
  if (value >= low && value <= high) return {};
  std::ostringstream text;
  text << field << " = " << value << " is outside " << range;
  return text.str();
}

std::string countProblem(const char* field, int value) {
  return value < 0 ? std::string(field) + " = " + std::to_string(static_cast<unsigned>(value)) + " does not fit an int"
                   : std::string();
}

}  // namespace

std::string normalisationProblem(const FeatureStatistics& n) {
  if (n.mean.size() != kFeatureCount || n.std.size() != kFeatureCount)
    return "normalisation needs " + std::to_string(kFeatureCount) + " means and stds, got " +
           std::to_string(n.mean.size()) + " and " + std::to_string(n.std.size());
  for (Eigen::Index i = 0; i < kFeatureCount; ++i) {
    const std::string index = "[" + std::to_string(i) + "]";
    std::string problem = outside("normalisation mean" + index, n.mean(i), -kMaxNormalisationMean,
                                  kMaxNormalisationMean, "[-1e6, 1e6]");
    if (problem.empty())
      problem = outside("normalisation std" + index, n.std(i), kMinNormalisationStd, kMaxNormalisationStd, "[1e-6, 1e6]");
    if (!problem.empty()) return problem;
  }
  return {};
}

std::string metadataProblem(const NetworkMetadata& m) {
  const RepresentationInfo& r = m.representation;
  const TrainingConfig& t = m.training;
  const LossWeights& w = t.weights;
  for (const std::string& problem :
       {outside("fps", r.fps, kMinRepresentationValue, kMaxRepresentationValue, "[1, 1e4]"),
        outside("reference body height", r.reference_body_height_cm, kMinRepresentationValue, kMaxRepresentationValue,
                "[1, 1e4] cm"),
        countProblem("epochs", t.epochs), countProblem("batch windows", t.batch_windows),
        countProblem("window frames", t.window_frames),
        outside("learning rate", t.learning_rate, 0.0, std::numeric_limits<double>::max(), "[0, finite]"),
        outside("sparsity", t.sparsity, 0.0, kMaxTrainingCoefficient, "[0, 1e9]"),
        outside("loss weight (content)", w.content, 0.0, kMaxTrainingCoefficient, "[0, 1e9]"),
        outside("loss weight (style)", w.style, 0.0, kMaxTrainingCoefficient, "[0, 1e9]"),
        outside("loss weight (foot)", w.foot, 0.0, kMaxTrainingCoefficient, "[0, 1e9]"),
        outside("loss weight (bone)", w.bone, 0.0, kMaxTrainingCoefficient, "[0, 1e9]"),
        outside("loss weight (trajectory)", w.trajectory, 0.0, kMaxTrainingCoefficient, "[0, 1e9]")})
    if (!problem.empty()) return problem;
  if (!(t.dropout >= 0.0 && t.dropout < 1.0)) return outside("dropout", t.dropout, 0.0, -1.0, "[0, 1)");
  for (std::size_t e = 0; e < m.loss_history.epochs.size(); ++e)
    for (double value : m.loss_history.epochs[e])
      if (!(std::abs(value) <= kMaxLossValue))
        return outside("loss history (epoch " + std::to_string(e + 1) + ")", value, 0.0, -1.0,
                       "float32's finite range");
  return {};
}

std::string valuesProblem(const std::string& tensor_name, const Mat<float>& values, float max_magnitude) {
  for (Eigen::Index c = 0; c < values.cols(); ++c)
    for (Eigen::Index r = 0; r < values.rows(); ++r)
      if (!(std::abs(values(r, c)) <= max_magnitude)) {
        std::ostringstream text;
        text << "tensor '" << tensor_name << "' has the value " << values(r, c) << " at (" << r << ", " << c
             << "); trained networks stay within +-" << max_magnitude;
        return text.str();
      }
  return {};
}

}  // namespace motionstyle::nn
