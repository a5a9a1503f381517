// BVH reader: malformed input. Each case must raise InputError naming the file, the offending line and
// what was expected; never a crash, a hang or a huge allocation.

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "bvh/bvh_reader.h"
#include "bvh_test_clips.h"
#include "common/errors.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

using test::kTinyBvh;
using test::replaced;

// Parses `text` as "clip.bvh" and checks the InputError's line and that its detail mentions `needle`.
void expectRejected(std::string_view text, int line, std::string_view needle) {
  try {
    parseBvh(text, "clip.bvh");
    ADD_FAILURE() << "accepted invalid input; expected an error on line " << line << " about '" << needle << "'";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "clip.bvh");
    EXPECT_EQ(error.line(), line) << error.what();
    EXPECT_NE(error.detail().find(needle), std::string::npos) << "detail: " << error.detail() << "\nwanted: " << needle;
    EXPECT_NE(std::string(error.what()).find("clip.bvh"), std::string::npos) << error.what();
  }
}

// The tiny clip's hierarchy (lines 1-15) followed by `tail`.
std::string hierarchyThen(std::string_view tail) {
  const std::size_t motion = kTinyBvh.find("MOTION");
  return std::string(kTinyBvh.substr(0, motion)) + std::string(tail);
}

TEST(BvhReaderInvalid, EmptyOrBlankFile) {
  expectRejected("", 1, "empty file");
  expectRejected(" \n\t\r\n\n", 1, "empty file");
}

TEST(BvhReaderInvalid, FirstLineIsNotHierarchy) {
  expectRejected("ROOT Hips\n{\n", 1, "expected HIERARCHY");
  expectRejected("HIERARCHY extra\n", 1, "expected HIERARCHY");
}

TEST(BvhReaderInvalid, TruncatedHierarchy) {
  const std::size_t cut = kTinyBvh.find("\t\tEnd Site");  // ends after line 9
  expectRejected(kTinyBvh.substr(0, cut), 9, "truncated hierarchy");
  expectRejected("HIERARCHY\n", 1, "expected ROOT");
  expectRejected("HIERARCHY\nROOT Hips\n{\n\tOFFSET 0 0 0\n", 4, "expected CHANNELS");
}

TEST(BvhReaderInvalid, MissingMotionSection) {
  expectRejected(hierarchyThen(""), 15, "expected MOTION");
  expectRejected(hierarchyThen("Frames: 2\nFrame Time: 0.1\n"), 16, "expected MOTION");
  expectRejected(hierarchyThen("MOTION\n"), 16, "expected 'Frames: <count>'");
  expectRejected(hierarchyThen("MOTION\nFrames: 1\n"), 17, "expected 'Frame Time: <seconds>'");
  expectRejected(hierarchyThen("MOTION\nFrame Time: 0.1\nFrames: 1\n"), 17, "expected 'Frames: <count>'");
}

TEST(BvhReaderInvalid, FramesCountLargerThanTheData) {
  expectRejected(replaced(kTinyBvh, "Frames: 2", "Frames: 3"), 20, "expected 3 frames");
  expectRejected(replaced(kTinyBvh, "Frames: 2", "Frames: 3") + "\n  \n", 22, "got 2");
  expectRejected(hierarchyThen("MOTION\nFrames: 1\nFrame Time: 0.1\n"), 18, "got 0");
}

TEST(BvhReaderInvalid, FramesCountSmallerThanTheData) {
  expectRejected(replaced(kTinyBvh, "Frames: 2", "Frames: 1"), 20, "got more");
  expectRejected(replaced(kTinyBvh, "Frames: 2", "Frames: 0"), 19, "got more");
  expectRejected(std::string(kTinyBvh) + "\n\n1 2 3 4 5 6 7 8 9\n", 23, "got more");
}

TEST(BvhReaderInvalid, FramesCountIsNotACount) {
  expectRejected(replaced(kTinyBvh, "Frames: 2", "Frames: two"), 17, "frame count");
  expectRejected(replaced(kTinyBvh, "Frames: 2", "Frames: -2"), 17, "frame count");
  expectRejected(replaced(kTinyBvh, "Frames: 2", "Frames: 2.5"), 17, "frame count");
  expectRejected(replaced(kTinyBvh, "Frames: 2", "Frames: 99999999999"), 17, "frame count");
}

TEST(BvhReaderInvalid, NonNumericValues) {
  expectRejected(replaced(kTinyBvh, "7.5", "abc"), 20, "expected a number for Zrotation of joint 'Spine' (value 7 of 9)");
  expectRejected(replaced(kTinyBvh, "7.5", "7.5x"), 20, "got '7.5x'");
  expectRejected(replaced(kTinyBvh, "7.5", "7,5"), 20, "expected a number");
  expectRejected(replaced(kTinyBvh, "7.5", "--7"), 20, "expected a number");
  expectRejected(replaced(kTinyBvh, "7.5", "+-7"), 20, "expected a number");
  expectRejected(replaced(kTinyBvh, "OFFSET 0 10 0", "OFFSET 0 ten 0"), 8, "expected a number in OFFSET");
}

TEST(BvhReaderInvalid, NanAndInfinity) {
  expectRejected(replaced(kTinyBvh, "7.5", "nan"), 20, "expected a finite number");
  expectRejected(replaced(kTinyBvh, "7.5", "-inf"), 20, "expected a finite number");
  expectRejected(replaced(kTinyBvh, "7.5", "Infinity"), 20, "expected a finite number");
  expectRejected(replaced(kTinyBvh, "7.5", "1e999"), 20, "within double range");
  expectRejected(replaced(kTinyBvh, "OFFSET 0 10 0", "OFFSET 0 NaN 0"), 8, "expected a finite number in OFFSET");
  expectRejected(replaced(kTinyBvh, "Frame Time: 0.0333333", "Frame Time: nan"), 18, "positive, finite frame time");
  expectRejected(replaced(kTinyBvh, "Frame Time: 0.0333333", "Frame Time: inf"), 18, "positive, finite frame time");
}

TEST(BvhReaderInvalid, ZeroOrNegativeFrameTime) {
  expectRejected(replaced(kTinyBvh, "Frame Time: 0.0333333", "Frame Time: 0"), 18, "positive, finite frame time");
  expectRejected(replaced(kTinyBvh, "Frame Time: 0.0333333", "Frame Time: -0.0333333"), 18, "positive");
  expectRejected(replaced(kTinyBvh, "Frame Time: 0.0333333", "Frame Time:"), 18, "positive");
}

TEST(BvhReaderInvalid, FrameTimeOutsideThePhysicalRange) {
  // 1e-4 s (10 kHz) to 1 s (1 fps), see kBvhMinFrameTime: denormals and absurd rates stop on read.
  const std::string_view time = "Frame Time: 0.0333333";
  expectRejected(replaced(kTinyBvh, time, "Frame Time: 5e-324"), 18, "frame time from 0.0001 to 1 s");
  expectRejected(replaced(kTinyBvh, time, "Frame Time: 0.00009"), 18, "got '0.00009'");
  expectRejected(replaced(kTinyBvh, time, "Frame Time: 10"), 18, "frame time from 0.0001 to 1 s");
  expectRejected(replaced(kTinyBvh, time, "Frame Time: 1e308"), 18, "frame time from 0.0001 to 1 s");
  EXPECT_DOUBLE_EQ(parseBvh(replaced(kTinyBvh, time, "Frame Time: 1"), "clip.bvh").frame_time, 1.0);
  EXPECT_DOUBLE_EQ(parseBvh(replaced(kTinyBvh, time, "Frame Time: 0.0001"), "clip.bvh").frame_time, 1e-4);
}

TEST(BvhReaderInvalid, NonPhysicalValues) {
  // Beyond 1e6 file units or degrees (kBvhMaxMagnitude) nothing is a capture: refused with the line.
  expectRejected(replaced(kTinyBvh, "7.5", "1e308"), 20,
                 "expected a value within +-1000000 for Zrotation of joint 'Spine' (value 7 of 9), got '1e308'");
  expectRejected(replaced(kTinyBvh, "1.5 2.5", "-1000001 2.5"), 20, "within +-1000000 for Xposition");
  expectRejected(replaced(kTinyBvh, "OFFSET 0 10 0", "OFFSET 0 1e300 0"), 8, "within +-1000000 in OFFSET");
  expectRejected(replaced(kTinyBvh, "OFFSET 0 5 0", "OFFSET 0 5 -2e6"), 12, "within +-1000000 in OFFSET");
  const Motion at_bound = parseBvh(replaced(kTinyBvh, "7.5", "-1000000"), "clip.bvh");
  EXPECT_DOUBLE_EQ(at_bound.values(1, 6), -1e6);
}

TEST(BvhReaderInvalid, NoFramesWhereMotionIsNeeded) {
  // "Frames: 0" is a valid skeleton-only file, unless the caller needs motion: then the Frames line.
  const std::string skeleton_only = hierarchyThen("MOTION\nFrames: 0\nFrame Time: 0.0333333\n");
  EXPECT_EQ(parseBvh(skeleton_only, "clip.bvh").frameCount(), 0);
  try {
    parseBvh(skeleton_only, "clip.bvh", /*minimum_frames=*/1);
    ADD_FAILURE() << "accepted a clip without frames";
  } catch (const InputError& error) {
    EXPECT_EQ(error.line(), 17) << error.what();
    EXPECT_NE(error.detail().find("the clip has no frames"), std::string::npos) << error.detail();
  }
  EXPECT_EQ(parseBvh(kTinyBvh, "clip.bvh", 2).frameCount(), 2);
  EXPECT_THROW(parseBvh(kTinyBvh, "clip.bvh", 3), InputError);
}

TEST(BvhReaderInvalid, DevicesAndBinaryFilesStopAtTheFirstRead) {
  // /dev/zero never ends: the reader must stop at its first bytes (line 1), not at the 1 GiB cap.
  for (const char* device : {"/dev/zero", "/dev/urandom"}) {
    if (!std::filesystem::exists(device)) continue;
    try {
      readBvh(device);
      ADD_FAILURE() << "read " << device;
    } catch (const InputError& error) {
      EXPECT_EQ(error.file(), device);
      EXPECT_GE(error.line(), 1) << error.what();
    }
  }
  // A BVH that turns binary after its header: the NUL byte's line.
  const std::filesystem::path file = std::filesystem::temp_directory_path() / "motionstyle-nul-test.bvh";
  {
    std::FILE* out = std::fopen(file.c_str(), "wb");
    ASSERT_NE(out, nullptr);
    std::string text = std::string(kTinyBvh.substr(0, kTinyBvh.find("MOTION"))) + "MOTION\n";
    text.append(100000, '\0');
    std::fwrite(text.data(), 1, text.size(), out);
    std::fclose(out);
  }
  try {
    readBvh(file);
    ADD_FAILURE() << "read a file full of NUL bytes";
  } catch (const InputError& error) {
    EXPECT_EQ(error.line(), 17) << error.what();
    EXPECT_NE(error.detail().find("NUL byte"), std::string::npos) << error.detail();
  }
  std::filesystem::remove(file);
}

// Another tool's motion file dropped on the app or given to the CLI: the error names its format and
// what to do, by its magic bytes (whatever its name) or by its extension.
TEST(BvhReaderInvalid, AnotherFormatIsNamedWithWhatToDo) {
  const test::TempDir dir("other-formats");
  const std::vector<std::pair<std::string, std::string>> files = {
      {"take.fbx", "; FBX 7.4.0 project file\n"},
      {"named-as-bvh.bvh", std::string("Kaydara FBX Binary  \0\x1a\0", 23) + std::string(64, '\x01')},
      {"take.glb", std::string("glTF\x02\0\0\0", 8)},
      {"take.gltf", "{\n  \"asset\": {\"version\": \"2.0\"}\n}\n"},
      {"markers.c3d", "\x02P unused"}};
  for (const auto& [name, bytes] : files) {
    const std::filesystem::path file = dir / name;
    std::FILE* out = std::fopen(file.c_str(), "wb");
    ASSERT_NE(out, nullptr);
    std::fwrite(bytes.data(), 1, bytes.size(), out);
    std::fclose(out);
    try {
      readBvh(file);
      ADD_FAILURE() << "read " << name;
    } catch (const InputError& error) {
      EXPECT_EQ(error.file(), file.string());
      EXPECT_EQ(error.line(), 1) << error.what();
      EXPECT_NE(error.detail().find("not BVH; MotionStyle reads BVH"), std::string::npos) << error.detail();
    }
  }
  // A text file that is none of them keeps the parser's plain complaint.
  const std::filesystem::path notes = dir / "notes.bvh";
  std::FILE* out = std::fopen(notes.c_str(), "wb");
  ASSERT_NE(out, nullptr);
  std::fputs("shot 12, take 3\n", out);
  std::fclose(out);
  try {
    readBvh(notes);
    ADD_FAILURE() << "read notes.bvh";
  } catch (const InputError& error) {
    EXPECT_EQ(error.detail().find("not BVH"), std::string::npos) << error.detail();
  }
}

TEST(BvhReaderInvalid, DuplicateJointNames) {
  expectRejected(replaced(kTinyBvh, "JOINT Spine", "JOINT Hips"), 6, "first declared on line 2");
}

TEST(BvhReaderInvalid, JointWithZeroOrPartialChannels) {
  expectRejected(replaced(kTinyBvh, "CHANNELS 3 Zrotation Xrotation Yrotation", "CHANNELS 0"), 9,
                 "expected 3 or 6 channels on JOINT 'Spine', got 0");
  expectRejected(replaced(kTinyBvh, "CHANNELS 3 Zrotation Xrotation Yrotation", "CHANNELS 2 Zrotation Xrotation"), 9,
                 "expected 3 or 6 channels");
  expectRejected(replaced(kTinyBvh, "CHANNELS 3 Zrotation Xrotation Yrotation", "CHANNELS 3 Xposition Xrotation Yrotation"),
                 9, "3 rotation channels together");
  expectRejected(replaced(kTinyBvh, "CHANNELS 3 Zrotation Xrotation Yrotation", "CHANNELS 3 Zrotation Xrotation Zrotation"),
                 9, "'Zrotation' twice");
}

TEST(BvhReaderInvalid, HeaderClaimingAMillionNestedJoints) {
  std::string text = "HIERARCHY\nROOT j0\n{\n\tOFFSET 0 0 0\n\tCHANNELS 3 Xrotation Yrotation Zrotation\n";
  for (int j = 1; j < 1'000'000; ++j)
    text += "JOINT j" + std::to_string(j) + "\n{\nOFFSET 0 0 1\nCHANNELS 3 Xrotation Yrotation Zrotation\n";
  // j1000, the first joint at depth 1001, is declared on line 6 + 4 * 999.
  expectRejected(text, 4002, "nested at most 1000 deep");
}

TEST(BvhReaderInvalid, HeaderClaimingTooManyJoints) {
  std::string text = "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 3 Xrotation Yrotation Zrotation\n";
  for (int j = 1; j < 20'000; ++j)
    text += "JOINT j" + std::to_string(j) + "\n{\nOFFSET 0 0 1\nCHANNELS 3 Xrotation Yrotation Zrotation\n}\n";
  // j10000, the 10001st joint, is declared on line 6 + 5 * 9999.
  expectRejected(text, 50001, "at most 10000 joints");
}

TEST(BvhReaderInvalid, HeaderClaimingABillionFrames) {
  // Must fail on the data, not try to allocate a billion frames (8 bytes x 9 channels x 1e9 = 72 GB).
  expectRejected(replaced(kTinyBvh, "Frames: 2", "Frames: 1000000000"), 20, "expected 1000000000 frames");
  expectRejected(replaced(kTinyBvh, "Frames: 2", "Frames: 2147483647"), 20, "got 2");
}

TEST(BvhReaderInvalid, BinaryGarbage) {
  std::mt19937 random(1234);
  std::string garbage(4096, '\0');
  for (char& c : garbage) c = static_cast<char>(random() & 0xFF);
  garbage[0] = '\x7F';  // a line that is not blank
  expectRejected(garbage, 1, "expected HIERARCHY");
  expectRejected(std::string("HIERARCHY\0\x01\xFF", 13), 1, "expected HIERARCHY");
  // Garbage in the middle of the frames is reported on its line, with the bytes escaped.
  expectRejected(replaced(kTinyBvh, "7.5", std::string("\x01\xFE\0", 3)), 20, "got '\\x01\\xFE\\x00'");
}

TEST(BvhReaderInvalid, UnknownChannelName) {
  expectRejected(replaced(kTinyBvh, "CHANNELS 3 Zrotation Xrotation Yrotation", "CHANNELS 3 Zrotation Wrotation Yrotation"),
                 9, "expected a channel name (Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation), got 'Wrotation'");
}

TEST(BvhReaderInvalid, ChannelsCountDiffersFromTheNamesListed) {
  expectRejected(replaced(kTinyBvh, "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation",
                          "CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation"),
                 5, "expected 6 channel names as CHANNELS states, got 5");
  expectRejected(replaced(kTinyBvh, "CHANNELS 3 Zrotation", "CHANNELS 2 Zrotation"), 9, "expected 2 channel names");
  expectRejected(replaced(kTinyBvh, "CHANNELS 3 Zrotation", "CHANNELS Zrotation"), 9, "channel count");
}

TEST(BvhReaderInvalid, MissingBraces) {
  expectRejected(replaced(kTinyBvh, "\tJOINT Spine\n\t{\n", "\tJOINT Spine\n"), 7, "expected '{' after JOINT 'Spine'");
  expectRejected(replaced(kTinyBvh, "\t\t}\n\t}\n}\n", "\t\t}\n\t}\n"), 15, "closing joint 'Hips' (opened on line 2)");
  expectRejected(replaced(kTinyBvh, "\t}\n}\n", "\t}\n}\n}\n"), 16, "unbalanced braces");
}

TEST(BvhReaderInvalid, OffsetWithTwoNumbers) {
  expectRejected(replaced(kTinyBvh, "OFFSET 0 10 0", "OFFSET 0 10"), 8, "expected 3 numbers after OFFSET, got 2");
  expectRejected(replaced(kTinyBvh, "OFFSET 0 10 0", "OFFSET 0 10 0 0"), 8, "expected 3 numbers after OFFSET, got 4");
  expectRejected(replaced(kTinyBvh, "\t\tOFFSET 0 10 0\n", ""), 8, "expected OFFSET x y z of JOINT 'Spine'");
}

TEST(BvhReaderInvalid, WrongNumberOfValuesOnAFrameLine) {
  expectRejected(replaced(kTinyBvh, " 9.5\n", "\n"), 20, "expected 9 values on frame line 2, got 8");
  expectRejected(replaced(kTinyBvh, " 9.5\n", " 9.5 10.5\n"), 20, "got more ('10.5' is value 10)");
}

TEST(BvhReaderInvalid, StructureErrors) {
  expectRejected(replaced(kTinyBvh, "}\nMOTION", "}\nROOT Other\nMOTION"), 16, "only one ROOT");
  expectRejected(replaced(kTinyBvh, "JOINT Spine", "JOINT"), 6, "expected a name after JOINT");
  expectRejected(replaced(kTinyBvh, "JOINT Spine", "JOINT Spine {"), 6, "no braces");
  expectRejected(replaced(kTinyBvh, "\t\tEnd Site\n", "\t\tEnd Site\n\t\tJOINT Tip\n"), 11, "expected '{' after End Site");
  expectRejected(replaced(kTinyBvh, "\t\t\tOFFSET 0 5 0\n", "\t\t\tOFFSET 0 5 0\n\t\t\tCHANNELS 3 Xrotation Yrotation Zrotation\n"),
                 13, "closing the End Site");
  expectRejected(replaced(kTinyBvh, "JOINT Spine", "BONE Spine"), 6, "expected JOINT, End Site or '}'");
}

TEST(BvhReaderInvalid, UnreadableFile) {
  const std::filesystem::path missing = std::filesystem::temp_directory_path() / "motionstyle-no-such-file.bvh";
  try {
    readBvh(missing);
    ADD_FAILURE() << "read a file that does not exist";
  } catch (const InputError& error) {
    EXPECT_EQ(error.line(), 0);
    EXPECT_EQ(error.file(), missing.string());
    EXPECT_NE(error.detail().find("cannot read"), std::string::npos) << error.detail();
  }
  EXPECT_THROW(readBvh(std::filesystem::temp_directory_path()), InputError);
}

TEST(BvhReaderInvalid, ErrorLinesCountMixedLineEndings) {
  // The CMU fixture has CRLF in its hierarchy and LF in its data: a line number must still be what an
  // editor shows. Line 500 is frame 313 (the data starts on line 188).
  std::string text;
  {
    const Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));  // must parse as committed
    ASSERT_EQ(motion.frameCount(), 720);
  }
  std::FILE* file = std::fopen(test::fixture("cmu_131_01.bvh").c_str(), "rb");
  ASSERT_NE(file, nullptr);
  char buffer[4096];
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, file)) > 0;) text.append(buffer, got);
  std::fclose(file);
  std::size_t line_start = 0;
  for (int line = 1; line < 500; ++line) line_start = text.find('\n', line_start) + 1;
  text.insert(line_start, "oops ");
  expectRejected(text, 500, "got 'oops'");
}

}  // namespace
}  // namespace motionstyle
