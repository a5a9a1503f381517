// Safe text (common/text_safety.h): valid UTF-8 without control characters; unsafe parts named, or
// replaced by U+FFFD.

#include <gtest/gtest.h>

#include <string>

#include "common/text_safety.h"

namespace motionstyle {
namespace {

const std::string kReplacement = "\xEF\xBF\xBD";

TEST(TextSafety, UnsafeBytesAreNamedWithTheirOffset) {
  EXPECT_EQ(textSafetyProblem("title\x1b]0;x\x07"), "control character 0x1b at byte 5");
  EXPECT_EQ(textSafetyProblem("a\tb"), "control character 0x09 at byte 1");
  EXPECT_EQ(textSafetyProblem("a\nb"), "control character 0x0a at byte 1");
  EXPECT_EQ(textSafetyProblem(std::string("nul\0", 4)), "control character 0x00 at byte 3");
  EXPECT_EQ(textSafetyProblem("del\x7f"), "control character 0x7f at byte 3");
  EXPECT_EQ(textSafetyProblem("csi\xc2\x9b"), "control character 0x9b at byte 3");  // C1
  EXPECT_EQ(textSafetyProblem("\xff"), "invalid UTF-8 at byte 0");
  EXPECT_EQ(textSafetyProblem("ab\xc3"), "invalid UTF-8 at byte 2");           // truncated
  EXPECT_EQ(textSafetyProblem("\xc0\xaf"), "invalid UTF-8 at byte 0");         // overlong
  EXPECT_EQ(textSafetyProblem("\xe0\x80\xaf"), "invalid UTF-8 at byte 0");     // overlong
  EXPECT_EQ(textSafetyProblem("\xed\xa0\x80"), "invalid UTF-8 at byte 0");     // surrogate
  EXPECT_EQ(textSafetyProblem("\xf4\x90\x80\x80"), "invalid UTF-8 at byte 0"); // above U+10FFFF
  EXPECT_EQ(textSafetyProblem("\x80"), "invalid UTF-8 at byte 0");             // lone continuation
}

TEST(TextSafety, SafeTextIsAcceptedUnchanged) {
  for (const std::string text : {"", "canonical-21-reference-rig", "Zoë_歩く.bvh", "non\xc2\xa0" "break", "\xf0\x9f\x92\x83",
                                 "\xf4\x8f\xbf\xbf", "2026-01-01 12:00 UTC"}) {
    EXPECT_EQ(textSafetyProblem(text), "") << text;
    EXPECT_EQ(safeText(text), text);
  }
}

TEST(TextSafety, SafeTextReplacesEachUnsafePart) {
  EXPECT_EQ(safeText("a\x1b]0;t\x07"), "a" + kReplacement + "]0;t" + kReplacement);
  EXPECT_EQ(safeText("caf\xe9"), "caf" + kReplacement);
  EXPECT_EQ(safeText("\xff\xfe"), kReplacement + kReplacement);
  EXPECT_EQ(safeText("x\xc2\x9by"), "x" + kReplacement + "y");
  const std::string once = safeText("\xed\xa0\x80\x1b ok \xc3");
  EXPECT_EQ(textSafetyProblem(once), "");
  EXPECT_EQ(safeText(once), once);
}

TEST(TextSafety, SafeLinesKeepsTheNewlinesOnly) {
  EXPECT_EQ(safeLines("one\ntwo\x1b\n\nthree\t"), "one\ntwo" + kReplacement + "\n\nthree" + kReplacement);
  EXPECT_EQ(safeLines(""), "");
  EXPECT_EQ(safeLines("\n"), "\n");
}

}  // namespace
}  // namespace motionstyle
