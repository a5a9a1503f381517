#include "bvh/bvh_reader.h"

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

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

// The whole file in one read: the parser then works on one contiguous buffer.
std::string readWholeFile(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code error;
  if (std::filesystem::is_directory(file, error)) throw InputError(name, 0, "cannot read: it is a directory");
  const std::unique_ptr<std::FILE, FileCloser> stream(std::fopen(file.c_str(), "rb"));
  if (!stream) throw InputError(name, 0, std::string("cannot read: ") + std::strerror(errno));

  std::string content;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  if (!error && size > kBvhMaxBytes)
    throw InputError(name, 0, "expected at most " + std::to_string(kBvhMaxBytes) + " bytes of BVH, got " + std::to_string(size));
  if (!error) {  // one read straight into the buffer the parser will walk
    content.resize(static_cast<std::size_t>(size));
    content.resize(std::fread(content.data(), 1, content.size(), stream.get()));
  }
  // Then read on until EOF rather than trusting the size: the file may have grown, or be a pipe.
  char buffer[1 << 16];
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, stream.get())) > 0;) {
    content.append(buffer, got);
    if (content.size() > kBvhMaxBytes)
      throw InputError(name, 0, "expected at most " + std::to_string(kBvhMaxBytes) + " bytes of BVH, got more");
  }
  if (std::ferror(stream.get())) throw InputError(name, 0, std::string("cannot read: ") + std::strerror(errno));
  return content;
}

}  // namespace

Motion readBvh(const std::filesystem::path& file) { return parseBvh(readWholeFile(file), file.string()); }

Motion parseBvh(std::string_view text, const std::string& source_name) {
  if (text.size() > kBvhMaxBytes)
    throw InputError(source_name, 0,
                     "expected at most " + std::to_string(kBvhMaxBytes) + " bytes of BVH, got " + std::to_string(text.size()));
  if (text.find_first_not_of(" \t\r\v\f\n") == std::string_view::npos)
    throw InputError(source_name, 1, "expected HIERARCHY, got an empty file");

  Motion motion;
  motion.source = source_name;
  bvh_detail::LineCursor cursor(text);
  motion.skeleton = bvh_detail::parseHierarchy(cursor, source_name);
  bvh_detail::parseMotionSection(cursor, source_name, motion);
  try {
    motion.validate();  // the parser enforces all of this already; kept as the contract's last word
  } catch (const std::invalid_argument& error) {
    throw InputError(source_name, 0, error.what());
  }
  return motion;
}

}  // namespace motionstyle
