// The stance hold in the clip's own rig (representation.h holdStancesInOwnRig, proportions.h
// enforceBoneLengths with a planted toe height): invalid input first, then the properties a clean-up
// relies on, measured where the output lands (the clip's own rig and proportions): a planted toe the
// style slid stays within kKeptFootRadiusCm of its stance's place, and a toe the style tipped into the
// floor, planted or swinging, stands no lower than the content's planted toes. Each fails without the
// hold.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "bvh/bvh_reader.h"
#include "features/proportions.h"
#include "features/representation.h"
#include "features/root_path.h"
#include "features/signal_filters.h"
#include "mapping/joint_mapping.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

constexpr int kToeLabel = static_cast<int>(ContactLabel::LeftToe);
const int kAnkle = index(CanonicalJoint::LeftAnkle), kToe = index(CanonicalJoint::LeftToe);

// The zombie (a rig whose proportions and toe bones differ from the reference's) with only its left
// toe's contacts, and the first of them that lasts at least 12 frames: [first, end).
struct ToeStance {
  MotionFeatures content;
  Eigen::Index first = 0, end = 0;
};

ToeStance zombieToeStance() {
  const Motion motion = readBvh(test::fixture("zombie.bvh"));
  ToeStance s{extractFeatures(motion, mapJoints(motion.skeleton, "zombie.bvh"))};
  for (int label = 0; label < kContactCount; ++label)
    if (label != kToeLabel) s.content.contacts.row(label).setZero();
  const Eigen::MatrixXd& c = s.content.contacts;
  for (Eigen::Index f = 0; f < c.cols();) {
    Eigen::Index e = f;
    while (e < c.cols() && c(kToeLabel, e) > 0.5) ++e;
    if (e - f >= 12) {
      s.first = f;
      s.end = e;
      return s;
    }
    f = e + 1;
  }
  ADD_FAILURE() << "the zombie has no toe stance of 12 frames";
  return s;
}

// The left toe's place on the floor and height, frames x 3 (x, z, y), in the clip's own rig.
Eigen::MatrixXd ownToe(const Eigen::MatrixXd& features, const FeatureAnchor& anchor) {
  const Eigen::MatrixXd world = referenceWorldPositions(features, anchor);
  Eigen::MatrixXd toe(world.rows(), 3);
  toe << world.col(3 * kToe), world.col(3 * kToe + 2), world.col(3 * kToe + 1);
  return toe;
}

// How far the toe strays on the floor from its median place over [first, end).
double toeSpread(const Eigen::MatrixXd& toe, Eigen::Index first, Eigen::Index end) {
  std::vector<double> xs, zs;
  for (Eigen::Index f = first; f < end; ++f) {
    xs.push_back(toe(f, 0));
    zs.push_back(toe(f, 1));
  }
  const Eigen::Vector2d place(median(xs), median(zs));
  double spread = 0.0;
  for (Eigen::Index f = first; f < end; ++f) spread = std::max(spread, (toe.row(f).head<2>().transpose() - place).norm());
  return spread;
}

// The content's planted left toes' median height in its own rig: the floor a held toe stands on.
double plantedToeHeight(const ToeStance& s) {
  std::vector<double> planted;
  const Eigen::MatrixXd content_toe = ownToe(s.content.values, s.content.anchor);
  for (Eigen::Index f = 0; f < content_toe.rows(); ++f)
    if (s.content.contacts(kToeLabel, f) > 0.5) planted.push_back(content_toe(f, 2));
  return median(planted);
}

// The left foot turned `degrees` further down about its ankle on `frames` (reference rig).
void tipLeftFoot(Eigen::MatrixXd& features, const std::vector<Eigen::Index>& frames, double degrees) {
  for (Eigen::Index f : frames) {
    const Eigen::Vector3d ankle = features.col(f).segment<3>(3 * kAnkle);
    const Eigen::Vector3d foot = features.col(f).segment<3>(3 * kToe) - ankle;
    const Eigen::Vector3d across = foot.cross(Eigen::Vector3d::UnitY()).normalized();
    features.col(f).segment<3>(3 * kToe) = ankle + Eigen::AngleAxisd(-degrees * M_PI / 180.0, across) * foot;
  }
}

TEST(StanceHoldInvalid, RejectsFeaturesOrContactsThatAreNotTheContentsAndHoldsNothingWithoutContacts) {
  const ToeStance s = zombieToeStance();
  Eigen::MatrixXd short_clip = s.content.values.leftCols(10);
  EXPECT_THROW(holdStancesInOwnRig(short_clip, s.content), std::invalid_argument);
  Eigen::MatrixXd rows(65, s.content.values.cols());
  EXPECT_THROW(holdStancesInOwnRig(rows, s.content), std::invalid_argument);
  MotionFeatures short_contacts = s.content;
  short_contacts.contacts = s.content.contacts.leftCols(10);
  Eigen::MatrixXd held = s.content.values;
  EXPECT_THROW(holdStancesInOwnRig(held, short_contacts), std::invalid_argument);
  MotionFeatures no_contacts = s.content;
  no_contacts.contacts.resize(0, 0);
  holdStancesInOwnRig(held, no_contacts);
  EXPECT_EQ(held, s.content.values);
}

// Held on the content itself, its toe stance spreads no further than the kept radius or its own spread.
TEST(StanceHold, TheContentsOwnStanceSpreadsNoFurther) {
  const ToeStance s = zombieToeStance();
  Eigen::MatrixXd held = s.content.values;
  holdStancesInOwnRig(held, s.content);
  const Eigen::MatrixXd before = ownToe(s.content.values, s.content.anchor), after = ownToe(held, s.content.anchor);
  EXPECT_LE(toeSpread(after, s.first, s.end), std::max(kKeptFootRadiusCm, toeSpread(before, s.first, s.end)) + 1e-6);
}

// The toe slid 15 cm along the world in the reference rig (within kLockableSpreadCm: still a stance).
TEST(StanceHold, APlantedToeTheStyleSlidIsHeldInTheClipsOwnRig) {
  const ToeStance s = zombieToeStance();
  Eigen::MatrixXd slid = s.content.values;
  const std::vector<RootFrame> roots = rootFrames(slid);
  const double span = static_cast<double>(s.end - s.first - 1);
  for (Eigen::Index f = s.first; f < s.end; ++f) {
    const RootFrame& root = roots[static_cast<std::size_t>(f)];
    const Eigen::Vector2d at = root.toWorld(slid(3 * kToe, f), slid(3 * kToe + 2, f)) +
                               Eigen::Vector2d(15.0 * static_cast<double>(f - s.first) / span, 0.0);
    const Eigen::Vector2d shift = root.toRootFrame(at) - Eigen::Vector2d(slid(3 * kToe, f), slid(3 * kToe + 2, f));
    for (const int j : {kAnkle, kToe}) {
      slid(3 * j, f) += shift.x();
      slid(3 * j + 2, f) += shift.y();
    }
  }
  ASSERT_GT(toeSpread(ownToe(slid, s.content.anchor), s.first, s.end), kKeptFootRadiusCm + 3.0);
  Eigen::MatrixXd held = slid;
  holdStancesInOwnRig(held, s.content);
  EXPECT_LE(toeSpread(ownToe(held, s.content.anchor), s.first, s.end), kKeptFootRadiusCm + 0.05);
}

// The foot tipped 40 degrees further down about its ankle in the reference rig: in the zombie's own rig
// its toe goes through the floor; held, it stands no lower than the content's planted toes.
TEST(StanceHold, APlantedToeTheStyleTippedIntoTheFloorStandsOnIt) {
  const ToeStance s = zombieToeStance();
  const double floor = plantedToeHeight(s);
  std::vector<Eigen::Index> stance;
  for (Eigen::Index f = s.first; f < s.end; ++f) stance.push_back(f);
  Eigen::MatrixXd tipped = s.content.values;
  tipLeftFoot(tipped, stance, 40.0);
  const Eigen::MatrixXd sunk = ownToe(tipped, s.content.anchor);
  ASSERT_LT(sunk.col(2).segment(s.first, s.end - s.first).minCoeff(), floor - 3.0);
  Eigen::MatrixXd held = tipped;
  holdStancesInOwnRig(held, s.content);
  const Eigen::MatrixXd toe = ownToe(held, s.content.anchor);
  for (Eigen::Index f = s.first; f < s.end; ++f) EXPECT_GE(toe(f, 2), floor - 0.05) << f;
}

// The same tip where the toe swings, away from any of its stances and their ramps: the foot turns up
// about its ankle until the toe stands no lower than the planted ones (the zombie with angry swung its
// toe 8 cm under the floor there). The ankle stays where it was.
TEST(StanceHold, AToeTheStyleSwingsUnderTheFloorIsTurnedUpOverIt) {
  const ToeStance s = zombieToeStance();
  const double floor = plantedToeHeight(s);
  const Eigen::MatrixXd& c = s.content.contacts;
  std::vector<Eigen::Index> swing;  // frames with no toe contact within the ramp and one frame more
  const Eigen::Index reach = kKeptFootRampFrames + 1;
  for (Eigen::Index f = reach; f + reach < c.cols(); ++f)
    if (c.row(kToeLabel).segment(f - reach, 2 * reach + 1).sum() == 0) swing.push_back(f);
  ASSERT_GE(swing.size(), 10u);
  Eigen::MatrixXd tipped = s.content.values;
  tipLeftFoot(tipped, swing, 80.0);
  const Eigen::MatrixXd sunk = ownToe(tipped, s.content.anchor);
  double lowest = 1e9;
  for (Eigen::Index f : swing) lowest = std::min(lowest, sunk(f, 2));
  ASSERT_LT(lowest, floor - 3.0);
  Eigen::MatrixXd held = tipped;
  holdStancesInOwnRig(held, s.content);
  const Eigen::MatrixXd toe = ownToe(held, s.content.anchor);
  for (Eigen::Index f : swing) {
    EXPECT_GE(toe(f, 2), floor - 0.05) << f;
    EXPECT_NEAR((held.col(f).segment<3>(3 * kToe) - held.col(f).segment<3>(3 * kAnkle)).norm(),
                (tipped.col(f).segment<3>(3 * kToe) - tipped.col(f).segment<3>(3 * kAnkle)).norm(), 1.0) << f;
  }
}

}  // namespace
}  // namespace motionstyle
