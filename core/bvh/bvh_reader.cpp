#include "bvh/bvh_reader.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "bvh/bvh_chunked_reader.h"
#include "bvh/bvh_hierarchy.h"
#include "bvh/bvh_motion_section.h"
#include "bvh/bvh_text.h"
#include "common/errors.h"

namespace motionstyle {
namespace {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};

class FileByteSource final : public bvh_detail::ByteSource {
 public:
  FileByteSource(std::FILE* file, const std::string& name) : file_(file), name_(name) {}

  std::size_t read(char* buffer, std::size_t capacity) override {
    const std::size_t got = std::fread(buffer, 1, capacity, file_);
    if (std::ferror(file_)) throw InputError(name_, 0, std::string("cannot read: ") + std::strerror(errno));
    return got;
  }

 private:
  std::FILE* file_;
  const std::string& name_;
};

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
  if (!bvh_detail::equalsIgnoreCase(bvh_detail::trim(line), "HIERARCHY")) {
    std::string problem = "expected HIERARCHY as the first line, got " + bvh_detail::excerpt(bvh_detail::trim(line));
    if (const char* format = otherMotionFormat(prefix, name))
      problem += std::string(": this is ") + format +
                 ", not BVH; MotionStyle reads BVH (export the clip as BVH first, e.g. Blender's File > Export > "
                 "Motion Capture (.bvh))";
    throw InputError(name, number, problem);
  }
}

// The hierarchy and then the MOTION section, whichever way `cursor` holds the text.
Motion parseLines(bvh_detail::LineCursor& cursor, const std::string& source_name, int minimum_frames) {
  Motion motion;
  motion.source = source_name;
  motion.skeleton = bvh_detail::parseHierarchy(cursor, source_name);
  bvh_detail::parseMotionSection(cursor, source_name, minimum_frames, motion);
  try {
    motion.validate();  // the parser enforces all of this already; kept as the contract's last word
  } catch (const std::invalid_argument& error) {
    throw InputError(source_name, 0, error.what());
  }
  return motion;
}

}  // namespace

namespace bvh_detail {

Motion readBvhChunked(ByteSource& source, const std::string& source_name, int minimum_frames,
                      const ChunkedTextOptions& options) {
  LineCursor cursor(source, source_name, options);
  const std::string_view prefix = cursor.readAhead(kBvhSniffBytes);
  requireHierarchyFirst(prefix, prefix.size() < kBvhSniffBytes, source_name);  // a short read is the end
  return parseLines(cursor, source_name, minimum_frames);
}

}  // namespace bvh_detail

Motion readBvh(const std::filesystem::path& file, int minimum_frames) {
  const std::string name = file.string();
  std::error_code error;
  if (std::filesystem::is_directory(file, error)) throw InputError(name, 0, "cannot read: it is a directory");
  const std::unique_ptr<std::FILE, FileCloser> stream(std::fopen(file.c_str(), "rb"));
  if (!stream) throw InputError(name, 0, std::string("cannot read: ") + std::strerror(errno));

  bvh_detail::ChunkedTextOptions options;
  options.chunk_bytes = bvh_detail::kBvhReadChunkBytes;
  const std::uintmax_t size = std::filesystem::file_size(file, error);  // fails for devices and pipes
  if (!error) {
    if (size > kBvhMaxBytes) throw InputError(name, 0, bvh_detail::tooLargeDetail(std::to_string(size)));
    options.total_bytes = size;
  }
  FileByteSource source(stream.get(), name);
  return bvh_detail::readBvhChunked(source, name, minimum_frames, options);
}

Motion parseBvh(std::string_view text, const std::string& source_name, int minimum_frames) {
  if (text.size() > kBvhMaxBytes)
    throw InputError(source_name, 0, bvh_detail::tooLargeDetail(std::to_string(text.size())));
  bvh_detail::LineCursor cursor(text);
  return parseLines(cursor, source_name, minimum_frames);
}

const char* otherMotionFormat(std::string_view first_bytes, const std::string& name) {
  if (first_bytes.starts_with("Kaydara FBX Binary") || first_bytes.starts_with("; FBX")) return "an FBX file";
  if (first_bytes.starts_with("glTF")) return "a binary glTF file (.glb)";
  std::string extension = std::filesystem::path(name).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension == ".fbx") return "an FBX file";
  if (extension == ".gltf" || extension == ".glb") return "a glTF file";
  if (extension == ".c3d") return "a C3D marker file";
  if (extension == ".blend") return "a Blender scene";
  if (extension == ".ma" || extension == ".mb") return "a Maya scene";
  return nullptr;
}

}  // namespace motionstyle
