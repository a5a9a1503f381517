// Every clip of both licensed Bandai datasets maps to the same 21 joints (label "data"; skips when the
// dataset is absent). Only each file's header is parsed: the mapping never looks at the motion.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "bvh/bvh_reader.h"
#include "mapping/joint_mapping.h"
#include "mapping_test_rigs.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

// The HIERARCHY section of a BVH file followed by an empty MOTION section.
std::string headerOnly(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string header, line;
  while (std::getline(in, line)) {
    if (line.find("MOTION") != std::string::npos) break;
    header += line + "\n";
  }
  return header + "MOTION\nFrames: 0\nFrame Time: 0.008333\n";
}

void expectBandaiMapping(const Skeleton& skeleton, const JointMapping& mapping, const std::string& file) {
  const test::Expected expected = test::bandaiRig().expected;
  const auto names = test::mappedNames(mapping, skeleton);
  for (CanonicalJoint joint : kAllCanonicalJoints)
    EXPECT_EQ(names.at(joint), expected.at(joint)) << file << ": " << canonicalJointName(joint);
  EXPECT_EQ(mapping.convention, "bandai") << file;
}

class BandaiMapping : public ::testing::TestWithParam<std::string> {};

TEST_P(BandaiMapping, EveryHeaderMapsToTheBandaiJoints) {
  MOTIONSTYLE_REQUIRE_BANDAI(bandai);
  const std::filesystem::path data = bandai / GetParam() / "data";
  ASSERT_TRUE(std::filesystem::is_directory(data)) << data;
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(data)) {
    if (entry.path().extension() != ".bvh") continue;
    ++files;
    const std::string file = entry.path().string();
    const Motion motion = parseBvh(headerOnly(entry.path()), file);
    expectBandaiMapping(motion.skeleton, mapJoints(motion.skeleton, file), file);
    if (::testing::Test::HasFailure()) return;  // one broken file is enough to read about
  }
  EXPECT_GT(files, 0) << data;
  std::cout << GetParam() << ": mapped " << files << " clip headers\n";
}

TEST_P(BandaiMapping, AFullyReadClipMapsLikeItsHeader) {
  MOTIONSTYLE_REQUIRE_BANDAI(bandai);
  const std::filesystem::path data = bandai / GetParam() / "data";
  std::filesystem::path first;
  for (const auto& entry : std::filesystem::directory_iterator(data))
    if (entry.path().extension() == ".bvh" && (first.empty() || entry.path() < first)) first = entry.path();
  ASSERT_FALSE(first.empty());
  const Motion motion = readBvh(first);
  EXPECT_GT(motion.frameCount(), 0);
  expectBandaiMapping(motion.skeleton, mapJoints(motion.skeleton, motion.source), first.string());
}

INSTANTIATE_TEST_SUITE_P(BothDatasets, BandaiMapping, ::testing::Values("dataset-1", "dataset-2"),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = param_info.param;
                           std::erase(name, '-');
                           return name;
                         });

}  // namespace
}  // namespace motionstyle
