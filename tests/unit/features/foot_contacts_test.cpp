#include <gtest/gtest.h>

#include "bvh/bvh_reader.h"
#include "features/foot_contacts.h"
#include "features/representation.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

TEST(FootContacts, RejectsBadInput) {
  EXPECT_THROW(detectFootContacts(Eigen::MatrixXd::Zero(10, 60), 60.0), std::invalid_argument);
  EXPECT_THROW(detectFootContacts(Eigen::MatrixXd::Zero(10, 63), 0.0), std::invalid_argument);
}

TEST(FootContacts, RemoveShortRunsMergesFlickerButKeepsEnds) {
  Eigen::RowVectorXd labels(12);
  labels << 1, 0, 1, 1, 1, 1, 0, 0, 0, 0, 1, 0;
  removeShortRuns(labels, 3);
  Eigen::RowVectorXd expected(12);
  // The interior single 1 at frame 10 is flicker and goes; the ends (frames 0 and 11) stay; the single
  // 0 at frame 1 is interior and is filled.
  expected << 1, 1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0;
  EXPECT_EQ(labels, expected);
}

TEST(FootContacts, PlantedLowFootIsInContactAndMovingOrHighFootIsNot) {
  const int frames = 60;
  Eigen::MatrixXd positions = Eigen::MatrixXd::Zero(frames, 63);
  const int heel = 3 * index(CanonicalJoint::LeftAnkle);
  const int toe = 3 * index(CanonicalJoint::RightToe);
  for (int t = 0; t < frames; ++t) {
    positions(t, heel + 1) = 8.0;                       // low and still for the first half...
    if (t >= 30) positions(t, heel + 2) = 3.0 * (t - 30);  // ...then sliding at 180 cm/s
    positions(t, toe + 1) = 40.0;                       // high the whole time
  }
  const Eigen::MatrixXd contacts = detectFootContacts(positions, 60.0);
  EXPECT_EQ(contacts.row(static_cast<int>(ContactLabel::LeftHeel)).head(29).sum(), 29.0);
  EXPECT_EQ(contacts.row(static_cast<int>(ContactLabel::LeftHeel)).tail(28).sum(), 0.0);
  EXPECT_EQ(contacts.row(static_cast<int>(ContactLabel::RightToe)).sum(), 0.0);
}

// Swing phases of one heel: runs of "not in contact" lasting at least min_frames (a real step, not a
// shuffle), as (first frame, last frame).
std::vector<std::pair<int, int>> swings(const Eigen::RowVectorXd& labels, int min_frames) {
  std::vector<std::pair<int, int>> result;
  for (Eigen::Index t = 0; t < labels.size();) {
    Eigen::Index end = t;
    while (end < labels.size() && labels[end] < 0.5) ++end;
    if (end - t >= min_frames && t > 0 && end < labels.size()) result.push_back({static_cast<int>(t), static_cast<int>(end - 1)});
    t = end + 1;
  }
  return result;
}

TEST(FootContacts, RealWalkAlternatesFeetAtTheWalksCadence) {
  // The zombie clip: a slow walk after a standing start.
  const Motion motion = readBvh(test::fixture("zombie.bvh"));
  const MotionFeatures features = extractFeatures(motion, mapJoints(motion.skeleton));
  const int min_swing = 9;  // 0.15 s at 60 fps
  const auto left = swings(features.contacts.row(static_cast<int>(ContactLabel::LeftHeel)), min_swing);
  const auto right = swings(features.contacts.row(static_cast<int>(ContactLabel::RightHeel)), min_swing);
  ASSERT_GE(left.size(), 2u);
  ASSERT_GE(right.size(), 2u);
  // In time order the steps alternate left, right, left... and never overlap (one foot always down).
  std::vector<std::tuple<int, int, char>> steps;
  for (const auto& [first, last] : left) steps.push_back({first, last, 'L'});
  for (const auto& [first, last] : right) steps.push_back({first, last, 'R'});
  std::sort(steps.begin(), steps.end());
  for (size_t i = 1; i < steps.size(); ++i) {
    EXPECT_NE(std::get<2>(steps[i]), std::get<2>(steps[i - 1])) << "step " << i << " at frame " << std::get<0>(steps[i]);
    EXPECT_GT(std::get<0>(steps[i]), std::get<1>(steps[i - 1])) << "both feet in the air at frame " << std::get<0>(steps[i]);
  }
  // Same foot to same foot: a walking stride of 0.8 to 2 s (this zombie is slow).
  for (const auto* side : {&left, &right})
    for (size_t i = 1; i < side->size(); ++i) {
      const double stride_s = ((*side)[i].first - (*side)[i - 1].first) / 60.0;
      EXPECT_GT(stride_s, 0.8);
      EXPECT_LT(stride_s, 2.0);
    }
}

}  // namespace
}  // namespace motionstyle
