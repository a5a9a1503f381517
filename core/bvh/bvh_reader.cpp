#include "bvh/bvh_reader.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "bvh/bvh_hierarchy.h"
#include "bvh/bvh_motion_section.h"
#include "bvh/bvh_text.h"
#include "common/errors.h"

namespace motionstyle {
namespace {

// What readBvh reads before it checks that the text starts like a BVH.
constexpr std::size_t kBvhSniffBytes = std::size_t{1} << 16;

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

std::string tooLarge(const std::string& got) {
  return "expected at most " + std::to_string(kBvhMaxBytes) + " bytes of BVH, got " + got;
}

// BVH is text: a NUL byte means a binary file or a device (/dev/zero). Names the line it is on.
void rejectNulBytes(const std::string& content, std::size_t from, const std::string& name) {
  const auto* nul = static_cast<const char*>(std::memchr(content.data() + from, '\0', content.size() - from));
  if (!nul) return;
  const auto offset = static_cast<std::ptrdiff_t>(nul - content.data());
  const int line = 1 + static_cast<int>(std::count(content.data(), nul, '\n'));
  throw InputError(name, line, "expected BVH text, got a NUL byte at offset " + std::to_string(offset) +
                                   " (a binary file or a device?)");
}

// The first non-blank line of every BVH is HIERARCHY (the parser demands it too): checked on the first
// kBvhSniffBytes so that a device or a binary file is refused before anything more is read.
void requireHierarchyFirst(std::string_view prefix, bool whole_file, const std::string& name) {
  bvh_detail::LineCursor cursor(prefix);
  std::string_view line;
  int number = 0;
  if (!cursor.nextNonBlank(line, number)) {
    if (whole_file) return;  // blank or empty: the parser says so
    throw InputError(name, cursor.lastLine(),
                     "expected HIERARCHY, got only blank lines in the first " + std::to_string(prefix.size()) + " bytes");
  }
  if (!bvh_detail::equalsIgnoreCase(bvh_detail::trim(line), "HIERARCHY"))
    throw InputError(name, number, "expected HIERARCHY as the first line, got " + bvh_detail::excerpt(bvh_detail::trim(line)));
}

// The whole file in one buffer, the parser then works on it contiguously. Reads the first
// kBvhSniffBytes, checks they start a BVH text (requireHierarchyFirst), then reads on to EOF, refusing
// NUL bytes and more than kBvhMaxBytes on the way: a device or a binary file costs one small read.
std::string readWholeFile(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code error;
  if (std::filesystem::is_directory(file, error)) throw InputError(name, 0, "cannot read: it is a directory");
  const std::unique_ptr<std::FILE, FileCloser> stream(std::fopen(file.c_str(), "rb"));
  if (!stream) throw InputError(name, 0, std::string("cannot read: ") + std::strerror(errno));

  const std::uintmax_t size = std::filesystem::file_size(file, error);  // fails for devices and pipes
  if (!error && size > kBvhMaxBytes) throw InputError(name, 0, tooLarge(std::to_string(size)));
  std::string content;
  auto readMore = [&](std::size_t bytes, bool check_nul) {  // appends up to `bytes`; false at EOF
    const std::size_t before = content.size();
    content.resize(before + bytes);
    content.resize(before + std::fread(content.data() + before, 1, bytes, stream.get()));
    if (std::ferror(stream.get())) throw InputError(name, 0, std::string("cannot read: ") + std::strerror(errno));
    if (check_nul) rejectNulBytes(content, before, name);
    return content.size() > before;
  };
  bool more = readMore(kBvhSniffBytes, /*check_nul=*/false);
  requireHierarchyFirst(content, content.size() < kBvhSniffBytes, name);  // a short read is the EOF
  rejectNulBytes(content, 0, name);
  // The rest: one read straight into the buffer when the size is known, then on until EOF rather than
  // trusting the size (the file may have grown, or be a pipe).
  if (more && !error && size > content.size()) more = readMore(static_cast<std::size_t>(size) - content.size(), true);
  while (more) {
    more = readMore(std::size_t{1} << 16, true);
    if (content.size() > kBvhMaxBytes) throw InputError(name, 0, tooLarge("more"));
  }
  return content;
}

}  // namespace

Motion readBvh(const std::filesystem::path& file, int minimum_frames) {
  return parseBvh(readWholeFile(file), file.string(), minimum_frames);
}

Motion parseBvh(std::string_view text, const std::string& source_name, int minimum_frames) {
  if (text.size() > kBvhMaxBytes) throw InputError(source_name, 0, tooLarge(std::to_string(text.size())));
  if (text.find_first_not_of(" \t\r\v\f\n") == std::string_view::npos)
    throw InputError(source_name, 1, "expected HIERARCHY, got an empty file");

  Motion motion;
  motion.source = source_name;
  bvh_detail::LineCursor cursor(text);
  motion.skeleton = bvh_detail::parseHierarchy(cursor, source_name);
  bvh_detail::parseMotionSection(cursor, source_name, minimum_frames, motion);
  try {
    motion.validate();  // the parser enforces all of this already; kept as the contract's last word
  } catch (const std::invalid_argument& error) {
    throw InputError(source_name, 0, error.what());
  }
  return motion;
}

}  // namespace motionstyle
