// Rigs the automatic mapping must refuse, with the exact list of missing canonical joints, and mappings
// describeMappingProblem must reject.

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "common/errors.h"
#include "mapping/joint_mapping.h"
#include "mapping_test_rigs.h"

namespace motionstyle {
namespace {

using test::CJ;

using test::RigBuilder;

constexpr std::string_view kPrefix = "cannot map the rig to the canonical skeleton: missing ";
constexpr std::string_view kSuffix = "; provide a joint mapping file (motionstyle-cli info CLIP --write-mapping MAP.json writes one to complete)";

// The comma-separated list between "missing " and " (" in the error message.
std::string missingListOf(const InputError& error) {
  const std::string& detail = error.detail();
  EXPECT_EQ(detail.rfind(kPrefix, 0), 0u) << detail;
  const size_t start = kPrefix.size();
  const size_t end = detail.find(" (", start);
  if (end == std::string::npos) return "<no list in: " + detail + ">";
  return detail.substr(start, end - start);
}

InputError mappingErrorOf(const Skeleton& skeleton, const std::string& source = "clip.bvh") {
  try {
    mapJoints(skeleton, source);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "mapJoints accepted the rig";
  return InputError("", 0, "");
}

TEST(MapJointsInvalid, LeftLegWithUnknownNamesListsExactlyTheLeftLeg) {
  const Skeleton rig = test::renamed(test::mixamoRig().skeleton, {{"LeftUpLeg", "bone_07"}, {"LeftLeg", "bone_08"},
                                                                  {"LeftFoot", "bone_09"}, {"LeftToeBase", "bone_10"}});
  const InputError error = mappingErrorOf(rig);
  EXPECT_EQ(error.file(), "clip.bvh");
  EXPECT_EQ(error.line(), 0);
  EXPECT_EQ(missingListOf(error), "LeftHip, LeftKnee, LeftAnkle, LeftToe");
  EXPECT_NE(error.detail().find("LeftKnee: no left-side joint named like Knee, Leg, LowerLeg"), std::string::npos)
      << error.detail();
  EXPECT_NE(error.detail().find("LeftHip, LeftAnkle, LeftToe: found from LeftKnee, which is missing"), std::string::npos)
      << error.detail();
  EXPECT_TRUE(error.detail().ends_with(kSuffix)) << error.detail();
}

TEST(MapJointsInvalid, RigWithMeaninglessNamesListsAllTwentyOneJoints) {
  RigBuilder b;
  b.joint("j0", "", {0, 90, 0}).chain({"j1", "j2", "j3", "j4"}, "j0", {0, 10, 0});
  b.chain({"j5", "j6", "j7", "j8"}, "j0", {10, -20, 0}).chain({"j9", "j10", "j11", "j12"}, "j0", {-10, -20, 0});
  const InputError error = mappingErrorOf(b.build(), "");
  std::string all;
  for (CanonicalJoint joint : kAllCanonicalJoints) all += (all.empty() ? "" : ", ") + std::string(canonicalJointName(joint));
  EXPECT_EQ(missingListOf(error), all);
  EXPECT_EQ(error.file(), "");
}

TEST(MapJointsInvalid, RigWithoutAHeadMissesTheSpineColumnOnly) {
  const InputError error = mappingErrorOf(test::renamed(test::mixamoRig().skeleton, {{"Head", "Kopf"}}));
  EXPECT_EQ(missingListOf(error), "Spine, Chest, Neck, Head");
  EXPECT_NE(error.detail().find("Head: no joint named like Head or Skull"), std::string::npos) << error.detail();
}

TEST(MapJointsInvalid, UnnamedLeftElbowMissesTheLeftArmOnly) {
  const InputError error = mappingErrorOf(test::renamed(test::mixamoRig().skeleton, {{"LeftForeArm", "LeftSegment3"}}));
  EXPECT_EQ(missingListOf(error), "LeftUpperArm, LeftElbow, LeftWrist, LeftHandEnd");
}

TEST(MapJointsInvalid, ArmsHangingOffTheHipsLeaveNoChest) {
  RigBuilder b;
  b.joint("Hips", "", {0, 100, 0}).chain({"Spine", "Spine1", "Neck", "Head"}, "Hips", {0, 12, 0});
  for (const std::string s : {"Left", "Right"}) {
    b.chain({s + "Arm", s + "ForeArm", s + "Hand"}, "Hips", {10, 0, 0});
    b.chain({s + "UpLeg", s + "Leg", s + "Foot", s + "ToeBase"}, "Hips", {0, -20, 0});
  }
  const InputError error = mappingErrorOf(b.build());
  EXPECT_EQ(missingListOf(error), "Spine, Chest, Neck");
  EXPECT_NE(error.detail().find("Chest: the arms do not branch off the spine"), std::string::npos) << error.detail();
}

TEST(MapJointsInvalid, KneeWithNothingBelowMissesAnkleAndToe) {
  RigBuilder b;
  b.joint("Hips", "", {0, 100, 0}).chain({"Spine", "Chest", "Neck", "Head"}, "Hips", {0, 12, 0});
  for (const std::string s : {"Left", "Right"}) {
    b.chain({s + "Arm", s + "ForeArm", s + "Hand", s + "HandEnd"}, "Chest", {10, 0, 0});
    if (s == "Left") b.chain({s + "UpLeg", s + "Leg"}, "Hips", {0, -20, 0});
    else b.chain({s + "UpLeg", s + "Leg", s + "Foot", s + "ToeBase"}, "Hips", {0, -20, 0});
  }
  const InputError error = mappingErrorOf(b.build());
  EXPECT_EQ(missingListOf(error), "LeftAnkle, LeftToe");
  EXPECT_NE(error.detail().find("LeftAnkle: no joint below LeftKnee 'LeftLeg'"), std::string::npos) << error.detail();
}

TEST(MapJointsInvalid, HandWithoutChildOrEndSiteMissesTheHandEnd) {
  RigBuilder b;
  b.joint("Hips", "", {0, 100, 0}).chain({"Spine", "Chest", "Neck", "Head"}, "Hips", {0, 12, 0});
  for (const std::string s : {"Left", "Right"}) {
    b.chain({s + "Arm", s + "ForeArm", s + "Hand"}, "Chest", {10, 0, 0}, /*end_site=*/s == "Right");
    b.chain({s + "UpLeg", s + "Leg", s + "Foot", s + "ToeBase"}, "Hips", {0, -20, 0});
  }
  const InputError error = mappingErrorOf(b.build());
  EXPECT_EQ(missingListOf(error), "LeftHandEnd");
}

TEST(MapJointsInvalid, InvalidSkeletonIsAProgrammingError) {
  EXPECT_THROW(mapJoints(Skeleton{}), std::invalid_argument);
  EXPECT_THROW(guessJointMapping(Skeleton{}), std::invalid_argument);
}

TEST(MapJointsInvalid, GuessLeavesExactlyTheUnmappableJointsUnset) {
  const test::TestRig rig = test::mixamoRig();
  const Skeleton skeleton = test::renamed(rig.skeleton, {{"RightForeArm", "RightSegment3"}});
  const JointMapping guess = guessJointMapping(skeleton);
  const std::vector<CanonicalJoint> expected_missing = {CJ::RightUpperArm, CJ::RightElbow, CJ::RightWrist, CJ::RightHandEnd};
  EXPECT_EQ(guess.missing(), expected_missing);
  const auto names = test::mappedNames(guess, skeleton);
  for (CanonicalJoint joint : kAllCanonicalJoints) {
    if (std::find(expected_missing.begin(), expected_missing.end(), joint) != expected_missing.end()) continue;
    EXPECT_EQ(names.at(joint), rig.expected.at(joint)) << canonicalJointName(joint);
  }
}

class MappingProblem : public ::testing::Test {
 protected:
  test::TestRig rig = test::mixamoRig();
  JointMapping mapping = mapJoints(rig.skeleton);
  int at(const std::string& name) const { return rig.skeleton.find(name); }
};

TEST_F(MappingProblem, RejectsAnIndexOutsideTheSkeleton) {
  mapping[CJ::LeftKnee] = rig.skeleton.jointCount();
  const auto problem = describeMappingProblem(mapping, rig.skeleton);
  ASSERT_TRUE(problem);
  EXPECT_EQ(*problem, "LeftKnee refers to joint " + std::to_string(rig.skeleton.jointCount()) +
                          " but the skeleton has " + std::to_string(rig.skeleton.jointCount()) + " joints");
  EXPECT_THROW(mapping.validate(rig.skeleton), std::invalid_argument);
}

TEST_F(MappingProblem, RejectsSwappedChainJoints) {
  mapping[CJ::LeftKnee] = at("LeftFoot");
  mapping[CJ::LeftAnkle] = at("LeftLeg");
  EXPECT_EQ(describeMappingProblem(mapping, rig.skeleton),
            "LeftAnkle 'LeftLeg' does not hang below LeftKnee 'LeftFoot'");
}

TEST_F(MappingProblem, RejectsOneRigJointUsedTwice) {
  mapping[CJ::RightHip] = at("LeftUpLeg");
  EXPECT_EQ(describeMappingProblem(mapping, rig.skeleton), "RightHip 'LeftUpLeg' is already used for LeftHip");
}

TEST_F(MappingProblem, RejectsAHeadThatDoesNotHangBelowTheNeck) {
  mapping[CJ::Neck] = at("LeftShoulder");
  EXPECT_EQ(describeMappingProblem(mapping, rig.skeleton), "Head 'Head' does not hang below Neck 'LeftShoulder'");
}

TEST_F(MappingProblem, ListsEveryMissingJoint) {
  mapping[CJ::Spine] = -1;
  mapping[CJ::RightToe] = -1;
  EXPECT_EQ(describeMappingProblem(mapping, rig.skeleton), "missing RightToe, Spine");
  EXPECT_FALSE(describeMappingProblem(mapJoints(rig.skeleton), rig.skeleton));
}

}  // namespace
}  // namespace motionstyle
