#include "features/feature_statistics.h"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "features/feature_layout.h"

namespace motionstyle {
namespace {

constexpr double kMinimumStd = 1e-4;  // a constant feature must not divide by zero
constexpr int kPositionChannels = 3 * kCanonicalJointCount;

}  // namespace

void FeatureStatistics::validate() const {
  if (mean.size() != kFeatureCount || std.size() != kFeatureCount)
    throw std::invalid_argument("feature statistics must have 66 means and 66 stds");
  if (!mean.allFinite() || !std.allFinite() || (std.array() <= 0.0).any())
    throw std::invalid_argument("feature statistics must be finite with positive stds");
}

void FeatureStatistics::normalize(Eigen::MatrixXd& features) const {
  if (features.rows() != kFeatureCount) throw std::invalid_argument("normalize: features must have 66 rows");
  features = (features.colwise() - mean).array().colwise() / std.array();
}

void FeatureStatistics::denormalize(Eigen::MatrixXd& features) const {
  if (features.rows() != kFeatureCount) throw std::invalid_argument("denormalize: features must have 66 rows");
  features = (features.array().colwise() * std.array()).matrix().colwise() + mean;
}

Eigen::MatrixXf FeatureStatistics::normalized(const Eigen::MatrixXd& features) const {
  if (features.rows() != kFeatureCount) throw std::invalid_argument("normalized: features must have 66 rows");
  return ((features.colwise() - mean).array().colwise() / std.array()).matrix().cast<float>();
}

Eigen::MatrixXd FeatureStatistics::denormalized(const Eigen::MatrixXf& normalized_features) const {
  if (normalized_features.rows() != kFeatureCount) throw std::invalid_argument("denormalized: features must have 66 rows");
  return (normalized_features.cast<double>().array().colwise() * std.array()).matrix().colwise() + mean;
}

FeatureStatistics computeFeatureStatistics(const std::vector<Eigen::MatrixXd>& clips) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(kFeatureCount);
  Eigen::VectorXd sum_squares = Eigen::VectorXd::Zero(kFeatureCount);
  double frames = 0.0;
  for (const Eigen::MatrixXd& clip : clips) {
    if (clip.rows() != kFeatureCount) throw std::invalid_argument("computeFeatureStatistics: clips must have 66 rows");
    sum += clip.rowwise().sum();
    sum_squares += clip.array().square().matrix().rowwise().sum();
    frames += static_cast<double>(clip.cols());
  }
  if (frames == 0.0) throw std::invalid_argument("computeFeatureStatistics: no frames");
  FeatureStatistics statistics;
  statistics.mean = sum / frames;
  const Eigen::VectorXd variance = (sum_squares / frames - statistics.mean.cwiseAbs2()).cwiseMax(0.0);
  statistics.std.resize(kFeatureCount);
  const double shared_position_std = std::sqrt(variance.head(kPositionChannels).mean());
  statistics.std.head(kPositionChannels).setConstant(shared_position_std);
  for (int v = kPositionChannels; v < kFeatureCount; ++v) {
    // Velocities: mean 0, so their spread is measured about 0.
    statistics.mean[v] = 0.0;
    statistics.std[v] = std::sqrt(sum_squares[v] / frames);
  }
  statistics.std = statistics.std.cwiseMax(kMinimumStd);
  return statistics;
}

void saveFeatureStatistics(const FeatureStatistics& statistics, const std::filesystem::path& file) {
  statistics.validate();
  nlohmann::json json;
  json["format"] = "motionstyle-feature-statistics";
  json["version"] = 1;
  json["mean"] = std::vector<double>(statistics.mean.data(), statistics.mean.data() + kFeatureCount);
  json["std"] = std::vector<double>(statistics.std.data(), statistics.std.data() + kFeatureCount);
  writeFileAtomically(file, json.dump(2) + "\n");
}

FeatureStatistics loadFeatureStatistics(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), 0, "cannot open the feature statistics file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& error) {
    const auto byte = std::min(error.byte, text.size());
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(byte), '\n'));
    throw InputError(file.string(), line, "invalid JSON: " + std::string(error.what()));
  }
  try {
    if (json.value("format", "") != "motionstyle-feature-statistics")
      throw InputError(file.string(), 0, "expected \"format\": \"motionstyle-feature-statistics\"");
    if (json.value("version", 0) != 1)
      throw InputError(file.string(), 0, "unsupported version (this build reads version 1)");
    const auto mean = json.at("mean").get<std::vector<double>>();
    const auto std_values = json.at("std").get<std::vector<double>>();
    if (mean.size() != kFeatureCount || std_values.size() != kFeatureCount)
      throw InputError(file.string(), 0, "expected 66 values in \"mean\" and \"std\"");
    FeatureStatistics statistics;
    statistics.mean = Eigen::Map<const Eigen::VectorXd>(mean.data(), kFeatureCount);
    statistics.std = Eigen::Map<const Eigen::VectorXd>(std_values.data(), kFeatureCount);
    statistics.validate();
    return statistics;
  } catch (const nlohmann::json::exception& error) {
    throw InputError(file.string(), 0, std::string("unexpected content: ") + error.what());
  } catch (const std::invalid_argument& error) {
    throw InputError(file.string(), 0, error.what());
  }
}

}  // namespace motionstyle
