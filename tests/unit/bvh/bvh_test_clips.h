#pragma once
// Small BVH texts shared by the BVH tests, and helpers to derive broken variants from them.

#include <gtest/gtest.h>

#include <string>
#include <string_view>

#include "motion/motion.h"

namespace motionstyle::test {

// Three joints (root with 6 channels, a 3-channel joint, an End Site), two frames. Line numbers are
// referred to by the tests: 5 = root CHANNELS, 6 = JOINT Spine, 8 = Spine OFFSET, 9 = Spine CHANNELS,
// 15 = root '}', 16 = MOTION, 17 = Frames, 18 = Frame Time, 19-20 = frames.
inline constexpr std::string_view kTinyBvh =
    "HIERARCHY\n"
    "ROOT Hips\n"
    "{\n"
    "\tOFFSET 0 0 0\n"
    "\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    "\tJOINT Spine\n"
    "\t{\n"
    "\t\tOFFSET 0 10 0\n"
    "\t\tCHANNELS 3 Zrotation Xrotation Yrotation\n"
    "\t\tEnd Site\n"
    "\t\t{\n"
    "\t\t\tOFFSET 0 5 0\n"
    "\t\t}\n"
    "\t}\n"
    "}\n"
    "MOTION\n"
    "Frames: 2\n"
    "Frame Time: 0.0333333\n"
    "1 2 3 4 5 6 7 8 9\n"
    "1.5 2.5 3.5 4.5 5.5 6.5 7.5 8.5 9.5\n";

// `text` with its only occurrence of `from` replaced by `to` (fails the test if not exactly once).
inline std::string replaced(std::string_view text, std::string_view from, std::string_view to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string_view::npos) << "'" << from << "' not in the clip";
  EXPECT_EQ(text.find(from, at + 1), std::string_view::npos) << "'" << from << "' is in the clip twice";
  if (at == std::string_view::npos) return std::string(text);
  std::string result(text);
  result.replace(at, from.size(), to);
  return result;
}

// Every line terminator of `text` turned into CRLF.
inline std::string withCrlf(std::string_view text) {
  std::string result;
  for (char c : text) {
    if (c == '\n') result += '\r';
    result += c;
  }
  return result;
}

// Equal skeletons, frame times and values (exactly: the writer prints shortest round-trip decimals).
inline void expectSameMotion(const Motion& expected, const Motion& actual) {
  ASSERT_EQ(expected.skeleton.jointCount(), actual.skeleton.jointCount());
  for (int j = 0; j < expected.skeleton.jointCount(); ++j) {
    const Joint& a = expected.skeleton.joints[static_cast<size_t>(j)];
    const Joint& b = actual.skeleton.joints[static_cast<size_t>(j)];
    EXPECT_EQ(a.name, b.name) << "joint " << j;
    EXPECT_EQ(a.parent, b.parent) << a.name;
    EXPECT_EQ(a.end_site, b.end_site) << a.name;
    EXPECT_EQ(a.channels, b.channels) << a.name;
    EXPECT_EQ(a.offset, b.offset) << a.name;
  }
  EXPECT_EQ(expected.frame_time, actual.frame_time);
  ASSERT_EQ(expected.values.rows(), actual.values.rows());
  ASSERT_EQ(expected.values.cols(), actual.values.cols());
  EXPECT_TRUE(expected.values == actual.values) << "largest difference "
                                                << (expected.values - actual.values).cwiseAbs().maxCoeff();
}

}  // namespace motionstyle::test
