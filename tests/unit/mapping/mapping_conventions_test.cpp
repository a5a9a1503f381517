// Hand-built rigs in each naming convention map to the expected joints, and the mapping follows the
// rig's names and structure rather than its file order, namespace or extra joints.

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "mapping/joint_mapping.h"
#include "mapping_test_rigs.h"

namespace motionstyle {
namespace {

using test::CJ;

using test::TestRig;

void expectMapsTo(const Skeleton& skeleton, const test::Expected& expected) {
  const JointMapping mapping = mapJoints(skeleton, "rig.bvh");
  const auto names = test::mappedNames(mapping, skeleton);
  for (CanonicalJoint joint : kAllCanonicalJoints)
    EXPECT_EQ(names.at(joint), expected.at(joint)) << canonicalJointName(joint);
  EXPECT_FALSE(describeMappingProblem(mapping, skeleton));
}

// The same rig written with every joint's children in reverse order (a different but equivalent file).
Skeleton withSiblingsReversed(const Skeleton& skeleton) {
  Skeleton result;
  std::function<void(int, int)> visit = [&](int joint, int new_parent) {
    Joint copy = skeleton.joints[static_cast<size_t>(joint)];
    copy.parent = new_parent;
    result.joints.push_back(copy);
    const int me = result.jointCount() - 1;
    const std::vector<int> children = skeleton.children(joint);
    for (auto child = children.rbegin(); child != children.rend(); ++child) visit(*child, me);
  };
  visit(0, -1);
  result.validate();
  return result;
}

// Left and Right swapped in every name (the character's mirror image, as far as names go).
Skeleton withSidesSwapped(Skeleton skeleton) {
  for (Joint& joint : skeleton.joints) {
    const std::string_view name = joint.name;
    std::string swapped;
    for (size_t at = 0; at < name.size();) {
      if (name.substr(at).starts_with("Left")) swapped += "Right", at += 4;
      else if (name.substr(at).starts_with("Right")) swapped += "Left", at += 5;
      else swapped += name[at++];
    }
    joint.name = swapped;
  }
  skeleton.validate();
  return skeleton;
}

std::string rigTestName(const ::testing::TestParamInfo<std::function<TestRig()>>& param_info) {
  std::string label = param_info.param().label;
  std::erase(label, '-');
  return label;
}

class Conventions : public ::testing::TestWithParam<std::function<TestRig()>> {};

TEST_P(Conventions, MapsToTheExpectedJoints) {
  const TestRig rig = GetParam()();
  SCOPED_TRACE(rig.label);
  expectMapsTo(rig.skeleton, rig.expected);
  EXPECT_EQ(mapJoints(rig.skeleton).convention, rig.convention);
}

TEST_P(Conventions, FileOrderOfSiblingsDoesNotMatter) {
  const TestRig rig = GetParam()();
  SCOPED_TRACE(rig.label);
  expectMapsTo(withSiblingsReversed(rig.skeleton), rig.expected);
}

TEST_P(Conventions, NamespacePrefixDoesNotMatter) {
  const TestRig rig = GetParam()();
  SCOPED_TRACE(rig.label);
  const Skeleton prefixed = test::withPrefix(rig.skeleton, "Character1:");
  EXPECT_EQ(mapJoints(prefixed).joints, mapJoints(rig.skeleton).joints);
}

TEST_P(Conventions, EveryCanonicalBoneIsAChainOfTheRig) {
  // Each canonical joint hangs below its canonical parent's joint, so a bone never jumps across limbs.
  const TestRig rig = GetParam()();
  SCOPED_TRACE(rig.label);
  const JointMapping mapping = mapJoints(rig.skeleton);
  for (CanonicalJoint joint : kAllCanonicalJoints) {
    const auto parent = canonicalParent(joint);
    if (!parent) continue;
    int j = rig.skeleton.joints[static_cast<size_t>(mapping[joint])].parent;
    while (j >= 0 && j != mapping[*parent]) j = rig.skeleton.joints[static_cast<size_t>(j)].parent;
    EXPECT_EQ(j, mapping[*parent]) << canonicalJointName(joint);
  }
}

INSTANTIATE_TEST_SUITE_P(AllRigs, Conventions,
                         ::testing::Values(test::bandaiRig, test::cgspeedRig, test::mixamoRig,
                                           test::animatedDrawingsRig, test::unrealRig, test::bipedRig),
                         rigTestName);

TEST(MixamoConvention, MixamorigPrefixMapsTheSameJoints) {
  const TestRig rig = test::mixamoRig();
  const Skeleton prefixed = test::withPrefix(rig.skeleton, "mixamorig:");
  test::Expected expected = rig.expected;
  for (auto& [joint, name] : expected) name = "mixamorig:" + name;
  expectMapsTo(prefixed, expected);
  EXPECT_EQ(mapJoints(prefixed).convention, "mixamo");
}

TEST(MixamoConvention, TwistJointsInsideTheArmAreSkipped) {
  // LeftArm > LeftArmTwist > LeftForeArm: the upper arm is still LeftArm, not the twist joint.
  TestRig rig = test::mixamoRig();
  Skeleton& s = rig.skeleton;
  const int fore_arm = s.find("LeftForeArm");
  Joint twist = s.joints[static_cast<size_t>(fore_arm)];
  twist.name = "LeftArmTwist";
  twist.offset *= 0.5;
  s.joints.insert(s.joints.begin() + fore_arm, twist);
  for (size_t j = static_cast<size_t>(fore_arm) + 1; j < s.joints.size(); ++j)
    if (s.joints[j].parent >= fore_arm) ++s.joints[j].parent;
  s.joints[static_cast<size_t>(fore_arm) + 1].parent = fore_arm;
  expectMapsTo(s, rig.expected);
}

TEST(MirroredNames, SwappingLeftAndRightInTheNamesMirrorsTheMapping) {
  for (const auto& make : {test::mixamoRig, test::cgspeedRig, test::animatedDrawingsRig}) {
    const TestRig rig = make();
    SCOPED_TRACE(rig.label);
    const JointMapping original = mapJoints(rig.skeleton);
    const JointMapping mirrored = mapJoints(withSidesSwapped(rig.skeleton));
    for (CanonicalJoint joint : kAllCanonicalJoints)
      EXPECT_EQ(mirrored[mirrorJoint(joint)], original[joint]) << canonicalJointName(joint);
  }
}

TEST(HandEnd, ZeroLengthConnectorsBeforeTheFingersAreSkipped) {
  // CMU's "lhand" sits on the wrist (zero offset) and carries the fingers: the hand end is the finger
  // joint, away from the wrist; without it, the connector's End Site.
  test::RigBuilder b;
  b.joint("Hips", "", {0, 20, 0}).chain({"Spine", "Chest", "Neck", "Head"}, "Hips", {0, 2, 0});
  for (const std::string s : {"Left", "Right"}) {
    b.chain({s + "Shoulder", s + "Elbow", s + "Wrist"}, "Chest", {3, 0, 0}, false);
    b.joint(s == "Left" ? "lhand" : "rhand", s + "Wrist", {0, 0, 0});
    if (s == "Left") b.chain({"LFingers"}, "lhand", {0.7, 0, 0}).chain({"LThumb"}, "lhand", {0, 0, 0});
    else b.endSite("rhand", {0.6, 0, 0});
    b.chain({s + "Hip", s + "Knee", s + "Ankle", s + "Toe"}, "Hips", {0, -6, 0});
  }
  const Skeleton skeleton = b.build();
  const JointMapping mapping = mapJoints(skeleton);
  EXPECT_EQ(skeleton.joints[static_cast<size_t>(mapping[CJ::LeftHandEnd])].name, "LFingers");
  EXPECT_EQ(skeleton.joints[static_cast<size_t>(mapping[CJ::RightHandEnd])].name, "rhand_End");
}

TEST(HandEnd, ToeTipEndSiteIsUsedOnlyWithoutAToeJoint) {
  test::RigBuilder b;
  b.joint("Hips", "", {0, 20, 0}).chain({"Spine", "Chest", "Neck", "Head"}, "Hips", {0, 2, 0});
  for (const std::string s : {"Left", "Right"}) {
    b.chain({s + "Arm", s + "ForeArm", s + "Hand", s + "HandEnd"}, "Chest", {3, 0, 0});
    b.chain({s + "UpLeg", s + "Leg", s + "Foot"}, "Hips", {0, -6, 0}, /*end_site=*/s == "Right");
    if (s == "Left") b.chain({"LeftToe", "LeftToeTip"}, "LeftFoot", {0, -1, 2});
  }
  const Skeleton skeleton = b.build();
  const JointMapping mapping = mapJoints(skeleton);
  EXPECT_EQ(skeleton.joints[static_cast<size_t>(mapping[CJ::LeftToe])].name, "LeftToe");
  EXPECT_EQ(skeleton.joints[static_cast<size_t>(mapping[CJ::RightToe])].name, "RightFoot_End");
}

}  // namespace
}  // namespace motionstyle
