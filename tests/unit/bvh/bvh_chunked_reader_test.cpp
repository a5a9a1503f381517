// BVH reader in chunks (readBvh's path): whatever the chunk size, and whether the text's size is known
// (a file) or not (a pipe), it must give parseBvh's Motion and parseBvh's errors on the same lines.
// Malformed input first, then the clips it must read identically.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bvh/bvh_chunked_reader.h"
#include "bvh/bvh_reader.h"
#include "bvh_test_clips.h"
#include "common/errors.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

using test::expectSameMotion;
using test::kTinyBvh;
using test::replaced;

const std::size_t kChunkSizes[] = {1, 7, 64, 4096};

struct ChunkedRead {
  std::size_t chunk_bytes;
  bool size_known;  // a regular file; otherwise a pipe
};

std::string describe(const ChunkedRead& read) {
  return "chunks of " + std::to_string(read.chunk_bytes) + " bytes, " + (read.size_known ? "size known" : "a pipe");
}

// Every chunk size, with and without a known size.
std::vector<ChunkedRead> everyRead() {
  std::vector<ChunkedRead> reads;
  for (std::size_t chunk : kChunkSizes)
    for (bool size_known : {true, false}) reads.push_back({chunk, size_known});
  return reads;
}

Motion readInChunks(std::string_view text, const ChunkedRead& read, int minimum_frames = 0) {
  bvh_detail::StringByteSource source(text);
  bvh_detail::ChunkedTextOptions options;
  options.chunk_bytes = read.chunk_bytes;
  if (read.size_known) options.total_bytes = text.size();
  return bvh_detail::readBvhChunked(source, "clip.bvh", minimum_frames, options);
}

// The error reading `text` in chunks gives, or nullopt if it is accepted.
std::optional<InputError> errorInChunks(std::string_view text, const ChunkedRead& read) {
  try {
    readInChunks(text, read);
  } catch (const InputError& error) {
    return error;
  }
  return std::nullopt;
}

// Every chunked read of `text` fails on `line` with a detail containing `needle`, and all with the
// very same message.
void expectRejectedInChunks(std::string_view text, int line, std::string_view needle) {
  std::optional<std::string> first_message;
  for (const ChunkedRead& read : everyRead()) {
    const std::optional<InputError> error = errorInChunks(text, read);
    ASSERT_TRUE(error.has_value()) << "accepted invalid input, " << describe(read);
    EXPECT_EQ(error->file(), "clip.bvh");
    EXPECT_EQ(error->line(), line) << error->what() << "\n" << describe(read);
    EXPECT_NE(error->detail().find(needle), std::string::npos) << error->detail() << "\n" << describe(read);
    if (!first_message) first_message = error->what();
    EXPECT_EQ(error->what(), *first_message) << describe(read);
  }
}

// As expectRejectedInChunks, and parseBvh (the text in memory) gives the same message.
void expectRejectedAsInMemory(std::string_view text, int line, std::string_view needle) {
  expectRejectedInChunks(text, line, needle);
  try {
    parseBvh(text, "clip.bvh");
    ADD_FAILURE() << "parseBvh accepted what the chunked reader refuses";
  } catch (const InputError& error) {
    const std::optional<InputError> chunked = errorInChunks(text, {4096, true});
    ASSERT_TRUE(chunked.has_value());
    EXPECT_STREQ(error.what(), chunked->what());
  }
}

std::string fixtureText(const char* name) {
  std::string text;
  std::FILE* file = std::fopen(test::fixture(name).c_str(), "rb");
  EXPECT_NE(file, nullptr) << name;
  if (file == nullptr) return text;
  char buffer[4096];
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, file)) > 0;) text.append(buffer, got);
  std::fclose(file);
  return text;
}

// The offset where line `line` (1-based) of `text` starts.
std::size_t lineStart(std::string_view text, int line) {
  std::size_t start = 0;
  for (int l = 1; l < line; ++l) start = text.find('\n', start) + 1;
  return start;
}

TEST(BvhChunkedReaderInvalid, SameErrorsAsInMemory) {
  expectRejectedAsInMemory("", 1, "empty file");
  expectRejectedAsInMemory(" \n\t\r\n\n", 1, "empty file");
  expectRejectedAsInMemory("\xEF\xBB\xBF\n", 1, "truncated hierarchy");
  expectRejectedAsInMemory("ROOT Hips\n{\n", 1, "expected HIERARCHY");
  expectRejectedAsInMemory(kTinyBvh.substr(0, kTinyBvh.find("\t\tEnd Site")), 9, "truncated hierarchy");
  expectRejectedAsInMemory(replaced(kTinyBvh, "JOINT Spine", "JOINT Hips"), 6, "first declared on line 2");
  expectRejectedAsInMemory(replaced(kTinyBvh, "Frames: 2", "Frames: two"), 17, "frame count");
  expectRejectedAsInMemory(replaced(kTinyBvh, "Frame Time: 0.0333333", "Frame Time: 0"), 18, "frame time");
  expectRejectedAsInMemory(test::withCrlf(replaced(kTinyBvh, "Frames: 2", "Frames: 1")), 20, "got more");
}

TEST(BvhChunkedReaderInvalid, FrameCountsThatDoNotMatchTheData) {
  const std::string three = replaced(kTinyBvh, "Frames: 2", "Frames: 3");
  expectRejectedAsInMemory(three, 20, "expected 3 frames");
  expectRejectedAsInMemory(three + "\n  \n", 22, "got 2");
  expectRejectedAsInMemory(three.substr(0, three.size() - 1), 21, "got 2");  // no '\n' after the last frame
  expectRejectedAsInMemory(replaced(kTinyBvh, "Frames: 2", "Frames: 1000000000"), 20, "expected 1000000000 frames");
  expectRejectedAsInMemory(std::string(kTinyBvh) + "\n\n1 2 3 4 5 6 7 8 9\n", 23, "got more");
}

TEST(BvhChunkedReaderInvalid, BadFrameLinesAtEveryChunkBoundary) {
  // Chunk sizes 1 to 120 split the tiny clip's frame lines at every offset, the bad value included.
  const std::string bad_value = replaced(kTinyBvh, "7.5", "7.5x");
  const std::string too_many = replaced(kTinyBvh, " 9.5\n", " 9.5 10.5\n");
  const std::string too_few = replaced(kTinyBvh, " 9.5\n", "\n");
  for (const std::string* text : {&bad_value, &too_many, &too_few}) {
    const std::string expected = [&] {
      try {
        parseBvh(*text, "clip.bvh");
      } catch (const InputError& error) {
        return std::string(error.what());
      }
      return std::string("accepted");
    }();
    ASSERT_NE(expected.find(":20:"), std::string::npos) << expected;
    for (std::size_t chunk = 1; chunk <= 120; ++chunk) {
      for (bool size_known : {true, false}) {
        const std::optional<InputError> error = errorInChunks(*text, {chunk, size_known});
        ASSERT_TRUE(error.has_value()) << chunk;
        EXPECT_EQ(error->what(), expected) << describe({chunk, size_known});
      }
    }
  }
}

TEST(BvhChunkedReaderInvalid, BadFrameLineAcrossA4096ByteBoundary) {
  // The CMU fixture (CRLF hierarchy, LF data) with garbage on the frame line that straddles a 4096-byte
  // boundary, inside the first 64 KiB (read ahead for the HIERARCHY check) and beyond.
  for (const std::size_t boundary : {std::size_t{16} * 4096, std::size_t{100} * 4096}) {
    std::string text = fixtureText("cmu_131_01.bvh");
    const auto at = static_cast<std::ptrdiff_t>(boundary);
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + at, '\n'));
    ASSERT_GE(line, 188) << "byte " << boundary << " must be in the frame data";
    ASSERT_LT(lineStart(text, line) + 3, boundary);
    ASSERT_NE(text[boundary - 1], '\n');
    text.insert(boundary - 1, "#");  // a value of that line turns into garbage
    expectRejectedAsInMemory(text, line, "expected a number");
  }

  std::string oops = fixtureText("cmu_131_01.bvh");
  oops.insert(lineStart(oops, 500), "oops ");
  expectRejectedAsInMemory(oops, 500, "got 'oops'");
}

TEST(BvhChunkedReaderInvalid, NulBytesAreRefusedOnTheirLine) {
  const std::string header = std::string(kTinyBvh.substr(0, kTinyBvh.find("MOTION"))) + "MOTION\n";
  expectRejectedInChunks(header + std::string(1000, '\0'), 17, "NUL byte at offset " + std::to_string(header.size()));
  // Inside a frame line, and one in the CMU data beyond the first 64 KiB read.
  const std::string in_frame = replaced(kTinyBvh, "7.5", std::string("7\0", 2));
  expectRejectedInChunks(in_frame, 20, "NUL byte at offset " + std::to_string(in_frame.find('\0')));
  std::string cmu = fixtureText("cmu_131_01.bvh");
  const std::size_t at = 300'000;
  cmu[at] = '\0';
  const int line = 1 + static_cast<int>(std::count(cmu.begin(), cmu.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
  expectRejectedInChunks(cmu, line, "NUL byte at offset 300000");
  // An error on an earlier line comes first; on the NUL's own line the NUL does.
  const std::string earlier = replaced(replaced(kTinyBvh, "3 4 5", "3 x 5"), "7.5", std::string("7\0", 2));
  expectRejectedInChunks(earlier, 19, "expected a number");
  expectRejectedInChunks(replaced(kTinyBvh, "6.5 7.5", std::string("x 7\0", 4)), 20, "NUL byte");
}

TEST(BvhChunkedReaderInvalid, TheFirst64KiBMustStartWithHierarchy) {
  expectRejectedInChunks(std::string(70'000, '\n') + std::string(kTinyBvh), 65536, "only blank lines in the first 65536 bytes");
  expectRejectedInChunks("\xEF\xBB\xBFROOT Hips\n", 1, "expected HIERARCHY as the first line, got 'ROOT Hips'");
}

// An endless source (/dev/zero, or a header followed by zeros): counts what the reader takes.
class EndlessSource final : public bvh_detail::ByteSource {
 public:
  explicit EndlessSource(std::string prefix) : prefix_(std::move(prefix)) {}
  std::size_t read(char* buffer, std::size_t capacity) override {
    for (std::size_t i = 0; i < capacity; ++i, ++served_) buffer[i] = served_ < prefix_.size() ? prefix_[served_] : '\0';
    return capacity;
  }
  std::size_t served() const { return served_; }

 private:
  std::string prefix_;
  std::size_t served_ = 0;
};

TEST(BvhChunkedReaderInvalid, EndlessNulBytesStopAtTheFirstChunk) {
  const std::string header = std::string(kTinyBvh.substr(0, kTinyBvh.find("MOTION")));
  for (const std::string& prefix : {std::string(), header}) {
    for (std::size_t chunk : {std::size_t{64}, std::size_t{1} << 20}) {
      EndlessSource source(prefix);
      bvh_detail::ChunkedTextOptions options;
      options.chunk_bytes = chunk;
      EXPECT_THROW(bvh_detail::readBvhChunked(source, "zeros", 0, options), InputError);
      EXPECT_LE(source.served(), bvh_detail::kBvhSniffBytes + chunk) << "chunks of " << chunk;
    }
  }
}

TEST(BvhChunkedReader, SameMotionAsInMemoryWhateverTheChunkSize) {
  std::vector<std::string> clips = {std::string(kTinyBvh), test::withCrlf(kTinyBvh), "\xEF\xBB\xBF" + std::string(kTinyBvh),
                                    std::string(kTinyBvh.substr(0, kTinyBvh.size() - 1)),  // no final '\n'
                                    fixtureText("cmu_131_01.bvh"), fixtureText("zombie.bvh")};
  std::string blank = replaced(kTinyBvh, "\t\tEnd Site\n", "\n\t\tEnd Site   \n\n");
  blank = replaced(blank, "1 2 3 4 5 6 7 8 9\n", "  1 2 3 4 5 6 7 8 9 \t\n\n\t\n");
  clips.push_back(blank + "\n\n   \n");
  clips.push_back(test::withCrlf(clips.back()));
  clips.push_back(replaced(kTinyBvh.substr(0, kTinyBvh.find("1 2 3")), "Frames: 2", "Frames: 0"));  // skeleton only
  clips.push_back(replaced(kTinyBvh, "1 2 3 4 5 6 7 8 9", "+1 .5 -.5 1.87e-05 -2E+2 1. 0.0000 -0 987654.125"));
  for (const std::string& clip : clips) {
    const Motion expected = parseBvh(clip, "clip.bvh");
    for (const ChunkedRead& read : everyRead()) {
      SCOPED_TRACE(describe(read) + ", clip of " + std::to_string(clip.size()) + " bytes");
      const Motion actual = readInChunks(clip, read);
      EXPECT_EQ(actual.source, "clip.bvh");
      expectSameMotion(expected, actual);
    }
  }
}

TEST(BvhChunkedReader, MinimumFramesAsInMemory) {
  for (const ChunkedRead& read : everyRead()) {
    EXPECT_EQ(readInChunks(kTinyBvh, read, 2).frameCount(), 2);
    EXPECT_THROW(readInChunks(kTinyBvh, read, 3), InputError);
  }
}

TEST(BvhChunkedReader, ReadBvhReadsTheFileAsParseBvhTheText) {
  for (const char* name : {"cmu_131_01.bvh", "zombie.bvh"}) {
    const Motion from_file = readBvh(test::fixture(name));
    expectSameMotion(parseBvh(fixtureText(name), name), from_file);
    EXPECT_EQ(from_file.values.rows(), from_file.frameCount());
  }
}

}  // namespace
}  // namespace motionstyle
