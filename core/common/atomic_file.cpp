#include "common/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "common/errors.h"

namespace motionstyle {
namespace {

std::filesystem::path temporarySibling(const std::filesystem::path& destination) {
  std::random_device entropy;
  std::ostringstream name;
  name << "." << destination.filename().string() << ".tmp-" << std::hex << entropy() << entropy();
  return destination.parent_path() / name.str();
}

// fsync so that the rename below can never expose a file whose data is still only in the page cache.
void syncToDisk(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw WriteError(path.string(), std::strerror(errno));
  const int status = ::fsync(fd);
  const int saved = errno;
  ::close(fd);
  if (status != 0) throw WriteError(path.string(), std::strerror(saved));
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& destination,
                         const std::function<void(std::ostream&)>& write) {
  // Only regular files are replaced: renaming over a device node (/dev/null, /dev/full) or a
  // directory would destroy it rather than write to it.
  std::error_code status_error;
  const auto status = std::filesystem::status(destination, status_error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw WriteError(destination.string(), "it exists and is not a regular file");
  const std::filesystem::path temporary = temporarySibling(destination);
  try {
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      if (!out) throw WriteError(destination.string(), "cannot create " + temporary.string() + ": " +
                                                           std::strerror(errno));
      write(out);
      out.flush();
      if (!out) throw WriteError(destination.string(), "write failed (disk full?)");
      out.close();
      if (out.fail()) throw WriteError(destination.string(), "close failed (disk full?)");
    }
    syncToDisk(temporary);
    std::error_code error;
    std::filesystem::rename(temporary, destination, error);
    if (error) throw WriteError(destination.string(), "rename failed: " + error.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
}

void writeFileAtomically(const std::filesystem::path& destination, std::string_view content) {
  writeFileAtomically(destination, [content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

}  // namespace motionstyle
