// The canonical set: names, lookup, mirror pairs and their agreement with the canonical parent table.

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "mapping/canonical_joints.h"

namespace motionstyle {
namespace {

TEST(CanonicalJoints, UnknownNamesAreNotFound) {
  for (const std::string name : {"", "LeftFoot", "Hip", "Hips ", "LeftHandEnd_End", "Pelvis", "21"})
    EXPECT_FALSE(canonicalJointFromName(name)) << "'" << name << "'";
}

TEST(CanonicalJoints, NamesAreUniqueAndLookUpIgnoringCase) {
  std::set<std::string> seen;
  for (CanonicalJoint joint : kAllCanonicalJoints) {
    const std::string name(canonicalJointName(joint));
    EXPECT_TRUE(seen.insert(name).second) << name;
    EXPECT_EQ(canonicalJointFromName(name), joint);
    std::string lower = name;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_EQ(canonicalJointFromName(lower), joint);
  }
  EXPECT_EQ(seen.size(), static_cast<size_t>(kCanonicalJointCount));
  EXPECT_EQ(canonicalJointName(CanonicalJoint::Hips), "Hips");
  EXPECT_EQ(canonicalJointName(CanonicalJoint::RightHandEnd), "RightHandEnd");
}

TEST(CanonicalJoints, MirrorIsAnInvolutionThatSwapsSidesAndNames) {
  int centre = 0;
  for (CanonicalJoint joint : kAllCanonicalJoints) {
    const CanonicalJoint mirrored = mirrorJoint(joint);
    EXPECT_EQ(mirrorJoint(mirrored), joint);
    const std::string name(canonicalJointName(joint)), other(canonicalJointName(mirrored));
    switch (sideOf(joint)) {
      case BodySide::Center:
        ++centre;
        EXPECT_EQ(mirrored, joint);
        break;
      case BodySide::Left:
        EXPECT_EQ(sideOf(mirrored), BodySide::Right);
        EXPECT_EQ("Right" + name.substr(4), other);
        break;
      case BodySide::Right:
        EXPECT_EQ(sideOf(mirrored), BodySide::Left);
        EXPECT_EQ("Left" + name.substr(5), other);
        break;
    }
  }
  EXPECT_EQ(centre, 5);  // hips, spine, chest, neck, head
}

TEST(CanonicalJoints, MirroringCommutesWithTheParentTable) {
  for (CanonicalJoint joint : kAllCanonicalJoints) {
    const std::optional<CanonicalJoint> parent = canonicalParent(joint);
    const std::optional<CanonicalJoint> mirrored_parent = canonicalParent(mirrorJoint(joint));
    ASSERT_EQ(parent.has_value(), mirrored_parent.has_value()) << canonicalJointName(joint);
    if (parent) {
      EXPECT_EQ(mirrorJoint(*parent), *mirrored_parent) << canonicalJointName(joint);
    }
  }
  EXPECT_FALSE(canonicalParent(CanonicalJoint::Hips));
  EXPECT_EQ(canonicalParent(CanonicalJoint::LeftUpperArm), CanonicalJoint::Chest);
}

}  // namespace
}  // namespace motionstyle
