#pragma once
// Line-by-line access to a BVH text, whole in memory or read in chunks (internal to core/bvh).
//
// Line model (bvh_text.h): a line ends at '\n', '\r' is whitespace; line numbers are 1-based; a UTF-8
// byte order mark at the very start is skipped. Both modes give the very same lines and numbers.
//
// Chunked mode keeps in memory only the unread lines of the current chunk plus the incomplete line
// carried over to the next chunk: a buffer of about two chunks (or the longest line), whatever the
// text's length. Why: a 1M-frame clip must not cost its whole text (~1 KB per frame) on top of its
// values. The parser sees the text in `chunk_bytes` steps even where the cursor has read further
// ahead (readAhead), so tests with tiny chunks exercise every line split.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace motionstyle::bvh_detail {

// Where a chunked text comes from (a file, a pipe, a string in tests).
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  // Copies up to `capacity` (> 0) bytes into `buffer` and returns how many; 0 only at the end.
  // Throws InputError (line 0) if reading fails.
  virtual std::size_t read(char* buffer, std::size_t capacity) = 0;
};

// A string served `capacity` bytes at a time (no copy of the whole text is made).
class StringByteSource final : public ByteSource {
 public:
  explicit StringByteSource(std::string_view text) : rest_(text) {}
  std::size_t read(char* buffer, std::size_t capacity) override;

 private:
  std::string_view rest_;
};

struct ChunkedTextOptions {
  std::size_t chunk_bytes = std::size_t{1} << 20;  // bytes read (and handed to the parser) per step, > 0
  std::optional<std::uintmax_t> total_bytes;       // the text's size when known (a regular file)
  bool refuse_nul = true;  // InputError naming the line of a NUL byte, once the parser reaches that line
};

class LineCursor {
 public:
  // The whole text in memory: no copy, no NUL check, no size cap (the caller checks it).
  explicit LineCursor(std::string_view text);
  // The text read from `source` in chunks. `source_name` names the text in errors. Throws InputError
  // (line 0) once more than kBvhMaxBytes have been read.
  LineCursor(ByteSource& source, std::string source_name, const ChunkedTextOptions& options);

  // The next line (terminator excluded) and its number; false at the end of the text. The view stays
  // valid until the next call to next, nextNonBlank or fill.
  bool next(std::string_view& line, int& number);
  // The next line that is not blank; false at the end of the text.
  bool nextNonBlank(std::string_view& line, int& number);

  int linesRead() const { return line_; }
  // The line to name when the text ends too early: the last line (1 for an empty text).
  int lastLine() const { return line_ > 0 ? line_ : 1; }
  // True once a byte order mark was skipped (a text that has one is not empty).
  bool skippedByteOrderMark() const { return skipped_bom_; }

  // Chunked mode: reads until `bytes` are in memory (or the end) and returns the text's first bytes,
  // which the parser has not seen yet; call it before anything else. Empty in memory mode.
  std::string_view readAhead(std::size_t bytes);

  // The hot path (frame lines), which parses in place:
  // the unread complete lines (at the end of the text: all that is left, the last line unterminated).
  std::string_view window() const { return {data_ + begin_, complete_ - begin_}; }
  // The parser has read up to `to` (the start of a line inside window()) and `lines_read` lines in all.
  void consume(const char* to, int lines_read);
  // Replaces an exhausted window with the next complete lines; false at the end of the text. Throws
  // InputError naming the line when the next line holds a NUL byte, and as the constructor does.
  bool fill();

  // At the end of the text: whether its last byte is '\n' (true for an empty text).
  bool endsWithNewline() const { return last_byte_ == '\n'; }
  // Bytes after `p` (a pointer into window()): to the end of the text when its size is known, else
  // those already read. Bounds the frames still to come (a value takes at least 2 bytes).
  std::uintmax_t bytesAfter(const char* p) const;
  bool sizeKnown() const { return options_.total_bytes.has_value(); }

 private:
  bool readMore(std::size_t bytes);  // appends up to `bytes` from the source; false at its end
  void skipByteOrderMark();
  [[noreturn]] void failNul() const;

  // Buffer layout (indices into data_): [begin_, complete_) unread complete lines, [complete_, exposed_)
  // an incomplete line the parser was shown, [exposed_, end_) read but not yet shown.
  ByteSource* source_ = nullptr;  // null in memory mode
  std::string source_name_;
  ChunkedTextOptions options_;
  std::vector<char> buffer_;
  const char* data_ = nullptr;
  std::size_t begin_ = 0;
  std::size_t complete_ = 0;
  std::size_t exposed_ = 0;
  std::size_t end_ = 0;
  std::uintmax_t dropped_ = 0;  // bytes before data_[0] (already parsed and discarded)
  std::optional<std::uintmax_t> nul_offset_;  // a NUL byte found at this text offset, its line not reached yet
  bool at_end_ = false;                       // the source has no more bytes
  bool bom_checked_ = false;
  bool skipped_bom_ = false;
  char last_byte_ = '\n';
  int line_ = 0;
};

}  // namespace motionstyle::bvh_detail
