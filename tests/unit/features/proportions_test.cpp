// Proportions and retargeting (features/proportions.h): invalid input first, then the properties the
// representation relies on: bone lengths become the target's, directions are kept, feet stay on the
// floor, the round trip is the identity, degenerate bones are handled, and real rigs meet the networks
// in the reference proportions.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "bvh/bvh_reader.h"
#include "features/proportions.h"
#include "features/representation.h"
#include "features/signal_filters.h"
#include "mapping/joint_mapping.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

// Root-frame features of one real clip, in its own proportions.
Eigen::MatrixXd ownFeatures(const std::string& fixture) {
  const Motion motion = readBvh(test::fixture(fixture));
  FeatureOptions options;
  options.retarget_proportions = false;
  return extractFeatures(motion, mapJoints(motion.skeleton, fixture), options).values;
}

Proportions withoutHands(Proportions proportions) {
  proportions.bone_length[static_cast<std::size_t>(index(CanonicalJoint::LeftHandEnd))] = 0.0;
  proportions.bone_length[static_cast<std::size_t>(index(CanonicalJoint::RightHandEnd))] = 0.0;
  return proportions;
}

TEST(ProportionsInvalid, RejectsBadLengthsAndShapes) {
  Proportions legless = referenceProportions();
  for (CanonicalJoint j : {CanonicalJoint::LeftKnee, CanonicalJoint::LeftAnkle, CanonicalJoint::RightKnee, CanonicalJoint::RightAnkle})
    legless.bone_length[static_cast<std::size_t>(index(j))] = 0.0;
  EXPECT_THROW(legless.validate(), std::invalid_argument);
  Proportions negative = referenceProportions();
  negative.bone_length[3] = -1.0;
  EXPECT_THROW(negative.validate(), std::invalid_argument);
  Proportions nan = referenceProportions();
  nan.bone_length[14] = std::nan("");
  EXPECT_THROW(nan.validate(), std::invalid_argument);
  Eigen::MatrixXd wrong = Eigen::MatrixXd::Zero(65, 3);
  EXPECT_THROW(retargetFeatures(wrong, referenceProportions(), referenceProportions()), std::invalid_argument);
  Eigen::MatrixXd features = Eigen::MatrixXd::Zero(kFeatureCount, 3);
  EXPECT_THROW(retargetFeatures(features, legless, referenceProportions()), std::invalid_argument);
  EXPECT_THROW(measureProportions(Eigen::MatrixXd::Zero(kFeatureCount, 0)), std::invalid_argument);
  EXPECT_THROW(enforceBoneLengths(wrong, referenceProportions()), std::invalid_argument);
  EXPECT_THROW(enforceBoneLengths(features, legless), std::invalid_argument);
  EXPECT_THROW(enforceBoneLengths(features, referenceProportions(), Eigen::MatrixXd::Zero(kContactCount, 2)),
               std::invalid_argument);
  EXPECT_THROW(enforceBoneLengths(features, referenceProportions(), Eigen::MatrixXd::Zero(3, 3)), std::invalid_argument);
}

TEST(Proportions, TheReferenceIsTheBandaiActorsAndValid) {
  const Proportions& reference = referenceProportions();
  EXPECT_NO_THROW(reference.validate());
  EXPECT_NEAR(reference.legLength(), 38.89 + 40.78, 1e-9);
  for (int c = 1; c < kCanonicalJointCount; ++c)  // every bone has a length, hands included
    EXPECT_GT(reference.bone_length[static_cast<std::size_t>(c)], 1.0) << c;
}

TEST(Proportions, RetargetingGivesTheTargetBonesKeepsDirectionsAndFeetOnTheFloor) {
  for (const std::string fixture : {"cmu_131_01.bvh", "zombie.bvh"}) {
    const Eigen::MatrixXd own = ownFeatures(fixture);
    const Proportions from = measureProportions(own);
    Eigen::MatrixXd retargeted = own;
    retargetFeatures(retargeted, from, referenceProportions());
    const Proportions result = measureProportions(retargeted);
    for (int c = 1; c < kCanonicalJointCount; ++c) {
      const auto i = static_cast<std::size_t>(c);
      EXPECT_NEAR(result.bone_length[i], referenceProportions().bone_length[i], 1e-9) << fixture << " bone " << c;
      const int parent = kCanonicalParent[i];
      for (Eigen::Index f = 0; f < own.cols(); f += 50) {  // each bone keeps its direction
        const Eigen::Vector3d a = own.col(f).segment<3>(3 * c) - own.col(f).segment<3>(3 * parent);
        const Eigen::Vector3d b = retargeted.col(f).segment<3>(3 * c) - retargeted.col(f).segment<3>(3 * parent);
        EXPECT_GT(a.normalized().dot(b.normalized()), 1.0 - 1e-12) << fixture << " bone " << c << " frame " << f;
      }
    }
    // Root motion scales with the legs; turning is unchanged.
    const double ratio = referenceProportions().legLength() / from.legLength();
    EXPECT_NEAR(retargeted.row(kForwardVelocity).sum(), ratio * own.row(kForwardVelocity).sum(), 1e-9);
    EXPECT_EQ(retargeted.row(kTurningVelocity), own.row(kTurningVelocity));
  }
}

// Network outputs get exact bone lengths: every frame's bones, not just their mean, keep their
// directions, the hips stay, the velocities are untouched, and doing it twice changes nothing.
TEST(Proportions, EnforcingBoneLengthsSetsEveryFrameAndKeepsDirections) {
  Eigen::MatrixXd noisy = ownFeatures("zombie.bvh");
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 1.5);
  for (Eigen::Index f = 0; f < noisy.cols(); ++f)
    for (int r = 3; r < 63; ++r) noisy(r, f) += noise(rng);  // every joint but the hips, by ~1.5 cm
  const Proportions& reference = referenceProportions();
  Eigen::MatrixXd fixed = noisy;
  enforceBoneLengths(fixed, reference);
  for (Eigen::Index f = 0; f < fixed.cols(); f += 7)
    for (int c = 1; c < kCanonicalJointCount; ++c) {
      const int parent = kCanonicalParent[static_cast<std::size_t>(c)];
      const Eigen::Vector3d before = noisy.col(f).segment<3>(3 * c) - noisy.col(f).segment<3>(3 * parent);
      const Eigen::Vector3d after = fixed.col(f).segment<3>(3 * c) - fixed.col(f).segment<3>(3 * parent);
      EXPECT_NEAR(after.norm(), reference.bone_length[static_cast<std::size_t>(c)], 1e-9) << "bone " << c << " frame " << f;
      EXPECT_GT(before.normalized().dot(after.normalized()), 1.0 - 1e-12);
    }
  EXPECT_EQ(fixed.topRows(3), noisy.topRows(3));
  EXPECT_EQ(fixed.bottomRows(3), noisy.bottomRows(3));
  Eigen::MatrixXd twice = fixed;
  enforceBoneLengths(twice, reference);
  EXPECT_LT((twice - fixed).cwiseAbs().maxCoeff(), 1e-9);
}

// A joint's place on the floor from before, pulled to within kKeptFootRadiusCm of `stance`.
Eigen::Vector2d pulledTo(const Eigen::Vector2d& stance, const Eigen::Vector2d& was) {
  const Eigen::Vector2d off = was - stance;
  return off.norm() <= kKeptFootRadiusCm ? was : Eigen::Vector2d(stance + off * (kKeptFootRadiusCm / off.norm()));
}

// The median place on the floor of joint j over frames [first, end) (a character that stays put: the
// root frame is the world's).
Eigen::Vector2d medianPlace(const Eigen::MatrixXd& features, int j, Eigen::Index first, Eigen::Index end) {
  Eigen::Vector2d place;
  for (const int axis : {0, 2}) {
    std::vector<double> along;
    for (Eigen::Index f = first; f < end; ++f) along.push_back(features(3 * j + axis, f));
    place[axis / 2] = median(std::move(along));
  }
  return place;
}

// With contacts, the bones are as exact, the legs' frames far from any contact are the plain
// enforcement's, and on a contact frame the planted joint keeps its horizontal place from before (the
// ankle where the heel is planted, the toe where only the toe is), pulled to within kKeptFootRadiusCm
// of its stance's median place, and its height's changes, at the plain enforcement's mean height where
// that is higher than before (else at its height from before:
// EnforcingBoneLengthsNeverSinksAPlantedFoot); in between, the place moves linearly with the weight.
TEST(Proportions, EnforcingBoneLengthsKeepsPlantedFeetWhereTheyWere) {
  Eigen::MatrixXd noisy = ownFeatures("zombie.bvh");
  const Eigen::Index frames = noisy.cols();
  ASSERT_GT(frames, 60);
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.5);
  for (Eigen::Index f = 0; f < frames; ++f)
    for (int r = 3; r < 63; ++r) noisy(r, f) += noise(rng);
  noisy.bottomRows<3>().setZero();  // in place: a joint's root-frame place is its place in the world
  Eigen::MatrixXd contacts = Eigen::MatrixXd::Zero(kContactCount, frames);
  const int left_heel = static_cast<int>(ContactLabel::LeftHeel), right_toe = static_cast<int>(ContactLabel::RightToe);
  contacts.block(left_heel, 20, 1, 10).setOnes();  // the left heel planted over frames 20-29
  contacts.block(right_toe, 40, 1, 6).setOnes();   // the right toe alone over frames 40-45
  const Proportions& reference = referenceProportions();
  Eigen::MatrixXd plain = noisy, kept = noisy;
  enforceBoneLengths(plain, reference);
  enforceBoneLengths(kept, reference, contacts);
  for (Eigen::Index f = 0; f < frames; ++f)
    for (int c = 1; c < kCanonicalJointCount; ++c) {
      const int parent = kCanonicalParent[static_cast<std::size_t>(c)];
      const double length = (kept.col(f).segment<3>(3 * c) - kept.col(f).segment<3>(3 * parent)).norm();
      ASSERT_NEAR(length, reference.bone_length[static_cast<std::size_t>(c)], 1e-9) << "bone " << c << " frame " << f;
    }
  const auto joint = [](const Eigen::MatrixXd& m, Eigen::Index f, CanonicalJoint j) {
    return Eigen::Vector3d(m.col(f).segment<3>(3 * index(j)));
  };
  // Far from both contacts (more than kKeptFootRampFrames away) everything is the plain enforcement's.
  for (Eigen::Index f : {Eigen::Index{0}, Eigen::Index{14}, Eigen::Index{35}, Eigen::Index{52}, frames - 1})
    EXPECT_LT((kept.col(f) - plain.col(f)).cwiseAbs().maxCoeff(), 1e-9) << f;
  // The heel's contact: the ankle back where it was across and along; up, at a still offset from where it
  // was, whose mean over the contact is the plain enforcement's height; out of reach, on the reach.
  const double reach = reference.bone_length[static_cast<std::size_t>(index(CanonicalJoint::LeftKnee))] +
                       reference.bone_length[static_cast<std::size_t>(index(CanonicalJoint::LeftAnkle))];
  double rise = 0.0;  // the mean over the contact of the plain enforcement's height less the one before
  for (Eigen::Index f = 20; f < 30; ++f)
    rise += (joint(plain, f, CanonicalJoint::LeftAnkle).y() - joint(noisy, f, CanonicalJoint::LeftAnkle).y()) / 10.0;
  const Eigen::Vector2d heel_stance = medianPlace(noisy, index(CanonicalJoint::LeftAnkle), 20, 30);
  const Eigen::Vector2d toe_stance = medianPlace(noisy, index(CanonicalJoint::RightToe), 40, 46);
  int within = 0, pulled = 0;
  for (Eigen::Index f = 20; f < 30; ++f) {
    const Eigen::Vector3d ankle = joint(kept, f, CanonicalJoint::LeftAnkle), was = joint(noisy, f, CanonicalJoint::LeftAnkle);
    EXPECT_LT((joint(kept, f, CanonicalJoint::RightKnee) - joint(plain, f, CanonicalJoint::RightKnee)).norm(), 1e-9);
    const double leg = (ankle - joint(kept, f, CanonicalJoint::LeftHip)).norm();
    if (leg > reach * (1.0 - 1e-5)) {
      EXPECT_NEAR(leg, reach * (1.0 - 1e-6), 1e-9) << f;
      continue;
    }
    const Eigen::Vector2d place = pulledTo(heel_stance, {was.x(), was.z()});
    EXPECT_NEAR(ankle.x(), place.x(), 1e-9) << f;
    EXPECT_NEAR(ankle.z(), place.y(), 1e-9) << f;
    EXPECT_NEAR(ankle.y() - was.y(), std::max(rise, 0.0), 1e-9) << f;
    ++within;
  }
  EXPECT_GE(within, 5);
  int toe_within = 0;
  for (Eigen::Index f = 40; f < 46; ++f) {
    const Eigen::Vector3d toe = joint(kept, f, CanonicalJoint::RightToe), was = joint(noisy, f, CanonicalJoint::RightToe);
    if ((joint(kept, f, CanonicalJoint::RightAnkle) - joint(kept, f, CanonicalJoint::RightHip)).norm() > reach * (1.0 - 1e-5))
      continue;  // pulled in to the leg's reach
    ++toe_within;
    const Eigen::Vector2d place = pulledTo(toe_stance, {was.x(), was.z()});
    pulled += (place - Eigen::Vector2d(was.x(), was.z())).norm() > 1e-6;
    EXPECT_NEAR(toe.x(), place.x(), 1e-9) << f;
    EXPECT_NEAR(toe.z(), place.y(), 1e-9) << f;
  }
  EXPECT_GE(toe_within, 2);
  EXPECT_GE(pulled, 1);  // the noise strays further than the radius somewhere
  // Proportions without toes (a rig that ends at the ankles): the toes collapse onto the ankles, nothing
  // goes NaN.
  Proportions toeless = reference;
  for (CanonicalJoint j : {CanonicalJoint::LeftToe, CanonicalJoint::RightToe})
    toeless.bone_length[static_cast<std::size_t>(index(j))] = 0.0;
  Eigen::MatrixXd collapsed = noisy;
  for (CanonicalJoint j : {CanonicalJoint::LeftToe, CanonicalJoint::RightToe})
    collapsed.middleRows<3>(3 * index(j)) = collapsed.middleRows<3>(3 * (index(j) - 1));
  enforceBoneLengths(collapsed, toeless, contacts);
  EXPECT_TRUE(collapsed.allFinite());
  EXPECT_LT((collapsed.middleRows<3>(3 * index(CanonicalJoint::RightToe)) -
             collapsed.middleRows<3>(3 * index(CanonicalJoint::RightAnkle))).cwiseAbs().maxCoeff(), 1e-9);
  // Two frames before the heel's contact the weight is 1 - 2 / 5: the ankle moved 3 / 5 of the way to
  // its place, pulled toward the stance it ramps to.
  const Eigen::Vector3d from = joint(plain, 18, CanonicalJoint::LeftAnkle), was = joint(noisy, 18, CanonicalJoint::LeftAnkle);
  const Eigen::Vector2d to = pulledTo(heel_stance, {was.x(), was.z()});
  const Eigen::Vector3d at = joint(kept, 18, CanonicalJoint::LeftAnkle);
  EXPECT_NEAR(at.x(), from.x() + 0.6 * (to.x() - from.x()), 1e-9);
  EXPECT_NEAR(at.z(), from.z() + 0.6 * (to.y() - from.z()), 1e-9);
}

// The kept place is the world's: a walking character (the zombie's root velocities) whose left heel
// slides 12 cm through a 20-frame contact has it held within kKeptFootRadiusCm of one place on the
// floor; slid 50 cm (more than kLockableSpreadCm from its median), it is a step the style moved and
// keeps its place from before.
TEST(Proportions, EnforcingBoneLengthsHoldsAStanceInTheWorld) {
  const Eigen::MatrixXd walk = ownFeatures("zombie.bvh");
  ASSERT_GT(walk.cols(), 60);
  // World places on the floor of root-frame point p per frame (root_path.h's convention).
  std::vector<Eigen::Vector2d> place;
  std::vector<double> heading;
  Eigen::Vector2d root = Eigen::Vector2d::Zero();
  double turned = 0.0;
  const auto turn = [](double h, double x, double z) {
    return Eigen::Vector2d(std::cos(h) * x + std::sin(h) * z, -std::sin(h) * x + std::cos(h) * z);
  };
  for (Eigen::Index f = 0; f < walk.cols(); ++f) {
    place.push_back(root);
    heading.push_back(turned);
    root += turn(turned, walk(kSidewaysVelocity, f), walk(kForwardVelocity, f));
    turned += walk(kTurningVelocity, f);
  }
  const int ankle = index(CanonicalJoint::LeftAnkle), toe = index(CanonicalJoint::LeftToe);
  const auto world = [&](const Eigen::MatrixXd& m, Eigen::Index f) {
    const auto i = static_cast<std::size_t>(f);
    return Eigen::Vector2d(place[i] + turn(heading[i], m(3 * ankle, f), m(3 * ankle + 2, f)));
  };
  Eigen::MatrixXd contacts = Eigen::MatrixXd::Zero(kContactCount, walk.cols());
  contacts.block(static_cast<int>(ContactLabel::LeftHeel), 20, 1, 20).setOnes();
  for (const double slide : {12.0, 50.0}) {
    // The foot still in the world at frame 20's place, then slid along the world's x.
    Eigen::MatrixXd before = walk;
    const Eigen::Vector2d planted = world(walk, 20);
    for (Eigen::Index f = 20; f < 40; ++f) {
      const auto i = static_cast<std::size_t>(f);
      const Eigen::Vector2d at = planted + Eigen::Vector2d(slide * static_cast<double>(f - 20) / 19.0, 0.0);
      const Eigen::Vector2d local = turn(-heading[i], at.x() - place[i].x(), at.y() - place[i].y());
      const Eigen::Vector2d shift = local - Eigen::Vector2d(before(3 * ankle, f), before(3 * ankle + 2, f));
      for (const int j : {ankle, toe}) {
        before(3 * j, f) += shift.x();
        before(3 * j + 2, f) += shift.y();
      }
    }
    Eigen::MatrixXd kept = before;
    enforceBoneLengths(kept, referenceProportions(), contacts);
    const Eigen::Vector2d median = planted + Eigen::Vector2d(slide * 10.0 / 19.0, 0.0);
    int held = 0;
    for (Eigen::Index f = 20; f < 40; ++f) {
      if ((kept.col(f).segment<3>(3 * ankle) - kept.col(f).segment<3>(3 * index(CanonicalJoint::LeftHip))).norm() >
          (referenceProportions().legLength() * (1.0 - 1e-5)))
        continue;  // pulled in to the leg's reach
      ++held;
      if (slide < kLockableSpreadCm) {
        EXPECT_LE((world(kept, f) - median).norm(), kKeptFootRadiusCm + 1e-9) << f;
      } else {
        EXPECT_NEAR((world(kept, f) - world(before, f)).norm(), 0.0, 1e-9) << f;
      }
    }
    EXPECT_GE(held, 10) << slide;
  }
}

// A planted foot whose leg the output has short (the foot 3 cm up its shin) comes out of the plain
// enforcement 3 cm lower: into the floor it stood on. With contacts it keeps its height from before.
// Where the leg is long, the enforcement raises the foot, and that level (the knee's bend) stays.
TEST(Proportions, EnforcingBoneLengthsNeverSinksAPlantedFoot) {
  Eigen::MatrixXd own = ownFeatures("zombie.bvh");
  retargetFeatures(own, measureProportions(own), referenceProportions());  // legs of the reference's length
  const Eigen::Index frames = own.cols();
  ASSERT_GT(frames, 40);
  Eigen::MatrixXd contacts = Eigen::MatrixXd::Zero(kContactCount, frames);
  contacts.block(static_cast<int>(ContactLabel::LeftHeel), 20, 1, 10).setOnes();
  const int hip = index(CanonicalJoint::LeftHip), knee = index(CanonicalJoint::LeftKnee);
  const int ankle = index(CanonicalJoint::LeftAnkle), toe = index(CanonicalJoint::LeftToe);
  const double reach = referenceProportions().bone_length[static_cast<std::size_t>(knee)] +
                       referenceProportions().bone_length[static_cast<std::size_t>(ankle)];  // thigh + shin
  for (const double up_the_shin : {3.0, -3.0}) {
    Eigen::MatrixXd before = own;
    for (const int joint : {ankle, toe}) before.row(3 * joint + 1).array() += up_the_shin;
    Eigen::MatrixXd plain = before, kept = before;
    enforceBoneLengths(plain, referenceProportions());
    enforceBoneLengths(kept, referenceProportions(), contacts);
    double plain_rise = 0.0;  // the plain enforcement's mean height over the contact less the one before
    for (Eigen::Index f = 20; f < 30; ++f) plain_rise += (plain(3 * ankle + 1, f) - before(3 * ankle + 1, f)) / 10.0;
    if (up_the_shin > 0.0) EXPECT_LT(plain_rise, -2.0);  // the short leg's foot sinks
    else EXPECT_GT(plain_rise, 2.0);                     // the long leg's rises
    int within = 0;
    for (Eigen::Index f = 20; f < 30; ++f) {
      if ((kept.col(f).segment<3>(3 * ankle) - kept.col(f).segment<3>(3 * hip)).norm() > reach * (1.0 - 1e-5)) continue;
      ++within;
      const double height_change = kept(3 * ankle + 1, f) - before(3 * ankle + 1, f);
      EXPECT_NEAR(height_change, up_the_shin > 0.0 ? 0.0 : plain_rise, 1e-9) << up_the_shin << " frame " << f;
    }
    EXPECT_GE(within, 5) << up_the_shin;
  }
}

TEST(Proportions, RetargetingThereAndBackIsTheIdentity) {
  const Eigen::MatrixXd own = ownFeatures("zombie.bvh");
  const Proportions from = measureProportions(own);
  const Proportions& other = referenceProportions();
  Eigen::MatrixXd there_and_back = own;
  retargetFeatures(there_and_back, from, other);
  retargetFeatures(there_and_back, other, from);
  EXPECT_LT((there_and_back - own).cwiseAbs().maxCoeff(), 1e-9);
  Eigen::MatrixXd same = own;
  retargetFeatures(same, from, from);
  EXPECT_EQ(same, own);
}

TEST(Proportions, BonesWithoutLengthCollapseOrAreLaidAlongTheirParent) {
  const Eigen::MatrixXd own = ownFeatures("cmu_131_01.bvh");
  const Proportions from = measureProportions(own);
  const Proportions handless = withoutHands(referenceProportions());
  ASSERT_GT(from.bone_length[static_cast<std::size_t>(index(CanonicalJoint::LeftHandEnd))], 1.0);
  Eigen::MatrixXd collapsed = own;
  retargetFeatures(collapsed, from, handless);  // hands collapse onto the wrists
  const int hand = 3 * index(CanonicalJoint::LeftHandEnd), wrist = 3 * index(CanonicalJoint::LeftWrist),
            elbow = 3 * index(CanonicalJoint::LeftElbow);
  EXPECT_LT((collapsed.middleRows<3>(hand) - collapsed.middleRows<3>(wrist)).cwiseAbs().maxCoeff(), 1e-12);
  Eigen::MatrixXd back = collapsed;
  retargetFeatures(back, handless, from);  // and come back along the forearm
  for (Eigen::Index f = 0; f < back.cols(); f += 40) {
    const Eigen::Vector3d bone = back.col(f).segment<3>(hand) - back.col(f).segment<3>(wrist);
    const Eigen::Vector3d forearm = back.col(f).segment<3>(wrist) - back.col(f).segment<3>(elbow);
    EXPECT_NEAR(bone.norm(), from.bone_length[static_cast<std::size_t>(index(CanonicalJoint::LeftHandEnd))], 1e-9);
    EXPECT_GT(bone.normalized().dot(forearm.normalized()), 1.0 - 1e-12);
  }
}

// What the retargeting is for: the sample rigs reach the networks in the actor's proportions.
TEST(Proportions, ExtractedFeaturesOfAnyRigHaveTheReferenceProportions) {
  for (const std::string fixture : {"cmu_131_01.bvh", "zombie.bvh"}) {
    const Motion motion = readBvh(test::fixture(fixture));
    const MotionFeatures features = extractFeatures(motion, mapJoints(motion.skeleton, fixture));
    const Proportions seen = measureProportions(features.values);
    for (int c = 1; c < kCanonicalJointCount; ++c)
      EXPECT_NEAR(seen.bone_length[static_cast<std::size_t>(c)],
                  referenceProportions().bone_length[static_cast<std::size_t>(c)], 1e-9)
          << fixture << " bone " << c;
    EXPECT_GT(std::abs(features.anchor.proportions.legLength() - referenceProportions().legLength()), 1.0) << fixture;
    // The planted toes stand as high as the reference actor's (step 9): the median of the toes' heights
    // over their contacts. The soft minimum of the feet (the rule before step 9) left CMU's 3 cm higher.
    std::vector<double> planted;
    for (ContactLabel label : {ContactLabel::LeftToe, ContactLabel::RightToe})
      for (int f = 0; f < features.frameCount(); ++f)
        if (features.contacts(static_cast<int>(label), f) > 0.5)
          planted.push_back(features.values(3 * index(kContactJoint[static_cast<std::size_t>(label)]) + 1, f));
    ASSERT_FALSE(planted.empty()) << fixture;
    std::sort(planted.begin(), planted.end());
    EXPECT_NEAR(planted[planted.size() / 2], kReferenceStanceToeHeightCm, 0.01) << fixture;
  }
}

}  // namespace
}  // namespace motionstyle
