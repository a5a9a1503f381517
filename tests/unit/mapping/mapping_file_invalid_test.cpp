// Joint mapping files that must be refused, each with the line the user has to look at.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "mapping/mapping_file.h"
#include "mapping_test_rigs.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

using Entries = std::vector<std::pair<std::string, std::string>>;

// The Mixamo rig's expected mapping as file entries, in canonical order.
Entries mixamoEntries() {
  Entries entries;
  const test::TestRig rig = test::mixamoRig();
  for (CanonicalJoint joint : kAllCanonicalJoints)
    entries.emplace_back(std::string(canonicalJointName(joint)), rig.expected.at(joint));
  return entries;
}

// Line 1 "{", 2 format, 3 version, 4 "joints": {, entry i on line 5 + i, then "  }" and "}".
std::string mappingText(const Entries& entries) {
  std::string text = "{\n  \"format\": \"motionstyle-joint-mapping\",\n  \"version\": 1,\n  \"joints\": {\n";
  for (size_t i = 0; i < entries.size(); ++i)
    text += "    \"" + entries[i].first + "\": \"" + entries[i].second + "\"" + (i + 1 < entries.size() ? ",\n" : "\n");
  return text + "  }\n}\n";
}

int entryLine(size_t entry) { return 5 + static_cast<int>(entry); }

class MappingFileInvalid : public ::testing::Test {
 protected:
  Skeleton skeleton = test::mixamoRig().skeleton;

  InputError errorOf(const std::string& text) {
    try {
      parseJointMapping(text, skeleton, "rig.json");
    } catch (const InputError& error) {
      EXPECT_EQ(error.file(), "rig.json");
      return error;
    }
    ADD_FAILURE() << "accepted:\n" << text;
    return InputError("", -1, "");
  }
};

TEST_F(MappingFileInvalid, BaselineIsAccepted) {
  // The mutations below are only meaningful if the unmutated text parses.
  EXPECT_NO_THROW(parseJointMapping(mappingText(mixamoEntries()), skeleton, "rig.json"));
}

TEST_F(MappingFileInvalid, EmptyTextIsInvalidJsonOnLineOne) {
  const InputError error = errorOf("");
  EXPECT_EQ(error.line(), 1);
  EXPECT_EQ(error.detail().rfind("invalid JSON: ", 0), 0u) << error.detail();
}

TEST_F(MappingFileInvalid, MissingCommaIsReportedOnTheLineOfTheNextKey) {
  const InputError error =
      errorOf("{\n  \"format\": \"motionstyle-joint-mapping\",\n  \"version\": 1\n  \"joints\": {}\n}\n");
  EXPECT_EQ(error.line(), 4);
  EXPECT_EQ(error.detail().rfind("invalid JSON: ", 0), 0u) << error.detail();
}

TEST_F(MappingFileInvalid, UnterminatedStringIsReportedOnItsLine) {
  std::string text = mappingText(mixamoEntries());
  const size_t quote = text.find("\"LeftUpLeg\"");
  text.erase(quote + 10, 1);  // "LeftUpLeg,  (the closing quote removed; the string runs into the newline)
  const InputError error = errorOf(text);
  EXPECT_EQ(error.line(), entryLine(1));
}

TEST_F(MappingFileInvalid, TrailingGarbageIsReportedOnItsLine) {
  const InputError error = errorOf(mappingText(mixamoEntries()) + "\n\n}\n");
  EXPECT_EQ(error.line(), entryLine(kCanonicalJointCount) + 4);
}

TEST_F(MappingFileInvalid, RootMustBeAnObject) {
  const InputError error = errorOf("[\"Hips\"]");
  EXPECT_EQ(error.line(), 1);
  EXPECT_NE(error.detail().find("expected a JSON object"), std::string::npos) << error.detail();
}

TEST_F(MappingFileInvalid, WrongFormatIsReportedOnItsLine) {
  std::string text = mappingText(mixamoEntries());
  text.replace(text.find("motionstyle-joint-mapping"), 25, "bone-map");
  const InputError error = errorOf(text);
  EXPECT_EQ(error.line(), 2);
  EXPECT_NE(error.detail().find("expected \"format\": \"motionstyle-joint-mapping\""), std::string::npos);
}

TEST_F(MappingFileInvalid, MissingFormatIsReportedOnLineOne) {
  std::string text = mappingText(mixamoEntries());
  text.erase(text.find("  \"format\""), text.find("  \"version\"") - text.find("  \"format\""));
  EXPECT_EQ(errorOf(text).line(), 1);
}

TEST_F(MappingFileInvalid, OtherVersionsAreRefused) {
  for (const std::string version : {"2", "\"1\"", "1.5", "0"}) {
    std::string text = mappingText(mixamoEntries());
    text.replace(text.find("\"version\": 1"), 12, "\"version\": " + version);
    const InputError error = errorOf(text);
    EXPECT_EQ(error.line(), 3) << version;
    EXPECT_NE(error.detail().find("expected \"version\": 1"), std::string::npos) << error.detail();
  }
}

TEST_F(MappingFileInvalid, JointsMustBeAnObject) {
  const InputError error =
      errorOf("{\n  \"format\": \"motionstyle-joint-mapping\",\n  \"version\": 1,\n  \"joints\": [\"Hips\"]\n}\n");
  EXPECT_EQ(error.line(), 4);
}

TEST_F(MappingFileInvalid, UnknownCanonicalNameIsReportedOnItsLine) {
  Entries entries = mixamoEntries();
  entries[3].first = "LeftFoot";  // instead of LeftAnkle
  const InputError error = errorOf(mappingText(entries));
  EXPECT_EQ(error.line(), entryLine(3));
  EXPECT_EQ(error.detail().rfind("unknown canonical joint \"LeftFoot\" (expected one of Hips, LeftHip, ", 0), 0u)
      << error.detail();
}

TEST_F(MappingFileInvalid, RepeatedKeyIsReportedOnItsSecondLine) {
  Entries entries = mixamoEntries();
  entries.insert(entries.begin() + 9, {"LeftKnee", "LeftFoot"});
  const InputError error = errorOf(mappingText(entries));
  EXPECT_EQ(error.line(), entryLine(9));
  EXPECT_EQ(error.detail(), "the key \"LeftKnee\" appears twice");
}

TEST_F(MappingFileInvalid, KeysDifferingOnlyInCaseRepeatAJoint) {
  Entries entries = mixamoEntries();
  entries.emplace_back("hips", "Hips");
  const InputError error = errorOf(mappingText(entries));
  EXPECT_EQ(error.line(), entryLine(kCanonicalJointCount));
  EXPECT_NE(error.detail().find("repeats Hips"), std::string::npos) << error.detail();
}

TEST_F(MappingFileInvalid, RigJointNotInTheSkeletonIsReportedOnItsLine) {
  Entries entries = mixamoEntries();
  entries[2].second = "LeftKnie";
  const InputError error = errorOf(mappingText(entries));
  EXPECT_EQ(error.line(), entryLine(2));
  EXPECT_EQ(error.detail().rfind("the rig has no joint named \"LeftKnie\" (for LeftKnee;", 0), 0u) << error.detail();
}

TEST_F(MappingFileInvalid, RigJointNamesAreCaseSensitive) {
  Entries entries = mixamoEntries();
  entries[0].second = "hips";
  EXPECT_EQ(errorOf(mappingText(entries)).line(), entryLine(0));
}

TEST_F(MappingFileInvalid, NonStringValueIsReportedOnItsLine) {
  std::string text = mappingText(mixamoEntries());
  text.replace(text.find("\"Spine2\""), 8, "17");
  const InputError error = errorOf(text);
  EXPECT_EQ(error.line(), entryLine(10));
  EXPECT_NE(error.detail().find("as a string for \"Chest\""), std::string::npos) << error.detail();
}

TEST_F(MappingFileInvalid, MissingJointsAreAllListed) {
  Entries entries = mixamoEntries();
  std::erase_if(entries, [](const auto& entry) { return entry.first.ends_with("Toe") || entry.first == "Neck"; });
  const InputError error = errorOf(mappingText(entries));
  EXPECT_EQ(error.line(), 0);
  EXPECT_EQ(error.detail(), "the joint mapping is unusable: missing LeftToe, RightToe, Neck");
}

TEST_F(MappingFileInvalid, InconsistentChainIsRefused) {
  Entries entries = mixamoEntries();
  std::swap(entries[14].second, entries[15].second);  // LeftElbow <-> LeftWrist
  const InputError error = errorOf(mappingText(entries));
  EXPECT_EQ(error.detail(), "the joint mapping is unusable: LeftWrist 'LeftForeArm' does not hang below LeftElbow 'LeftHand'");
}

class MappingFileOnDisk : public ::testing::Test {
 protected:
  std::filesystem::path dir;
  void SetUp() override { dir = test::uniqueTempDir("mapping-file-invalid"); }
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(MappingFileOnDisk, MissingFileNamesThePath) {
  const std::filesystem::path missing = dir / "absent.json";
  try {
    loadJointMapping(missing, test::mixamoRig().skeleton);
    FAIL() << "loaded a missing file";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), missing.string());
    EXPECT_EQ(error.line(), 0);
    EXPECT_EQ(error.detail().rfind("cannot read the joint mapping file", 0), 0u) << error.detail();
  }
}

TEST_F(MappingFileOnDisk, DirectoryIsNotAMappingFile) {
  EXPECT_THROW(loadJointMapping(dir, test::mixamoRig().skeleton), InputError);
}

TEST_F(MappingFileOnDisk, HugeFileIsRefusedUnread) {
  const std::filesystem::path huge = dir / "huge.json";
  {
    std::ofstream out(huge, std::ios::binary);
    out << mappingText(mixamoEntries()) << std::string(2 << 20, ' ');
  }
  try {
    loadJointMapping(huge, test::mixamoRig().skeleton);
    FAIL() << "loaded a 2 MiB mapping file";
  } catch (const InputError& error) {
    EXPECT_EQ(error.line(), 0);
    EXPECT_NE(error.detail().find("under 1 MiB"), std::string::npos) << error.detail();
  }
}

TEST_F(MappingFileOnDisk, InvalidJsonInAFileGivesTheFileAndLine) {
  const std::filesystem::path file = dir / "broken.json";
  {
    std::ofstream out(file, std::ios::binary);
    out << "{\r\n  \"format\": \"motionstyle-joint-mapping\",\r\n  \"version\": 1,\r\n  \"joints\": {\r\n    \"Hips\" \"Hips\"\r\n  }\r\n}\r\n";
  }
  try {
    loadJointMapping(file, test::mixamoRig().skeleton);
    FAIL() << "loaded invalid JSON";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), file.string());
    EXPECT_EQ(error.line(), 5);
  }
}

}  // namespace
}  // namespace motionstyle
