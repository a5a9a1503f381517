#include <gtest/gtest.h>

#include <algorithm>

#include "bvh/bvh_reader.h"
#include "features/foot_contacts.h"
#include "features/representation.h"
#include "mapping/joint_mapping.h"
#include "motion/kinematics.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

// The detector itself (thresholds, hysteresis, flicker, unit and axis invariance) is tested in
// tests/unit/ik/contacts_test.cpp on file-space clips; here: its use on the representation's canonical,
// reference-space positions.

TEST(FootContacts, RejectsBadCanonicalInput) {
  const std::array<int, kContactCount> feet = canonicalContactJoints();
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  // Too few joints: the last contact joint is missing.
  const int too_few = 3 * *std::max_element(feet.begin(), feet.end());
  EXPECT_THROW(detectContacts(Eigen::MatrixXd::Zero(10, too_few), feet, up, 0.0, 60.0, 170.0), std::invalid_argument);
  EXPECT_THROW(detectContacts(Eigen::MatrixXd::Zero(10, 63), feet, up, 0.0, 0.0, 170.0), std::invalid_argument);
  EXPECT_THROW(detectContacts(Eigen::MatrixXd::Zero(10, 63), feet, up, 0.0, 60.0, 0.0), std::invalid_argument);
}

TEST(FootContacts, PlantedLowFootIsInContactAndMovingOrHighFootIsNot) {
  const int frames = 60;
  Eigen::MatrixXd positions = Eigen::MatrixXd::Zero(frames, 63);
  const int heel = 3 * index(CanonicalJoint::LeftAnkle);
  const int toe = 3 * index(CanonicalJoint::RightToe);
  const int other_heel = 3 * index(CanonicalJoint::RightAnkle);
  for (int t = 0; t < frames; ++t) {
    positions(t, heel + 1) = 8.0;                          // low and still for the first half...
    if (t >= 30) positions(t, heel + 2) = 3.0 * (t - 30);  // ...then sliding at 180 cm/s
    positions(t, toe + 1) = 40.0 + (t % 2);                // high the whole time
    positions(t, other_heel + 1) = 8.0;                    // planted all along
  }
  const ContactLabels contacts =
      detectContacts(positions, canonicalContactJoints(), Eigen::Vector3d::UnitY(), 0.0, 60.0, 170.0);
  EXPECT_EQ(contacts.col(static_cast<int>(ContactLabel::LeftHeel)).head(29).sum(), 29);
  EXPECT_EQ(contacts.col(static_cast<int>(ContactLabel::LeftHeel)).tail(28).sum(), 0);
  EXPECT_EQ(contacts.col(static_cast<int>(ContactLabel::RightHeel)).sum(), frames);
  EXPECT_EQ(contacts.col(static_cast<int>(ContactLabel::RightToe)).sum(), 0);
}

TEST(FootContacts, RepresentationLabelsAreTheDetectorsOnItsReferencePositions) {
  // One detector: the representation's labels are exactly what detectContacts finds on the clip's
  // reference-space positions (rebuilt from the features), with the rest-pose body height in
  // reference cm, and they are plain 0/1 with some contact and some swing.
  const Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const MotionFeatures features = extractFeatures(motion, mapJoints(motion.skeleton));
  const Eigen::MatrixXd reference = referenceWorldPositions(features.values, features.anchor);
  const double body_height = restPoseBodyHeight(motion.skeleton, features.anchor.convention.fileUp()) *
                             features.anchor.convention.cm_per_unit * features.anchor.scale;
  EXPECT_GT(body_height, 120.0);  // a skeletal height of 127 reference cm is ~0.75 of the body's
  EXPECT_LT(body_height, 220.0);
  const ContactLabels expected =
      detectContacts(reference, canonicalContactJoints(), Eigen::Vector3d::UnitY(), 0.0, 60.0, body_height);
  ASSERT_EQ(features.contacts.rows(), kContactCount);
  ASSERT_EQ(features.contacts.cols(), features.values.cols());
  EXPECT_EQ(features.contacts, expected.transpose().cast<double>());
  for (int label = 0; label < kContactCount; ++label) {
    const double share = features.contacts.row(label).mean();
    EXPECT_GT(share, 0.2) << "label " << label;
    EXPECT_LT(share, 0.9) << "label " << label;
  }
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

TEST(FootContacts, FileSpaceGroundIsTheSameOnEveryJointAndInAnyUnit) {
  const Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton);
  const FileSpaceGround ground = detectFileSpaceGround(motion, mapping, canonicalJointPositions(motion, mapping));
  ASSERT_EQ(ground.contacts.rows(), motion.frameCount());
  EXPECT_GT(ground.contacts.sum(), 0);
  EXPECT_TRUE(ground.up.isApprox(ground.convention.fileUp()));
  // The app detects on every joint's positions through the mapping: the same floor and labels.
  const Eigen::MatrixXd world = worldPositions(motion);
  EXPECT_DOUBLE_EQ(estimateFloorHeight(world, contactJoints(mapping), ground.up), ground.floor_height);
  EXPECT_EQ(detectContacts(world, contactJoints(mapping), ground.up, ground.floor_height, motion.fps(),
                           restPoseBodyHeight(motion.skeleton, ground.up)),
            ground.contacts);
  // The same clip read as metres: the floor scales, the labels do not change.
  const FileSpaceGround in_metres =
      detectFileSpaceGround(motion, mapping, canonicalJointPositions(motion, mapping), std::string("m"));
  EXPECT_EQ(in_metres.floor_height, ground.floor_height);  // file units: the unit only scales cm_per_unit
  EXPECT_EQ(in_metres.contacts, ground.contacts);
  EXPECT_NE(in_metres.convention.cm_per_unit, ground.convention.cm_per_unit);
}

// The same clip under a static root (as Bandai's joint_Root, or a reference node) whose child's rest
// offset holds where it starts (its position channels replace the offset in the motion: kinematics.h):
// the same body height, floor and contacts wherever it starts. Before the
// body height measured the body alone, the root's offset counted as body (Bandai: 100 cm for a clip
// starting at the origin, 458 for one starting 450 cm ahead), and the thresholds moved with it.
TEST(FootContacts, AClipsContactsDoNotDependOnWhereAStaticRootStartsIt) {
  const Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton);
  const FileSpaceGround ground = detectFileSpaceGround(motion, mapping, canonicalJointPositions(motion, mapping));
  ASSERT_GT(ground.contacts.sum(), 0);
  // File units (this rig's body is about 26 tall): a start 4.5 m ahead, and one raised and to the side.
  for (const Eigen::Vector3d& start : {Eigen::Vector3d(0, 0, 70), Eigen::Vector3d(-3, 40, 70), Eigen::Vector3d(60, 12, -5)}) {
    Motion placed = motion;
    Joint root;
    root.name = "Reference";
    root.channels = motion.skeleton.joints[0].channels;
    placed.skeleton.joints.insert(placed.skeleton.joints.begin(), root);
    for (size_t j = 1; j < placed.skeleton.joints.size(); ++j) placed.skeleton.joints[j].parent += 1;
    placed.skeleton.joints[1].offset += start;
    placed.values.resize(motion.frameCount(), motion.values.cols() + static_cast<Eigen::Index>(root.channels.size()));
    placed.values.leftCols(static_cast<Eigen::Index>(root.channels.size())).setZero();
    placed.values.rightCols(motion.values.cols()) = motion.values;
    placed.validate();
    const JointMapping placed_mapping = mapJoints(placed.skeleton);
    const FileSpaceGround placed_ground =
        detectFileSpaceGround(placed, placed_mapping, canonicalJointPositions(placed, placed_mapping));
    EXPECT_NEAR(restPoseBodyHeight(placed.skeleton, ground.up), restPoseBodyHeight(motion.skeleton, ground.up), 1e-9)
        << start.transpose();
    EXPECT_NEAR(placed_ground.floor_height, ground.floor_height, 1e-9) << start.transpose();
    EXPECT_EQ(placed_ground.contacts, ground.contacts) << start.transpose();
  }
}

}  // namespace
}  // namespace motionstyle
