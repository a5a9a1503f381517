#include "common/output_paths.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "common/atomic_file.h"
#include "common/clip_files.h"
#include "common/errors.h"

namespace motionstyle {
namespace {

std::filesystem::path comparable(const std::filesystem::path& path) {
  std::error_code error;
  std::filesystem::path resolved = std::filesystem::weakly_canonical(followSymlinks(path), error);
  if (error) resolved = std::filesystem::absolute(path, error).lexically_normal();
  return resolved;
}

// True if `file` (existing) lies anywhere under `folder`.
bool isInside(const std::filesystem::path& file, const std::filesystem::path& folder) {
  const std::filesystem::path f = comparable(file), d = comparable(folder);
  const auto [end, ignored] = std::mismatch(d.begin(), d.end(), f.begin(), f.end());
  return end == d.end();
}

// Creating a file is the only check that holds for every user and file system (root ignores
// permission bits; /proc and read-only mounts refuse anyway). The probe uses a temporary's name, so a
// kill between create and unlink leaves nothing the next write would not remove.
void requireCreatableIn(const std::filesystem::path& folder, const NamedPath& output) {
  const std::filesystem::path probe =
      folder / ("." + output.path.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-probe");
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int saved = errno;
    if (saved == EEXIST) return;  // our own probe from an earlier check in this process: creatable
    throw WriteError(output.path.string(), output.role + ": cannot create a file in the folder " + folder.string() +
                                               ": " + std::strerror(saved));
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

void requireWritable(const NamedPath& output) {
  const std::filesystem::path target = followSymlinks(output.path);
  std::error_code error;
  const auto status = std::filesystem::status(target, error);
  if (std::filesystem::is_directory(status))
    throw WriteError(output.path.string(), output.role + " is a folder; give a file name");
  if (std::filesystem::exists(status)) {
    if (!std::filesystem::is_regular_file(status))
      throw WriteError(output.path.string(), output.role + " exists and is not a regular file");
    if (::access(target.c_str(), W_OK) != 0)
      throw WriteError(output.path.string(), output.role + " is read-only (" + std::strerror(errno) + ")");
  }
  const std::filesystem::path folder = target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
  const auto folder_status = std::filesystem::status(folder, error);
  if (!std::filesystem::exists(folder_status))
    throw WriteError(output.path.string(), output.role + ": the folder " + folder.string() + " does not exist");
  if (!std::filesystem::is_directory(folder_status))
    throw WriteError(output.path.string(), output.role + ": " + folder.string() + " is not a folder");
  requireCreatableIn(folder, output);
}

}  // namespace

bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code error;
  if (std::filesystem::exists(a, error) && std::filesystem::exists(b, error)) {
    const bool same = std::filesystem::equivalent(a, b, error);
    return !error && same;
  }
  return comparable(a) == comparable(b);
}

void checkOutputPaths(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& output = outputs[i];
    for (const NamedPath& input : inputs) {
      std::error_code error;
      if (sameFile(output.path, input.path))
        throw WriteError(output.path.string(), output.role + " is " + input.role + " (" + input.path.string() +
                                                   "): refusing to overwrite an input");
      if (std::filesystem::is_directory(input.path, error) && isClipFile(output.path) &&
          std::filesystem::exists(output.path, error) && isInside(output.path, input.path))
        throw WriteError(output.path.string(), output.role + " is a clip inside " + input.role + " (" +
                                                   input.path.string() + "): refusing to overwrite an input");
    }
    for (size_t j = 0; j < i; ++j)
      if (sameFile(output.path, outputs[j].path))
        throw WriteError(output.path.string(), output.role + " and " + outputs[j].role +
                                                   " are the same file: each output needs its own");
    requireWritable(output);
  }
}

}  // namespace motionstyle
