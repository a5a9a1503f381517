#include "common/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "common/errors.h"

namespace motionstyle {
namespace {

std::string temporaryPrefix(const std::filesystem::path& destination) {
  return "." + destination.filename().string() + ".tmp-";
}

std::filesystem::path temporarySibling(const std::filesystem::path& destination) {
  std::random_device entropy;
  std::ostringstream name;
  name << temporaryPrefix(destination) << ::getpid() << "-" << std::hex << entropy() << entropy();
  return destination.parent_path() / name.str();
}

// fsync so that the rename below can never expose a file whose data is still only in the page cache.
void syncToDisk(const std::filesystem::path& path, const std::filesystem::path& destination) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw WriteError(destination.string(), std::strerror(errno));
  const int status = ::fsync(fd);
  const int saved = errno;
  ::close(fd);
  if (status != 0) throw WriteError(destination.string(), std::strerror(saved));
}

// An existing destination's permission bits go to the temporary, so the rename keeps them.
void keepPermissions(const std::filesystem::path& temporary, const std::filesystem::path& destination) {
  struct stat existing {};
  if (::stat(destination.c_str(), &existing) != 0) return;  // a new file: 666 minus the umask
  if (::chmod(temporary.c_str(), existing.st_mode & 07777) != 0)
    throw WriteError(destination.string(), std::string("cannot copy its permissions: ") + std::strerror(errno));
}

// Only regular files are replaced: renaming over a device node (/dev/null, /dev/full) or a directory
// would destroy it rather than write to it.
void requireRegularOrAbsent(const std::filesystem::path& destination) {
  std::error_code status_error;
  const auto status = std::filesystem::status(destination, status_error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw WriteError(destination.string(), "it exists and is not a regular file");
}

// The process id in a temporary's name ".NAME.tmp-PID-RANDOM", or 0 if the name is not one of ours.
pid_t temporaryOwner(const std::string& name, const std::string& prefix) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
  const char* first = name.data() + prefix.size();
  const char* last = name.data() + name.size();
  long pid = 0;
  const auto [end, error] = std::from_chars(first, last, pid);
  if (error != std::errc() || end == first || end == last || *end != '-' || pid <= 0) return 0;
  return static_cast<pid_t>(pid);
}

}  // namespace

std::filesystem::path followSymlinks(const std::filesystem::path& path) {
  std::filesystem::path current = path;
  for (int hop = 0; hop < 40; ++hop) {
    std::error_code error;
    if (!std::filesystem::is_symlink(std::filesystem::symlink_status(current, error))) return current;
    const std::filesystem::path target = std::filesystem::read_symlink(current, error);
    if (error) return current;
    current = target.is_absolute() ? target : current.parent_path() / target;
  }
  throw WriteError(path.string(), "too many levels of symbolic links");
}

int removeStaleTemporaries(const std::filesystem::path& destination) {
  const std::string prefix = temporaryPrefix(destination);
  const std::filesystem::path folder = destination.parent_path().empty() ? "." : destination.parent_path();
  int removed = 0;
  std::error_code error;
  for (std::filesystem::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    const pid_t owner = temporaryOwner(it->path().filename().string(), prefix);
    if (owner == 0 || owner == ::getpid()) continue;
    if (::kill(owner, 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to signal: alive)
    std::error_code ignored;
    if (std::filesystem::remove(it->path(), ignored)) ++removed;
  }
  return removed;
}

AtomicFileBatch::~AtomicFileBatch() {
  for (const Staged& file : staged_) {
    std::error_code ignored;
    std::filesystem::remove(file.temporary, ignored);
  }
}

void AtomicFileBatch::stage(const std::filesystem::path& requested,
                            const std::function<void(std::ostream&)>& write) {
  const std::filesystem::path destination = followSymlinks(requested);
  requireRegularOrAbsent(destination);
  removeStaleTemporaries(destination);
  const std::filesystem::path temporary = temporarySibling(destination);
  try {
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out) throw WriteError(requested.string(), "cannot create " + temporary.string() + ": " +
                                                         std::strerror(errno));
      write(out);
      out.flush();
      if (!out) throw WriteError(requested.string(), "write failed (disk full?)");
      out.close();
      if (out.fail()) throw WriteError(requested.string(), "close failed (disk full?)");
    }
    keepPermissions(temporary, destination);
    if (durability_ == FileDurability::Synced) syncToDisk(temporary, requested);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  staged_.push_back({destination, temporary});
}

void AtomicFileBatch::stage(const std::filesystem::path& destination, std::string_view content) {
  stage(destination, [content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

void AtomicFileBatch::commit() {
  while (!staged_.empty()) {
    const Staged file = staged_.front();
    std::error_code error;
    std::filesystem::rename(file.temporary, file.destination, error);
    if (error) throw WriteError(file.destination.string(), "rename failed: " + error.message());
    staged_.erase(staged_.begin());
  }
}

void writeFileAtomically(const std::filesystem::path& destination,
                         const std::function<void(std::ostream&)>& write) {
  AtomicFileBatch batch;
  batch.stage(destination, write);
  batch.commit();
}

void writeFileAtomically(const std::filesystem::path& destination, std::string_view content,
                         FileDurability durability) {
  AtomicFileBatch batch(durability);
  batch.stage(destination, content);
  batch.commit();
}

}  // namespace motionstyle
