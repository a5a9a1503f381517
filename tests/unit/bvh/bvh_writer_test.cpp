// BVH writer: refusals and failed writes first, then the text it produces and read/write round trips.

#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "bvh_test_clips.h"
#include "common/errors.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

using test::expectSameMotion;
using test::kTinyBvh;

// A fresh, empty directory removed at the end of the test.
class BvhWriterFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    std::random_device entropy;
    dir_ = std::filesystem::temp_directory_path() / ("motionstyle-bvh-" + std::to_string(entropy()) + std::to_string(entropy()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static std::string contentOf(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream content;
    content << in.rdbuf();
    return content.str();
  }
  std::size_t entriesIn(const std::filesystem::path& dir) const {
    return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()));
  }

  std::filesystem::path dir_;
};

TEST(BvhWriterInvalid, RefusesMotionsTheReaderWouldReject) {
  Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  Motion no_channels = motion;
  no_channels.skeleton.joints[1].channels.clear();
  no_channels.values.conservativeResize(Eigen::NoChange, 6);
  EXPECT_THROW(formatBvh(no_channels), std::invalid_argument);

  Motion partial = motion;
  partial.skeleton.joints[1].channels.pop_back();
  partial.values.conservativeResize(Eigen::NoChange, 8);
  EXPECT_THROW(formatBvh(partial), std::invalid_argument);

  Motion bad_name = motion;
  bad_name.skeleton.joints[1].name = "Spine\nMOTION";
  EXPECT_THROW(formatBvh(bad_name), std::invalid_argument);
  bad_name.skeleton.joints[1].name = " Spine";
  EXPECT_THROW(formatBvh(bad_name), std::invalid_argument);

  Motion not_finite = motion;
  not_finite.values(1, 3) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(formatBvh(not_finite), std::invalid_argument);

  Motion bad_width = motion;
  bad_width.values.conservativeResize(Eigen::NoChange, 8);
  EXPECT_THROW(formatBvh(bad_width), std::invalid_argument);
}

TEST_F(BvhWriterFiles, FailedWriteIntoAMissingDirectoryThrowsWriteError) {
  const Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  const std::filesystem::path target = dir_ / "missing" / "out.bvh";
  EXPECT_THROW(writeBvh(motion, target), WriteError);
  EXPECT_FALSE(std::filesystem::exists(dir_ / "missing"));
  EXPECT_EQ(entriesIn(dir_), 0u);
}

TEST_F(BvhWriterFiles, FailedWriteOverADirectoryLeavesItUnchanged) {
  // Tests run as root, so a read-only directory would not stop the write; a directory in the way does.
  const Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  const std::filesystem::path target = dir_ / "out.bvh";
  std::filesystem::create_directory(target);
  std::ofstream(target / "keep.txt") << "keep me";
  EXPECT_THROW(writeBvh(motion, target), WriteError);
  EXPECT_TRUE(std::filesystem::is_directory(target));
  EXPECT_EQ(contentOf(target / "keep.txt"), "keep me");
  EXPECT_EQ(entriesIn(dir_), 1u) << "the temporary file was left behind";
}

TEST_F(BvhWriterFiles, RefusedMotionLeavesTheExistingFileUnchanged) {
  Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  const std::filesystem::path target = dir_ / "out.bvh";
  writeBvh(motion, target);
  const std::string before = contentOf(target);
  motion.values(0, 0) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(writeBvh(motion, target), std::invalid_argument);
  EXPECT_EQ(contentOf(target), before);
  EXPECT_EQ(entriesIn(dir_), 1u);
}

TEST(BvhWriter, StandardLayout) {
  const std::string text = formatBvh(parseBvh(test::withCrlf(kTinyBvh), "tiny.bvh"));
  // The canonical text: the tiny clip is written the way it was typed, except for the line endings.
  EXPECT_EQ(text, kTinyBvh);
}

TEST(BvhWriter, FrameTimeKeepsEnoughDigits) {
  Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  motion.frame_time = 1.0 / 120.0;
  const std::string text = formatBvh(motion);
  EXPECT_NE(text.find("Frame Time: 0.0083333333"), std::string::npos) << text;
  EXPECT_EQ(parseBvh(text, "120fps.bvh").frame_time, 1.0 / 120.0);
}

TEST(BvhWriter, ExtremeValuesRoundTripExactly) {
  Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  // The largest magnitudes the reader accepts (kBvhMaxMagnitude) and the smallest doubles.
  const double values[] = {1.87e-05, -0.0, 123456.123456789, -1e-300, 1e6, 0.1 + 0.2, 359.99999999, -1.0 / 3.0, 5e-324};
  for (int c = 0; c < 9; ++c) motion.values(1, c) = values[c];
  motion.skeleton.joints[1].offset = Eigen::Vector3d(1e-7, -98765.4321, 1.0 / 7.0);
  const std::string text = formatBvh(motion);
  for (std::size_t i = 1; i < text.size(); ++i)
    EXPECT_FALSE((text[i] == 'e' || text[i] == 'E') && std::isdigit(static_cast<unsigned char>(text[i - 1])))
        << "exponent notation at " << text.substr(i - 1, 10);
  expectSameMotion(motion, parseBvh(text, "extreme.bvh"));
}

TEST(BvhWriter, SkeletonNotInDepthFirstOrderIsWrittenDepthFirst) {
  // joints: root, A (root), B (root), A1 (A): valid, but a BVH file must list A1 right after A.
  Motion motion;
  motion.frame_time = 0.02;
  auto joint = [](std::string name, int parent, bool end_site) {
    Joint j;
    j.name = std::move(name);
    j.parent = parent;
    j.end_site = end_site;
    j.offset = Eigen::Vector3d(parent + 1.0, 0.0, 0.0);
    if (!end_site) j.channels = {ChannelType::Xrotation, ChannelType::Yrotation, ChannelType::Zrotation};
    return j;
  };
  motion.skeleton.joints = {joint("root", -1, false), joint("A", 0, false), joint("B", 0, false), joint("A1", 1, false),
                            joint("A1_End", 3, true)};
  motion.values.resize(2, 12);
  for (int f = 0; f < 2; ++f)
    for (int c = 0; c < 12; ++c) motion.values(f, c) = 100.0 * f + c;

  const Motion read = parseBvh(formatBvh(motion), "order.bvh");
  ASSERT_EQ(read.skeleton.jointCount(), 5);
  const char* expected_order[] = {"root", "A", "A1", "A1_End", "B"};
  for (int j = 0; j < 5; ++j) EXPECT_EQ(read.skeleton.joints[static_cast<size_t>(j)].name, expected_order[j]);
  EXPECT_EQ(read.skeleton.joints[4].parent, 0);
  // Each joint keeps its own values, wherever its columns moved.
  const std::vector<int> before = motion.skeleton.channelOffsets();
  const std::vector<int> after = read.skeleton.channelOffsets();
  for (const char* name : {"root", "A", "B", "A1"}) {
    const auto from = static_cast<size_t>(motion.skeleton.find(name));
    const auto to = static_cast<size_t>(read.skeleton.find(name));
    EXPECT_EQ(read.skeleton.joints[to].offset, motion.skeleton.joints[from].offset) << name;
    for (int f = 0; f < 2; ++f)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(read.values(f, after[to] + c), motion.values(f, before[from] + c)) << name;
  }
}

// read -> write -> read on the committed real-world clips, through the disk.
class BvhFixtureRoundTrip : public BvhWriterFiles, public ::testing::WithParamInterface<const char*> {};

TEST_P(BvhFixtureRoundTrip, ReproducesEverything) {
  const Motion original = readBvh(test::fixture(GetParam()));
  const std::filesystem::path copy = dir_ / GetParam();
  writeBvh(original, copy);
  const Motion reread = readBvh(copy);
  expectSameMotion(original, reread);  // exact, hence also within the required 1e-4
  EXPECT_EQ(formatBvh(reread), contentOf(copy)) << "writing is not stable";
  // Tabs for indentation, as importers expect.
  EXPECT_NE(contentOf(copy).find("\n\tJOINT "), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Fixtures, BvhFixtureRoundTrip, ::testing::Values("cmu_131_01.bvh", "zombie.bvh"));

}  // namespace
}  // namespace motionstyle
