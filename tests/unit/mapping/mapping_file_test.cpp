// Mapping files: round trips, atomic saves, and rigs only a file can map.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "bvh/bvh_reader.h"
#include "common/errors.h"
#include "mapping/mapping_file.h"
#include "mapping_test_rigs.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

using test::CJ;

std::string readText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

class MappingFile : public ::testing::Test {
 protected:
  std::filesystem::path dir;
  void SetUp() override { dir = test::uniqueTempDir("mapping-file"); }
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(MappingFile, SavingAnIncompleteMappingThrowsAndLeavesTheFileAlone) {
  const test::TestRig rig = test::mixamoRig();
  const std::filesystem::path file = dir / "rig.json";
  saveJointMapping(mapJoints(rig.skeleton), rig.skeleton, file);
  const std::string before = readText(file);
  JointMapping incomplete = mapJoints(rig.skeleton);
  incomplete[CJ::Neck] = -1;
  EXPECT_THROW(saveJointMapping(incomplete, rig.skeleton, file), std::invalid_argument);
  EXPECT_EQ(readText(file), before);
}

TEST_F(MappingFile, SaveThenLoadGivesTheSameJointsForEveryRig) {
  for (const auto& make : {test::bandaiRig, test::cgspeedRig, test::mixamoRig, test::animatedDrawingsRig,
                           test::unrealRig, test::bipedRig}) {
    const test::TestRig rig = make();
    SCOPED_TRACE(rig.label);
    const std::filesystem::path file = dir / (rig.label + ".json");
    const JointMapping mapping = mapJoints(rig.skeleton);
    saveJointMapping(mapping, rig.skeleton, file);
    const JointMapping loaded = loadJointMapping(file, rig.skeleton);
    EXPECT_EQ(loaded.joints, mapping.joints);
    EXPECT_EQ(loaded.convention, "file:" + file.string());
    EXPECT_EQ(readText(file), formatJointMapping(loaded, rig.skeleton));  // stable text
  }
  // Only the saved files remain: the atomic writer left no temporary file behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 6);
}

TEST_F(MappingFile, FormatListsTheCanonicalJointsInFeatureOrder) {
  const test::TestRig rig = test::bandaiRig();
  const std::string text = formatJointMapping(mapJoints(rig.skeleton), rig.skeleton);
  EXPECT_EQ(text.rfind("{\n  \"format\": \"motionstyle-joint-mapping\",\n  \"version\": 1,\n  \"joints\": {\n"
                       "    \"Hips\": \"Hips\",\n    \"LeftHip\": \"UpperLeg_L\",\n", 0),
            0u)
      << text;
  size_t previous = 0;
  for (CanonicalJoint joint : kAllCanonicalJoints) {
    std::string key = "\"";  // built by appending: GCC 12 warns falsely (-Wrestrict) on "\"" + string
    key += canonicalJointName(joint);
    key += "\":";
    const size_t at = text.find(key);
    ASSERT_NE(at, std::string::npos) << canonicalJointName(joint);
    EXPECT_GT(at, previous);
    previous = at;
  }
  EXPECT_NE(text.find("\"LeftHandEnd\": \"Hand_L_End\""), std::string::npos);
}

TEST_F(MappingFile, FileMapsARigTheAutomaticMappingCannotRead) {
  // German joint names: nothing the automatic mapping knows.
  test::RigBuilder b;
  b.joint("Becken", "", {0, 95, 0}).chain({"Ruecken", "Brust", "Hals", "Kopf"}, "Becken", {0, 12, 0});
  for (const std::string s : {"Links", "Rechts"}) {
    b.chain({"Oberarm" + s, "Unterarm" + s, "Handgelenk" + s}, "Brust", {12, 0, 0});
    b.chain({"Oberschenkel" + s, "Unterschenkel" + s, "Fussgelenk" + s, "Zehen" + s}, "Becken", {0, -20, 0});
  }
  const Skeleton skeleton = b.build();
  EXPECT_THROW(mapJoints(skeleton, "german.bvh"), InputError);

  const std::filesystem::path file = dir / "german.json";
  std::ofstream(file) << R"({
  // comments are allowed, and canonical names ignore case
  "format": "motionstyle-joint-mapping", "version": 1,
  "joints": {
    "hips": "Becken", "spine": "Ruecken", "chest": "Brust", "neck": "Hals", "head": "Kopf",
    "LeftHip": "OberschenkelLinks", "LeftKnee": "UnterschenkelLinks", "LeftAnkle": "FussgelenkLinks",
    "LeftToe": "ZehenLinks", "RightHip": "OberschenkelRechts", "RightKnee": "UnterschenkelRechts",
    "RightAnkle": "FussgelenkRechts", "RightToe": "ZehenRechts",
    "LeftUpperArm": "OberarmLinks", "LeftElbow": "UnterarmLinks", "LeftWrist": "HandgelenkLinks",
    "LeftHandEnd": "HandgelenkLinks_End", "RightUpperArm": "OberarmRechts", "RightElbow": "UnterarmRechts",
    "RightWrist": "HandgelenkRechts", "RightHandEnd": "HandgelenkRechts_End"
  }
})";
  const JointMapping mapping = mapJoints(skeleton, "german.bvh", file);
  EXPECT_EQ(mapping.convention, "file:" + file.string());
  EXPECT_EQ(skeleton.joints[static_cast<size_t>(mapping[CJ::Hips])].name, "Becken");
  EXPECT_EQ(skeleton.joints[static_cast<size_t>(mapping[CJ::RightHandEnd])].name, "HandgelenkRechts_End");
  EXPECT_TRUE(skeleton.joints[static_cast<size_t>(mapping[CJ::LeftHandEnd])].end_site);
}

// The template (info --write-mapping): empty where the automatic mapping found nothing, refused as it
// is with the line of the first gap, and a valid file once the gaps are filled in.
TEST_F(MappingFile, TheTemplateIsRefusedUntilItsGapsAreFilledIn) {
  test::RigBuilder b;  // German leg names: the automatic mapping finds the spine and arms only
  b.joint("Hips", "", {0, 95, 0}).chain({"Spine", "Chest", "Neck", "Head"}, "Hips", {0, 12, 0});
  for (const std::string s : {"Left", "Right"}) {
    b.chain({s + "Arm", s + "ForeArm", s + "Hand"}, "Chest", {s == "Left" ? 12.0 : -12.0, 0, 0});
    b.chain({"Oberschenkel" + s, "Unterschenkel" + s, "Fussgelenk" + s, "Zehen" + s}, "Hips",
            {s == "Left" ? 8.0 : -8.0, -20, 0});
  }
  const Skeleton skeleton = b.build();
  const JointMapping guess = guessJointMapping(skeleton);
  ASSERT_FALSE(guess.missing().empty());
  const std::string text = formatJointMappingTemplate(guess, skeleton, "german.bvh");
  EXPECT_NE(text.find("// Joint mapping for german.bvh"), std::string::npos);
  EXPECT_NE(text.find("UnterschenkelLeft"), std::string::npos);  // the rig's joints are listed
  EXPECT_NE(text.find("\"LeftKnee\": \"\""), std::string::npos) << text;
  try {
    parseJointMapping(text, skeleton, "german.json");
    ADD_FAILURE() << "a template with gaps was accepted";
  } catch (const InputError& error) {
    EXPECT_GT(error.line(), 0);
    EXPECT_NE(std::string(error.what()).find("no rig joint given"), std::string::npos) << error.what();
  }
  std::string filled = text;
  for (const std::string s : {"Left", "Right"})
    for (const auto& [canonical, rig] : {std::pair{"Hip", "Oberschenkel"}, std::pair{"Knee", "Unterschenkel"},
                                         std::pair{"Ankle", "Fussgelenk"}, std::pair{"Toe", "Zehen"}}) {
      const std::string gap = "\"" + s + canonical + "\": \"\"";
      const size_t at = filled.find(gap);
      if (at != std::string::npos) filled.replace(at, gap.size(), "\"" + s + canonical + "\": \"" + rig + s + "\"");
    }
  for (const std::string trunk : {"Hips", "Spine", "Chest", "Neck"}) {  // found from the legs: gaps too
    const std::string gap = "\"" + trunk + "\": \"\"";
    const size_t at = filled.find(gap);
    if (at != std::string::npos) filled.replace(at, gap.size(), "\"" + trunk + "\": \"" + trunk + "\"");
  }
  const JointMapping mapping = parseJointMapping(filled, skeleton, "german.json");
  EXPECT_TRUE(mapping.missing().empty());
  for (CanonicalJoint joint : kAllCanonicalJoints) {  // what the guess found is kept
    if (guess[joint] >= 0) {
      EXPECT_EQ(mapping[joint], guess[joint]) << canonicalJointName(joint);
    }
  }
}

TEST_F(MappingFile, ReadmeExampleIsAValidFileForAnUnrealRig) {
  const std::filesystem::path readme =
      std::filesystem::path(MOTIONSTYLE_TEST_DATA_DIR) / ".." / ".." / "core" / "mapping" / "README.md";
  const std::string text = readText(readme);
  const size_t start = text.find("```json\n");
  ASSERT_NE(start, std::string::npos) << readme;
  const size_t end = text.find("```", start + 8);
  ASSERT_NE(end, std::string::npos);
  const test::TestRig rig = test::unrealRig();
  const JointMapping example = parseJointMapping(text.substr(start + 8, end - start - 8), rig.skeleton, "README.md");
  EXPECT_EQ(example.joints, mapJoints(rig.skeleton).joints);
}

TEST_F(MappingFile, AGivenFileIsPreferredOverTheAutomaticMapping) {
  const Motion zombie = readBvh(test::fixture("zombie.bvh"));
  JointMapping custom = mapJoints(zombie.skeleton);
  custom[CJ::LeftHandEnd] = zombie.skeleton.find("LeftHandThumb1");
  const std::filesystem::path file = dir / "zombie.json";
  saveJointMapping(custom, zombie.skeleton, file);

  EXPECT_EQ(mapJoints(zombie.skeleton, zombie.source, file).joints, custom.joints);
  const JointMapping automatic = mapJoints(zombie.skeleton, zombie.source, std::nullopt);
  EXPECT_EQ(automatic.convention, "animated-drawings");
  EXPECT_EQ(zombie.skeleton.joints[static_cast<size_t>(automatic[CJ::LeftHandEnd])].name, "LeftHandEnd");
}

}  // namespace
}  // namespace motionstyle
