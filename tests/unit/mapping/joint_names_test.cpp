// Reading sides and base names out of rig joint names.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mapping/joint_names.h"

namespace motionstyle {
namespace {

const char* sideName(BodySide side) {
  return side == BodySide::Left ? "Left" : side == BodySide::Right ? "Right" : "Center";
}

std::string firstReading(std::string_view name) {
  const std::vector<JointNameReading> readings = readJointName(name);
  if (readings.empty()) return "<none>";
  return std::string(sideName(readings.front().side)) + " " + readings.front().base;
}

bool hasReading(std::string_view name, BodySide side, const std::string& base) {
  for (const JointNameReading& reading : readJointName(name))
    if (reading.side == side && reading.base == base) return true;
  return false;
}

TEST(JointNames, NamesWithNothingLeftHaveNoReading) {
  EXPECT_TRUE(readJointName("").empty());
  EXPECT_TRUE(readJointName("mixamorig:").empty());
  EXPECT_TRUE(readJointName("__ -.").empty());
}

TEST(JointNames, TwoSideMarkersGiveNoExplicitSide) {
  EXPECT_EQ(firstReading("L_R"), "Center lr");
}

TEST(JointNames, ExplicitSideMarkersComeFirst) {
  EXPECT_EQ(firstReading("mixamorig:LeftUpLeg"), "Left upleg");
  EXPECT_EQ(firstReading("Character1|RightHandIndex1"), "Right handindex1");
  EXPECT_EQ(firstReading("Hand_L"), "Left hand");
  EXPECT_EQ(firstReading("l_hand"), "Left hand");
  EXPECT_EQ(firstReading("LThumb"), "Left thumb");
  EXPECT_EQ(firstReading("LHipJoint"), "Left hipjoint");
  EXPECT_EQ(firstReading("Bip01 L Thigh"), "Left thigh");
  EXPECT_EQ(firstReading("thigh.R"), "Right thigh");
  EXPECT_EQ(firstReading("Left Knee"), "Left knee");
  EXPECT_EQ(firstReading("leftKnee"), "Left knee");
  EXPECT_EQ(firstReading("Hand_L_End"), "Left handend");
  EXPECT_EQ(firstReading("mixamorig_RightFoot"), "Right foot");
}

TEST(JointNames, CentreNamesStayWhole) {
  EXPECT_EQ(firstReading("Hips"), "Center hips");
  EXPECT_EQ(firstReading("lowerback"), "Center lowerback");
  EXPECT_EQ(firstReading("joint_Root"), "Center jointroot");
  EXPECT_EQ(firstReading("Spine1"), "Center spine1");
  EXPECT_EQ(firstReading("Bip01"), "Center bip01");
  EXPECT_EQ(firstReading("DEF-spine.003"), "Center spine003");
}

TEST(JointNames, GluedSidesAreOfferedAfterTheCentreReading) {
  EXPECT_EQ(firstReading("lhand"), "Center lhand");
  EXPECT_TRUE(hasReading("lhand", BodySide::Left, "hand"));
  EXPECT_TRUE(hasReading("rfemur", BodySide::Right, "femur"));
  EXPECT_TRUE(hasReading("lefthand", BodySide::Left, "hand"));
  EXPECT_TRUE(hasReading("handright", BodySide::Right, "hand"));
  EXPECT_FALSE(hasReading("Hips", BodySide::Left, "hips"));
}

TEST(JointNames, FlattenKeepsSideWordsAndDropsDecorations) {
  EXPECT_EQ(flattenJointName("mixamorig:LeftHandIndex1"), "lefthandindex1");
  EXPECT_EQ(flattenJointName("Bip01 L Finger0"), "lfinger0");
  EXPECT_EQ(flattenJointName("Right_Hand-Thumb 2"), "righthandthumb2");
}

}  // namespace
}  // namespace motionstyle
