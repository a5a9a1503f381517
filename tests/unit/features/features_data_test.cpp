// Representation checks over the licensed Bandai Namco dataset (label "data"; skipped when absent).
#include <gtest/gtest.h>

#include <algorithm>

#include "bvh/bvh_reader.h"
#include "features/feature_statistics.h"
#include "features/representation.h"
#include "motion/resample.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

std::vector<std::filesystem::path> sampleClips(const std::filesystem::path& bandai, const std::string& pattern,
                                               size_t count) {
  std::vector<std::filesystem::path> all;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(bandai))
    if (entry.path().extension() == ".bvh" && entry.path().filename().string().find(pattern) != std::string::npos)
      all.push_back(entry.path());
  std::sort(all.begin(), all.end());
  std::vector<std::filesystem::path> sample;
  const size_t step = std::max<size_t>(1, all.size() / count);
  for (size_t i = 0; i < all.size() && sample.size() < count; i += step) sample.push_back(all[i]);
  return sample;
}

TEST(RepresentationData, RoundTripWithinOnePercentOfBodyHeightOnBandaiClips) {
  MOTIONSTYLE_REQUIRE_BANDAI(bandai);
  const auto clips = sampleClips(bandai, "", 24);
  ASSERT_FALSE(clips.empty());
  for (const auto& path : clips) {
    const Motion motion = readBvh(path);
    const JointMapping mapping = mapJoints(motion.skeleton, path.string());
    const MotionFeatures features = extractFeatures(motion, mapping);
    EXPECT_EQ(features.anchor.convention.up_axis, "+Y") << path;
    EXPECT_EQ(features.anchor.convention.unit, "cm") << path;
    const Eigen::MatrixXd expected = canonicalJointPositions(resampleMotion(motion, 60.0), mapping);
    const Eigen::MatrixXd recovered = canonicalWorldPositions(features.values, features.anchor);
    const double tolerance = 0.01 * skeletalHeight(motion.skeleton, mapping);
    double worst = 0.0;
    for (Eigen::Index f = 0; f < expected.rows(); ++f)
      for (int c = 0; c < kCanonicalJointCount; ++c)
        worst = std::max(worst, (expected.row(f).segment<3>(3 * c) - recovered.row(f).segment<3>(3 * c)).norm());
    EXPECT_LT(worst, tolerance) << path;
  }
}

TEST(RepresentationData, BandaiActorsAreNearTheReferenceScale) {
  MOTIONSTYLE_REQUIRE_BANDAI(bandai);
  for (const auto& path : sampleClips(bandai, "_normal_", 6)) {
    const Motion motion = readBvh(path);
    const JointMapping mapping = mapJoints(motion.skeleton, path.string());
    EXPECT_NEAR(skeletalHeight(motion.skeleton, mapping), kReferenceSkeletalHeightCm, 0.1 * kReferenceSkeletalHeightCm)
        << path;
  }
}

TEST(RepresentationData, WalkContactsAlternateBetweenFeet) {
  MOTIONSTYLE_REQUIRE_BANDAI(bandai);
  for (const auto& path : sampleClips(bandai, "dataset-2_walk_normal", 4)) {
    const Motion motion = readBvh(path);
    const MotionFeatures features = extractFeatures(motion, mapJoints(motion.skeleton, path.string()));
    std::vector<std::pair<int, char>> strikes;
    for (const auto& [label, side] : {std::pair{ContactLabel::LeftHeel, 'L'}, std::pair{ContactLabel::RightHeel, 'R'}}) {
      const Eigen::RowVectorXd row = features.contacts.row(static_cast<int>(label));
      for (Eigen::Index t = 1; t < row.size(); ++t)
        if (row[t] > 0.5 && row[t - 1] < 0.5) strikes.push_back({static_cast<int>(t), side});
    }
    std::sort(strikes.begin(), strikes.end());
    ASSERT_GE(strikes.size(), 3u) << path;
    for (size_t i = 1; i < strikes.size(); ++i) EXPECT_NE(strikes[i].second, strikes[i - 1].second) << path << " strike " << i;
  }
}

TEST(RepresentationData, StatisticsOverClipsAreFiniteAndPositive) {
  MOTIONSTYLE_REQUIRE_BANDAI(bandai);
  std::vector<Eigen::MatrixXd> clips;
  for (const auto& path : sampleClips(bandai, "dataset-2_", 10)) {
    const Motion motion = readBvh(path);
    clips.push_back(extractFeatures(motion, mapJoints(motion.skeleton, path.string())).values);
  }
  const FeatureStatistics statistics = computeFeatureStatistics(clips);
  EXPECT_NO_THROW(statistics.validate());
  EXPECT_GT(statistics.std[kForwardVelocity], 0.1);
}

}  // namespace
}  // namespace motionstyle
