// BVH reader and writer on the licensed Bandai dataset (label "data"; skips when it is absent).
// Nothing from the dataset is written to disk: round trips stay in memory.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "bvh_test_clips.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

std::vector<std::filesystem::path> bvhFilesUnder(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".bvh") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(BvhBandai, EveryFileParsesAndRoundTripsExactly) {
  MOTIONSTYLE_REQUIRE_BANDAI(dir);
  const std::vector<std::filesystem::path> files = bvhFilesUnder(dir);
  ASSERT_GT(files.size(), 100u) << "expected the two Bandai datasets under " << dir;
  long long frames = 0;
  for (const std::filesystem::path& file : files) {
    SCOPED_TRACE(file.string());
    const Motion motion = readBvh(file);
    ASSERT_GT(motion.frameCount(), 0);
    // Bandai rigs carry 6 channels on every joint.
    for (const Joint& joint : motion.skeleton.joints) ASSERT_EQ(joint.channels.size(), joint.end_site ? 0u : 6u) << joint.name;
    EXPECT_NEAR(motion.fps(), 30.0, 0.01);
    test::expectSameMotion(motion, parseBvh(formatBvh(motion), file.string() + " (rewritten)"));
    if (HasFailure()) return;  // one broken file is enough detail
    frames += motion.frameCount();
  }
  RecordProperty("files", static_cast<int>(files.size()));
  RecordProperty("frames", static_cast<int>(frames));
}

}  // namespace
}  // namespace motionstyle
