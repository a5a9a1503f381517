#pragma once
// Per-feature normalisation statistics (mean and std of each of the 66 values), computed over a set of
// clips, saved and loaded. The networks see (x - mean) / std.
//
// As in Holden et al. 2016: joint-position channels keep their own means but share ONE std (so that the
// body's proportions survive normalisation); the three root velocities have mean 0 and their own std.

#include <Eigen/Core>
#include <filesystem>
#include <vector>

namespace motionstyle {

struct FeatureStatistics {
  Eigen::VectorXd mean;  // kFeatureCount
  Eigen::VectorXd std;   // kFeatureCount, every entry > 0

  // Throws std::invalid_argument unless both have 66 finite entries and every std is > 0.
  void validate() const;
  // features: kFeatureCount x frames (in place): x_n = (x - mean) / std and back, x = x_n * std + mean.
  void normalize(Eigen::MatrixXd& features) const;
  void denormalize(Eigen::MatrixXd& features) const;
  // The same as copies in the networks' float precision (computed in double, rounded once), so that
  // every caller feeds a network the very same numbers. std::invalid_argument unless 66 rows.
  Eigen::MatrixXf normalized(const Eigen::MatrixXd& features) const;
  Eigen::MatrixXd denormalized(const Eigen::MatrixXf& normalized_features) const;
};

// clips: each kFeatureCount x frames. Throws std::invalid_argument when there are no frames at all.
FeatureStatistics computeFeatureStatistics(const std::vector<Eigen::MatrixXd>& clips);

// JSON: {"format": "motionstyle-feature-statistics", "version": 1, "mean": [66], "std": [66]}.
void saveFeatureStatistics(const FeatureStatistics& statistics, const std::filesystem::path& file);  // atomic
FeatureStatistics loadFeatureStatistics(const std::filesystem::path& file);  // InputError on bad files

}  // namespace motionstyle
