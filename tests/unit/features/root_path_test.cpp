// The root path read from features' root velocities (features/root_path.h): invalid input first, then
// the integration's properties: a straight walk, a quarter turn, the inverse of a root frame, and the
// summary at the path's end.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "features/feature_layout.h"
#include "features/root_path.h"

namespace motionstyle {
namespace {

TEST(RootPathInvalid, FeaturesOfAnotherShapeAreRejected) {
  EXPECT_THROW(rootFrames(Eigen::MatrixXd::Zero(65, 3)), std::invalid_argument);
  EXPECT_THROW(summariseRootPath(Eigen::MatrixXd::Zero(67, 3)), std::invalid_argument);
}

// 10 frames forward at 2 cm a frame, then 10 turning a quarter turn while going on: the root's places
// and headings one frame after the other, frames + 1 of them, from the given start.
TEST(RootPath, RootFramesIntegrateTheRootVelocities) {
  Eigen::MatrixXd features = Eigen::MatrixXd::Zero(kFeatureCount, 20);
  features.row(kForwardVelocity).setConstant(2.0);
  features.row(kTurningVelocity).tail(10).setConstant(0.5 * std::numbers::pi / 10.0);
  const Eigen::Vector2d start(5.0, -3.0);
  const std::vector<RootFrame> roots = rootFrames(features, start, 0.0);
  ASSERT_EQ(roots.size(), 21u);
  EXPECT_LT((roots[0].place - start).norm(), 1e-12);
  EXPECT_LT((roots[10].place - (start + Eigen::Vector2d(0.0, 20.0))).norm(), 1e-12);  // straight along +Z
  EXPECT_NEAR(roots[20].heading, 0.5 * std::numbers::pi, 1e-12);
  for (std::size_t t = 0; t + 1 < roots.size(); ++t)  // every step 2 cm long, along the frame's heading
    EXPECT_LT((roots[t + 1].place - roots[t].toWorld(0.0, 2.0)).norm(), 1e-12) << t;
  // A positive turn takes +Z toward +X: after the quarter turn the root's forward is the world's +X.
  const Eigen::Vector2d forward = roots[20].toWorld(0.0, 1.0) - roots[20].place;
  EXPECT_LT((forward - Eigen::Vector2d(1.0, 0.0)).norm(), 1e-12);
  // toRootFrame undoes toWorld at any heading.
  for (const RootFrame& root : roots) {
    const Eigen::Vector2d back = root.toRootFrame(root.toWorld(3.0, -7.0));
    EXPECT_LT((back - Eigen::Vector2d(3.0, -7.0)).norm(), 1e-9);
  }
  // The summary is the path's end (from the origin) and its length.
  const RootPathSummary summary = summariseRootPath(features);
  const std::vector<RootFrame> from_origin = rootFrames(features);
  EXPECT_LT((summary.displacement - from_origin.back().place).norm(), 1e-12);
  EXPECT_NEAR(summary.heading_change, from_origin.back().heading, 1e-12);
  EXPECT_NEAR(summary.distance_cm, 40.0, 1e-9);
}

}  // namespace
}  // namespace motionstyle
