// BVH reader: what valid input turns into (hierarchy, channels, values, the formatting it tolerates).

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_text.h"
#include "bvh_test_clips.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

using test::expectSameMotion;
using test::kTinyBvh;
using test::replaced;

TEST(BvhReader, TinyClipHierarchy) {
  const Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  const Skeleton& skeleton = motion.skeleton;
  ASSERT_EQ(skeleton.jointCount(), 3);
  EXPECT_EQ(skeleton.joints[0].name, "Hips");
  EXPECT_EQ(skeleton.joints[0].parent, -1);
  EXPECT_EQ(skeleton.joints[1].name, "Spine");
  EXPECT_EQ(skeleton.joints[1].parent, 0);
  EXPECT_EQ(skeleton.joints[2].name, "Spine_End");
  EXPECT_EQ(skeleton.joints[2].parent, 1);
  EXPECT_TRUE(skeleton.joints[2].end_site);
  EXPECT_FALSE(skeleton.joints[1].end_site);
  EXPECT_TRUE(skeleton.joints[2].channels.empty());
  EXPECT_EQ(skeleton.joints[1].offset, Eigen::Vector3d(0, 10, 0));
  EXPECT_EQ(skeleton.joints[2].offset, Eigen::Vector3d(0, 5, 0));
  const std::vector<ChannelType> root = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition,
                                         ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
  EXPECT_EQ(skeleton.joints[0].channels, root);
  const std::vector<ChannelType> spine = {ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
  EXPECT_EQ(skeleton.joints[1].channels, spine);
}

TEST(BvhReader, TinyClipMotion) {
  const Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  EXPECT_EQ(motion.source, "tiny.bvh");
  EXPECT_EQ(motion.frame_time, 0.0333333);
  ASSERT_EQ(motion.frameCount(), 2);
  ASSERT_EQ(motion.values.cols(), 9);
  for (int c = 0; c < 9; ++c) {
    EXPECT_EQ(motion.values(0, c), c + 1.0);
    EXPECT_EQ(motion.values(1, c), c + 1.5);
  }
}

TEST(BvhReader, LineEndingsIndentationAndCaseDoNotMatter) {
  const Motion reference = parseBvh(kTinyBvh, "tiny.bvh");
  expectSameMotion(reference, parseBvh(test::withCrlf(kTinyBvh), "crlf.bvh"));

  std::string spaced(kTinyBvh);
  for (char& c : spaced)
    if (c == '\t') c = ' ';
  expectSameMotion(reference, parseBvh(spaced, "spaces.bvh"));

  std::string lower = replaced(kTinyBvh, "HIERARCHY", "hierarchy");
  lower = replaced(lower, "End Site", "end site");
  lower = replaced(lower, "Frame Time:", "FRAME TIME :");
  lower = replaced(lower, "Frames: 2", "frames:2");
  lower = replaced(lower, "CHANNELS 3 Zrotation", "channels 3 zrotation");
  expectSameMotion(reference, parseBvh(lower, "lower.bvh"));

  expectSameMotion(reference, parseBvh("\xEF\xBB\xBF" + std::string(kTinyBvh), "bom.bvh"));
}

TEST(BvhReader, NumberFormats) {
  std::string text = replaced(kTinyBvh, "1 2 3 4 5 6 7 8 9", "+1 .5 -.5 1.87e-05 -2E+2 1. 0.0000 -0 987654.125");
  text = replaced(text, "OFFSET 0 10 0", "OFFSET 1e1 -0.0 .25");
  text = replaced(text, "Frame Time: 0.0333333", "Frame Time: .0083333");
  const Motion motion = parseBvh(text, "numbers.bvh");
  const double expected[] = {1.0, 0.5, -0.5, 1.87e-05, -200.0, 1.0, 0.0, 0.0, 987654.125};
  for (int c = 0; c < 9; ++c) EXPECT_EQ(motion.values(0, c), expected[c]) << "value " << c + 1;
  EXPECT_TRUE(std::signbit(motion.values(0, 7)));
  EXPECT_EQ(motion.skeleton.joints[1].offset, Eigen::Vector3d(10, 0, 0.25));
  EXPECT_EQ(motion.frame_time, 0.0083333);
}

TEST(BvhReader, NumbersReadExactlyAsFromChars) {
  // The reader's fast path for short decimals must give the very double std::from_chars gives.
  std::mt19937_64 random(42);
  auto digits = [&](int count) {
    std::string text;
    for (int i = 0; i < count; ++i) text += static_cast<char>('0' + random() % 10);
    return text;
  };
  int compared = 0;
  for (int i = 0; i < 200'000; ++i) {
    std::string word = (random() % 2 ? "-" : "") + digits(static_cast<int>(random() % 12));
    if (random() % 4 != 0) word += "." + digits(static_cast<int>(random() % 12));
    if (random() % 5 == 0) word += (random() % 2 ? "e" : "E") + std::to_string(static_cast<int>(random() % 61) - 30);
    double expected = 0.0;
    const auto [stop, error] = std::from_chars(word.data(), word.data() + word.size(), expected);
    double actual = 0.0;
    const bvh_detail::NumberStatus status = bvh_detail::parseNumber(word, actual);
    if (error != std::errc() || stop != word.data() + word.size()) {
      EXPECT_NE(status, bvh_detail::NumberStatus::Ok) << word;
      continue;
    }
    ASSERT_EQ(status, bvh_detail::NumberStatus::Ok) << word;
    ASSERT_EQ(std::memcmp(&expected, &actual, sizeof(double)), 0) << word << ": " << expected << " vs " << actual;
    ++compared;
  }
  EXPECT_GT(compared, 150'000);
}

TEST(BvhReader, BlankLinesAndTrailingWhitespaceAreIgnored) {
  std::string text = replaced(kTinyBvh, "\t\tEnd Site\n", "\n\t\tEnd Site   \n\n");
  text = replaced(text, "1 2 3 4 5 6 7 8 9\n", "  1 2 3 4 5 6 7 8 9 \t\n\n\t\n");
  text += "\n\n   \n";
  expectSameMotion(parseBvh(kTinyBvh, "tiny.bvh"), parseBvh(text, "blank.bvh"));
  // No newline after the last frame.
  const std::string unterminated(kTinyBvh.substr(0, kTinyBvh.size() - 1));
  expectSameMotion(parseBvh(kTinyBvh, "tiny.bvh"), parseBvh(unterminated, "unterminated.bvh"));
}

TEST(BvhReader, ZeroFramesIsASkeletonOnlyFile) {
  const std::size_t data = kTinyBvh.find("1 2 3");
  const Motion motion = parseBvh(replaced(kTinyBvh.substr(0, data), "Frames: 2", "Frames: 0"), "rest.bvh");
  EXPECT_EQ(motion.frameCount(), 0);
  EXPECT_EQ(motion.values.cols(), 9);
  EXPECT_EQ(motion.skeleton.jointCount(), 3);
}

TEST(BvhReader, EndSiteNamesStayUnique) {
  // A real joint already called "Spine_End": the End Site of Spine must get another name.
  std::string text = replaced(kTinyBvh, "\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 5 0\n\t\t}\n",
                              "\t\tEnd Site\n\t\t{\n\t\t\tOFFSET 0 5 0\n\t\t}\n"
                              "\t\tJOINT Spine_End\n\t\t{\n\t\t\tOFFSET 1 0 0\n\t\t\tCHANNELS 3 Xrotation Yrotation Zrotation\n"
                              "\t\t\tEnd Site\n\t\t\t{\n\t\t\t\tOFFSET 1 0 0\n\t\t\t}\n\t\t}\n");
  text = replaced(text, "1 2 3 4 5 6 7 8 9\n", "1 2 3 4 5 6 7 8 9 10 11 12\n");
  text = replaced(text, " 9.5\n", " 9.5 10.5 11.5 12.5\n");
  const Motion motion = parseBvh(text, "names.bvh");
  ASSERT_EQ(motion.skeleton.jointCount(), 5);
  EXPECT_EQ(motion.skeleton.joints[2].name, "Spine_End2");
  EXPECT_TRUE(motion.skeleton.joints[2].end_site);
  EXPECT_EQ(motion.skeleton.joints[3].name, "Spine_End");
  EXPECT_EQ(motion.skeleton.joints[4].name, "Spine_End_End");
  EXPECT_EQ(motion.skeleton.joints[4].parent, 3);
}

TEST(BvhReader, JointNamesKeepInnerSpacesAndPunctuation) {
  std::string text = replaced(kTinyBvh, "JOINT Spine", "JOINT  mixamorig:Left Arm.001 \t");
  const Motion motion = parseBvh(text, "names.bvh");
  EXPECT_EQ(motion.skeleton.joints[1].name, "mixamorig:Left Arm.001");
  EXPECT_EQ(motion.skeleton.joints[2].name, "mixamorig:Left Arm.001_End");
}

TEST(BvhReader, ThreePositionChannelsOnly) {
  const std::string text = replaced(kTinyBvh, "CHANNELS 3 Zrotation Xrotation Yrotation", "CHANNELS 3 Xposition Yposition Zposition");
  const Motion motion = parseBvh(text, "positions.bvh");
  EXPECT_EQ(motion.skeleton.joints[1].channels[2], ChannelType::Zposition);
}

TEST(BvhReader, CapsAreInclusive) {
  // Exactly kBvhMaxDepth nested joints (the last one an End Site) is accepted.
  std::string text = "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 3 Xrotation Yrotation Zrotation\n";
  for (int j = 1; j < kBvhMaxDepth - 1; ++j)
    text += "JOINT j" + std::to_string(j) + "\n{\nOFFSET 0 0 1\nCHANNELS 3 Xrotation Yrotation Zrotation\n";
  text += "End Site\n{\nOFFSET 0 0 1\n}\n";
  for (int j = 0; j < kBvhMaxDepth - 1; ++j) text += "}\n";
  text += "MOTION\nFrames: 1\nFrame Time: 0.01\n";
  for (int c = 0; c < 3 * (kBvhMaxDepth - 1); ++c) text += "0 ";
  text += "\n";
  const Motion motion = parseBvh(text, "deep.bvh");
  EXPECT_EQ(motion.skeleton.jointCount(), kBvhMaxDepth);
  EXPECT_EQ(motion.values.cols(), 3 * (kBvhMaxDepth - 1));
}

TEST(BvhReader, CmuFixture) {
  const Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  EXPECT_EQ(motion.source, test::fixture("cmu_131_01.bvh").string());
  EXPECT_EQ(motion.frameCount(), 720);
  EXPECT_EQ(motion.frame_time, 0.0083333);
  EXPECT_NEAR(motion.fps(), 120.0, 0.01);
  const Skeleton& skeleton = motion.skeleton;
  EXPECT_EQ(skeleton.joints[0].name, "Hips");
  EXPECT_EQ(skeleton.joints[1].name, "LHipJoint");
  EXPECT_EQ(skeleton.joints[0].channels.size(), 6u);
  for (const Joint& joint : skeleton.joints) {
    if (joint.parent >= 0 && !joint.end_site) {
      EXPECT_EQ(joint.channels.size(), 3u) << joint.name;
    }
  }
  EXPECT_EQ(skeleton.joints[3].offset, Eigen::Vector3d(2.49329, -6.85026, 0.0));  // LeftKnee
  EXPECT_NE(skeleton.find("LeftToe_End"), -1);
  // First and last values of the trimmed data (lines 188 and 907 of the file).
  EXPECT_EQ(motion.values(0, 0), 5.23);
  EXPECT_EQ(motion.values(719, motion.values.cols() - 1), -0.7343);
}

TEST(BvhReader, ZombieFixture) {
  const Motion motion = readBvh(test::fixture("zombie.bvh"));
  EXPECT_EQ(motion.frameCount(), 300);
  EXPECT_EQ(motion.frame_time, 0.0333333);
  EXPECT_EQ(motion.skeleton.joints[0].name, "Hips");
  EXPECT_EQ(motion.skeleton.joints[1].name, "Spine");
  EXPECT_EQ(motion.skeleton.joints[1].offset, Eigen::Vector3d(0.0, 1.15266, 1.729));
  EXPECT_EQ(motion.values(0, 0), 0.1081);
  EXPECT_EQ(motion.values(0, 1), -113.8641);
}

}  // namespace
}  // namespace motionstyle
