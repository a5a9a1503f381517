#include "bvh/bvh_line_cursor.h"

#include <algorithm>
#include <cstring>
#include <utility>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_text.h"
#include "common/errors.h"

namespace motionstyle::bvh_detail {
namespace {

constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";

// The last '\n' in [from, to), or nullptr.
const char* lastNewline(const char* from, const char* to) {
  while (to > from)
    if (*--to == '\n') return to;
  return nullptr;
}

}  // namespace

std::size_t StringByteSource::read(char* buffer, std::size_t capacity) {
  const std::size_t count = std::min(capacity, rest_.size());
  if (count > 0) std::memcpy(buffer, rest_.data(), count);
  rest_.remove_prefix(count);
  return count;
}

LineCursor::LineCursor(std::string_view text)
    : data_(text.data()), complete_(text.size()), exposed_(text.size()), end_(text.size()), at_end_(true), bom_checked_(true) {
  options_.total_bytes = text.size();
  options_.refuse_nul = false;
  if (!text.empty()) last_byte_ = text.back();
  if (text.substr(0, kByteOrderMark.size()) == kByteOrderMark) {
    begin_ = kByteOrderMark.size();
    skipped_bom_ = true;
  }
}

LineCursor::LineCursor(ByteSource& source, std::string source_name, const ChunkedTextOptions& options)
    : source_(&source), source_name_(std::move(source_name)), options_(options) {
  options_.chunk_bytes = std::max<std::size_t>(options_.chunk_bytes, 1);
}

bool LineCursor::next(std::string_view& line, int& number) {
  if (begin_ == complete_ && !fill()) return false;
  const char* begin = data_ + begin_;
  const std::size_t left = complete_ - begin_;
  const auto* newline = static_cast<const char*>(std::memchr(begin, '\n', left));
  const std::size_t length = newline ? static_cast<std::size_t>(newline - begin) : left;
  line = std::string_view(begin, length);
  begin_ += length + (newline ? 1 : 0);
  number = ++line_;
  return true;
}

bool LineCursor::nextNonBlank(std::string_view& line, int& number) {
  while (next(line, number))
    if (!trim(line).empty()) return true;
  return false;
}

std::string_view LineCursor::readAhead(std::size_t bytes) {
  if (source_ == nullptr) return {};
  while (end_ < bytes && readMore(bytes - end_)) {
  }
  return {data_, end_};
}

void LineCursor::consume(const char* to, int lines_read) {
  begin_ = static_cast<std::size_t>(to - data_);
  line_ = lines_read;
}

bool LineCursor::fill() {
  if (source_ == nullptr) return false;
  if (nul_offset_) failNul();
  while (exposed_ < end_ || readMore(options_.chunk_bytes)) {
    // Shows the parser the next chunk_bytes of what was read; complete lines become the window.
    const std::size_t from = exposed_;
    exposed_ = std::min(end_, exposed_ + options_.chunk_bytes);
    if (options_.refuse_nul) {
      if (const auto* nul = static_cast<const char*>(std::memchr(data_ + from, '\0', exposed_ - from))) {
        // The lines before the NUL's line stay readable: an error on them is reported first.
        nul_offset_ = dropped_ + static_cast<std::uintmax_t>(nul - data_);
        const char* newline = lastNewline(data_ + complete_, nul);
        if (newline != nullptr) complete_ = static_cast<std::size_t>(newline + 1 - data_);
        skipByteOrderMark();
        if (complete_ == begin_) failNul();
        return true;
      }
    }
    if (const char* newline = lastNewline(data_ + from, data_ + exposed_)) {
      complete_ = static_cast<std::size_t>(newline + 1 - data_);
      skipByteOrderMark();
      return true;  // not empty: the '\n' found comes after any byte order mark
    }
  }
  complete_ = end_;  // the last line, without a '\n'
  skipByteOrderMark();
  return complete_ > begin_;
}

std::uintmax_t LineCursor::bytesAfter(const char* p) const {
  const auto index = static_cast<std::size_t>(p - data_);
  if (!options_.total_bytes) return end_ - index;
  const std::uintmax_t offset = dropped_ + index;
  return *options_.total_bytes > offset ? *options_.total_bytes - offset : 0;
}

bool LineCursor::readMore(std::size_t bytes) {
  if (at_end_) return false;
  if (begin_ > 0) {  // what the parser has read is dropped, the unread rest moves to the front
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    dropped_ += begin_;
    complete_ -= begin_;
    exposed_ -= begin_;
    end_ -= begin_;
    begin_ = 0;
  }
  if (buffer_.size() < end_ + bytes) buffer_.resize(std::max(end_ + bytes, 2 * buffer_.size()));
  data_ = buffer_.data();
  const std::size_t got = source_->read(buffer_.data() + end_, bytes);
  if (got == 0) {
    at_end_ = true;
    return false;
  }
  end_ += got;
  last_byte_ = buffer_[end_ - 1];
  if (dropped_ + end_ > kBvhMaxBytes) throw InputError(source_name_, 0, tooLargeDetail("more"));
  return true;
}

// The first line is whole in the window once complete_ > 0: a mark would be its first 3 bytes.
void LineCursor::skipByteOrderMark() {
  if (bom_checked_ || complete_ == 0) return;
  bom_checked_ = true;
  if (std::string_view(data_, complete_).substr(0, kByteOrderMark.size()) == kByteOrderMark) {
    begin_ = kByteOrderMark.size();
    skipped_bom_ = true;
  }
}

void LineCursor::failNul() const {
  throw InputError(source_name_, line_ + 1,
                   "expected BVH text, got a NUL byte at offset " + std::to_string(*nul_offset_) +
                       " (a binary file or a device?)");
}

}  // namespace motionstyle::bvh_detail
