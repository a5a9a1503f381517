// The committed real clips (tests/data) map completely to the joints a person would pick.

#include <gtest/gtest.h>

#include "bvh/bvh_reader.h"
#include "mapping/joint_mapping.h"
#include "mapping_test_rigs.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

using test::CJ;

void expectNames(const Skeleton& skeleton, const JointMapping& mapping, const test::Expected& expected) {
  const auto names = test::mappedNames(mapping, skeleton);
  for (CanonicalJoint joint : kAllCanonicalJoints)
    EXPECT_EQ(names.at(joint), expected.at(joint)) << canonicalJointName(joint);
}

// Every canonical bone of these rigs has a length in the rest pose (the bone-length loss needs one).
void expectNoZeroLengthBone(const Skeleton& skeleton, const JointMapping& mapping) {
  std::vector<Eigen::Vector3d> rest(skeleton.joints.size());
  for (size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    rest[j] = joint.offset + (joint.parent >= 0 ? rest[static_cast<size_t>(joint.parent)] : Eigen::Vector3d::Zero());
  }
  for (CanonicalJoint joint : kAllCanonicalJoints) {
    const auto parent = canonicalParent(joint);
    if (!parent) continue;
    const double length = (rest[static_cast<size_t>(mapping[joint])] - rest[static_cast<size_t>(mapping[*parent])]).norm();
    EXPECT_GT(length, 0.0) << canonicalJointName(joint);
  }
}

TEST(MappingFixtures, Cmu131MapsToItsBallJointsAndSkipsConnectors) {
  const Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton, motion.source);
  // lowerback, lowerneck, LHipJoint, LeftCollar and lhand are zero-length connectors; "LeftShoulder" is
  // the shoulder ball joint here (the clavicle is "LeftCollar").
  test::Expected expected = {{CJ::Hips, "Hips"}, {CJ::Spine, "Chest"}, {CJ::Chest, "Chest2"}, {CJ::Neck, "Neck"},
                             {CJ::Head, "Head"}};
  for (const std::string s : {"Left", "Right"}) {
    auto c = [&](CanonicalJoint j) { return s == "Left" ? j : mirrorJoint(j); };
    expected[c(CJ::LeftHip)] = s + "Hip", expected[c(CJ::LeftKnee)] = s + "Knee";
    expected[c(CJ::LeftAnkle)] = s + "Ankle", expected[c(CJ::LeftToe)] = s + "Toe";
    expected[c(CJ::LeftUpperArm)] = s + "Shoulder", expected[c(CJ::LeftElbow)] = s + "Elbow";
    expected[c(CJ::LeftWrist)] = s + "Wrist", expected[c(CJ::LeftHandEnd)] = s.substr(0, 1) + "Fingers";
  }
  expectNames(motion.skeleton, mapping, expected);
  EXPECT_EQ(mapping.convention, "cmu");
  expectNoZeroLengthBone(motion.skeleton, mapping);
}

TEST(MappingFixtures, ZombieMapsLikeTheAnimatedDrawingsRig) {
  const Motion motion = readBvh(test::fixture("zombie.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton, motion.source);
  expectNames(motion.skeleton, mapping, test::animatedDrawingsRig().expected);
  EXPECT_EQ(mapping.convention, "animated-drawings");
  expectNoZeroLengthBone(motion.skeleton, mapping);
}

}  // namespace
}  // namespace motionstyle
