#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <stdexcept>

#include "common/errors.h"
#include "features/feature_layout.h"
#include "features/feature_statistics.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

std::filesystem::path tempFile(const test::TempDir& dir, const std::string& name, const std::string& content) {
  const auto path = dir.path() / name;
  std::ofstream(path) << content;
  return path;
}

TEST(FeatureStatistics, RejectsEmptyAndMisshapenInput) {
  EXPECT_THROW(computeFeatureStatistics({}), std::invalid_argument);
  EXPECT_THROW(computeFeatureStatistics({Eigen::MatrixXd::Zero(65, 4)}), std::invalid_argument);
  FeatureStatistics bad;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
}

TEST(FeatureStatistics, RejectsBadFiles) {
  const test::TempDir dir("statistics");
  EXPECT_THROW(loadFeatureStatistics("/nonexistent/stats.json"), InputError);
  try {
    loadFeatureStatistics(tempFile(dir, "stats_bad.json", "{\n  \"format\": \"motionstyle-feature-statistics\",\n  oops\n}"));
    FAIL() << "invalid JSON accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.line(), 3);
  }
  EXPECT_THROW(loadFeatureStatistics(tempFile(dir, "stats_fmt.json", R"({"format": "other", "version": 1})")), InputError);
  EXPECT_THROW(loadFeatureStatistics(tempFile(dir, "stats_len.json",
                                              R"({"format": "motionstyle-feature-statistics", "version": 1,
                                                  "mean": [1, 2], "std": [1, 2]})")),
               InputError);
}

TEST(FeatureStatistics, PositionsShareOneStdAndVelocitiesAreCentredOnZero) {
  std::mt19937 random(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd clip(kFeatureCount, 500);
  for (Eigen::Index r = 0; r < clip.rows(); ++r)
    for (Eigen::Index c = 0; c < clip.cols(); ++c) clip(r, c) = 5.0 + static_cast<double>(r % 7) * normal(random);
  const FeatureStatistics statistics = computeFeatureStatistics({clip, clip.leftCols(100)});
  const Eigen::VectorXd position_std = statistics.std.head(63);
  EXPECT_DOUBLE_EQ(position_std.minCoeff(), position_std.maxCoeff());
  EXPECT_EQ(statistics.mean.tail(3), Eigen::Vector3d::Zero());
  EXPECT_NEAR(statistics.mean[0], clip.row(0).mean(), 1e-9);
  EXPECT_GT(statistics.std.minCoeff(), 0.0);

  Eigen::MatrixXd normalized = clip;
  statistics.normalize(normalized);
  statistics.denormalize(normalized);
  EXPECT_LT((normalized - clip).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(FeatureStatistics, SaveLoadRoundTrip) {
  FeatureStatistics statistics;
  statistics.mean = Eigen::VectorXd::LinSpaced(kFeatureCount, -3.0, 3.0);
  statistics.std = Eigen::VectorXd::LinSpaced(kFeatureCount, 0.5, 9.0);
  const test::TempDir dir("statistics");
  const auto path = dir.path() / "stats.json";
  saveFeatureStatistics(statistics, path);
  const FeatureStatistics loaded = loadFeatureStatistics(path);
  EXPECT_EQ(loaded.mean, statistics.mean);
  EXPECT_EQ(loaded.std, statistics.std);
}

TEST(FeatureStatistics, NormalizedCopiesAreTheInPlaceValuesInFloat) {
  FeatureStatistics statistics;
  statistics.mean = Eigen::VectorXd::LinSpaced(kFeatureCount, -3.0, 3.0);
  statistics.std = Eigen::VectorXd::LinSpaced(kFeatureCount, 0.5, 9.0);
  const Eigen::MatrixXd x = Eigen::MatrixXd::Random(kFeatureCount, 7) * 50.0;
  Eigen::MatrixXd in_place = x;
  statistics.normalize(in_place);
  const Eigen::MatrixXf normalized = statistics.normalized(x);
  EXPECT_EQ(normalized, in_place.cast<float>());
  EXPECT_LT((statistics.denormalized(normalized) - x).cwiseAbs().maxCoeff(), 1e-4);  // float rounding
  EXPECT_THROW(statistics.normalized(Eigen::MatrixXd::Zero(65, 2)), std::invalid_argument);
  EXPECT_THROW(statistics.denormalized(Eigen::MatrixXf::Zero(65, 2)), std::invalid_argument);
}

}  // namespace
}  // namespace motionstyle
