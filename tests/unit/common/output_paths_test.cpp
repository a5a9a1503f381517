// checkOutputPaths: an output that is an input (by path, symlink, hard link, or a clip in an input
// folder) or another output, or that cannot be written, is refused before any work; outputs that can
// be written pass and nothing is left behind by the check.
#include "common/output_paths.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "common/errors.h"

namespace motionstyle {
namespace {

namespace fs = std::filesystem;

class OutputPathsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = fs::temp_directory_path() / ("motionstyle-outputs-" + std::to_string(::getpid()) + "-" +
                                           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(folder_);
    fs::create_directories(folder_ / "clips");
    std::ofstream(folder_ / "clips" / "in.bvh") << "HIERARCHY";
  }
  void TearDown() override { fs::remove_all(folder_); }

  // The message of the WriteError checkOutputPaths throws, or "" if it passes.
  static std::string refusal(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
    try {
      checkOutputPaths(inputs, outputs);
    } catch (const WriteError& error) {
      return error.what();
    }
    return "";
  }

  fs::path in() const { return folder_ / "clips" / "in.bvh"; }
  fs::path folder_;
};

TEST_F(OutputPathsTest, RefusesTheInputItself) {
  EXPECT_NE(refusal({{in(), "the input clip"}}, {{in(), "--out"}}).find("--out is the input clip"), std::string::npos);
  const fs::path spelled_differently = folder_ / "clips" / "." / ".." / "clips" / "in.bvh";
  EXPECT_NE(refusal({{in(), "the input clip"}}, {{spelled_differently, "--metrics"}}), "");
}

TEST_F(OutputPathsTest, RefusesTheInputThroughASymlinkOrAHardLink) {
  fs::create_symlink(in(), folder_ / "link.bvh");
  fs::create_hard_link(in(), folder_ / "hard.bvh");
  EXPECT_NE(refusal({{in(), "the input clip"}}, {{folder_ / "link.bvh", "--out"}}), "");
  EXPECT_NE(refusal({{in(), "the input clip"}}, {{folder_ / "hard.bvh", "--out"}}), "");
  EXPECT_NE(refusal({{folder_ / "link.bvh", "the input clip"}}, {{in(), "--out"}}), "");
}

TEST_F(OutputPathsTest, RefusesAClipInsideAnInputFolder) {
  EXPECT_NE(refusal({{folder_ / "clips", "--data"}}, {{in(), "--out"}}).find("inside --data"), std::string::npos);
  // A new file in the data folder, or a network file there, overwrites nothing.
  EXPECT_EQ(refusal({{folder_ / "clips", "--data"}}, {{folder_ / "clips" / "ae.net", "--out"}}), "");
}

TEST_F(OutputPathsTest, RefusesTwoOutputsThatAreOneFile) {
  const fs::path out = folder_ / "out.bvh";  // does not exist yet
  EXPECT_NE(refusal({{in(), "the input clip"}}, {{out, "--out"}, {folder_ / "." / "out.bvh", "--metrics"}})
                .find("--metrics and --out are the same file"),
            std::string::npos);
}

TEST_F(OutputPathsTest, RefusesPlacesThatCannotBeWritten) {
  EXPECT_NE(refusal({}, {{folder_ / "clips", "--out"}}).find("is a folder"), std::string::npos);
  EXPECT_NE(refusal({}, {{folder_ / "missing" / "out.bvh", "--out"}}).find("does not exist"), std::string::npos);
  EXPECT_NE(refusal({}, {{in() / "out.bvh", "--out"}}).find("is not a folder"), std::string::npos);
  EXPECT_NE(refusal({}, {{"/dev/null", "--metrics"}}).find("not a regular file"), std::string::npos);
  // Nobody can create files in /proc, root included (permission bits do not stop root).
  EXPECT_NE(refusal({}, {{"/proc/motionstyle-out.bvh", "--out"}}).find("cannot create a file"), std::string::npos);
}

TEST_F(OutputPathsTest, PassesWritableOutputsAndLeavesNothingBehind) {
  std::ofstream(folder_ / "old.bvh") << "previous result";
  EXPECT_EQ(refusal({{in(), "the input clip"}}, {{folder_ / "old.bvh", "--out"}, {folder_ / "new.json", "--metrics"}}), "");
  int entries = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(folder_)) ++entries;
  EXPECT_EQ(entries, 2);  // clips/ and old.bvh: the probe file is gone
}

TEST(SameFile, ComparesExistingAndNewPaths) {
  EXPECT_TRUE(sameFile("/tmp/../tmp/x-motionstyle-new", "/tmp/x-motionstyle-new"));
  EXPECT_FALSE(sameFile("/tmp/x-motionstyle-a", "/tmp/x-motionstyle-b"));
}

}  // namespace
}  // namespace motionstyle
