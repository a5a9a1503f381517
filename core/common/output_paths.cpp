#include "common/output_paths.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>
#include <set>

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

// True if `file` lies anywhere under `folder`; both comparable().
bool isInside(const std::filesystem::path& file, const std::filesystem::path& folder) {
  const auto [end, ignored] = std::mismatch(folder.begin(), folder.end(), file.begin(), file.end());
  return end == folder.end();
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

// `creatable`: folders already found creatable in this check (a batch writes many files into one).
void requireWritable(const NamedPath& output, std::set<std::filesystem::path>& creatable) {
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
  if (creatable.insert(folder).second) requireCreatableIn(folder, output);
}

// What identifies a file for sameFile, computed once per path: the device and inode of an existing
// file (symlinks and hard links meet there), else its absolute path with symlinks followed.
struct FileIdentity {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::filesystem::path path;  // for a file that does not exist (yet)

  explicit FileIdentity(const std::filesystem::path& file) {
    struct stat info {};
    if (::stat(file.c_str(), &info) == 0) {
      exists = true;
      device = info.st_dev;
      inode = info.st_ino;
    } else {
      path = comparable(file);
    }
  }

  bool operator==(const FileIdentity& other) const {
    if (exists && other.exists) return device == other.device && inode == other.inode;
    return !exists && !other.exists && path == other.path;
  }
};

}  // namespace

bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
  return FileIdentity(a) == FileIdentity(b);
}

// Each path is looked at once (a batch of N clips: N identities, not N^2 file-system calls).
void checkOutputPaths(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs) {
  std::vector<FileIdentity> input_identities;
  std::vector<std::optional<std::filesystem::path>> input_folders;  // comparable(input) when a folder
  for (const NamedPath& input : inputs) {
    input_identities.emplace_back(input.path);
    std::error_code error;
    input_folders.push_back(std::filesystem::is_directory(input.path, error)
                                ? std::optional<std::filesystem::path>(comparable(input.path))
                                : std::nullopt);
  }
  std::vector<FileIdentity> output_identities;
  std::set<std::filesystem::path> creatable_folders;
  for (size_t i = 0; i < outputs.size(); ++i) {
    const NamedPath& output = outputs[i];
    output_identities.emplace_back(output.path);
    const FileIdentity& identity = output_identities.back();
    std::optional<std::filesystem::path> resolved;  // comparable(output.path), when a folder asks
    for (size_t k = 0; k < inputs.size(); ++k) {
      const NamedPath& input = inputs[k];
      if (identity == input_identities[k])
        throw WriteError(output.path.string(), output.role + " is " + input.role + " (" + input.path.string() +
                                                   "): refusing to overwrite an input");
      if (!input_folders[k] || !identity.exists || !isClipFile(output.path)) continue;
      if (!resolved) resolved = comparable(output.path);
      if (isInside(*resolved, *input_folders[k]))
        throw WriteError(output.path.string(), output.role + " is a clip inside " + input.role + " (" +
                                                   input.path.string() + "): refusing to overwrite an input");
    }
    for (size_t j = 0; j < i; ++j)
      if (identity == output_identities[j])
        throw WriteError(output.path.string(), output.role + " and " + outputs[j].role +
                                                   " are the same file: each output needs its own");
    requireWritable(output, creatable_folders);
  }
}

}  // namespace motionstyle
