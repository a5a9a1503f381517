#include "common/resource_paths.h"

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <system_error>

#ifndef MOTIONSTYLE_BUILD_TREE_DIR
#define MOTIONSTYLE_BUILD_TREE_DIR ""
#endif
#ifndef MOTIONSTYLE_SOURCE_RESOURCES_DIR
#define MOTIONSTYLE_SOURCE_RESOURCES_DIR ""
#endif

namespace motionstyle {
namespace {

namespace fs = std::filesystem;

bool isDirectory(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(path, error);
}

// Resolves symlinks where the path exists, so /usr/bin/../share and a symlinked build dir compare equal.
fs::path normalised(const fs::path& path) {
  std::error_code error;
  fs::path result = fs::weakly_canonical(path, error);
  return error ? path.lexically_normal() : result;
}

bool isInside(const fs::path& path, const fs::path& directory) {
  if (path.empty() || directory.empty()) return false;
  const fs::path child = normalised(path);
  const fs::path parent = normalised(directory);
  auto [parent_end, child_at] = std::mismatch(parent.begin(), parent.end(), child.begin(), child.end());
  // A trailing separator leaves an empty last element on the parent; it matches anything.
  return parent_end == parent.end() || (std::next(parent_end) == parent.end() && parent_end->empty());
}

// <resources>/models/<name><extension> if `name` is a valid network name and that file exists.
std::optional<fs::path> shippedModelsFile(const fs::path& resources, std::string_view name, std::string_view extension) {
  if (!isValidNetworkName(name)) return std::nullopt;
  const fs::path file = resources / "models" / (std::string(name) + std::string(extension));
  std::error_code error;
  if (!fs::is_regular_file(file, error)) return std::nullopt;
  return file;
}

}  // namespace

ResourceSearch currentResourceSearch() {
  ResourceSearch search;
  if (const char* value = std::getenv(kResourcesEnvironmentVariable); value && *value)
    search.override_directory = fs::path(value);
  std::error_code error;
  const fs::path executable = fs::read_symlink("/proc/self/exe", error);
  if (!error) search.executable = executable;
  search.build_tree = MOTIONSTYLE_BUILD_TREE_DIR;
  search.source_resources = MOTIONSTYLE_SOURCE_RESOURCES_DIR;
  return search;
}

bool isResourceDirectory(const fs::path& directory) {
  return !directory.empty() && isDirectory(directory / "models") && isDirectory(directory / "samples");
}

std::vector<fs::path> resourceCandidates(const ResourceSearch& search) {
  if (search.override_directory) return {*search.override_directory};
  std::vector<fs::path> candidates;
  if (!search.source_resources.empty() && isInside(search.executable, search.build_tree))
    candidates.push_back(search.source_resources);
  if (!search.executable.empty())
    candidates.push_back((search.executable.parent_path() / ".." / "share" / "motionstyle").lexically_normal());
  return candidates;
}

std::optional<fs::path> findResourceDirectory(const ResourceSearch& search) {
  for (const fs::path& candidate : resourceCandidates(search))
    if (isResourceDirectory(candidate)) return candidate;
  return std::nullopt;
}

std::optional<fs::path> resourceDirectory() { return findResourceDirectory(currentResourceSearch()); }

bool isValidNetworkName(std::string_view name) {
  if (name.empty() || name.size() > 128) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

std::optional<fs::path> shippedNetworkFile(const fs::path& resources, std::string_view name) {
  return shippedModelsFile(resources, name, kNetworkFileExtension);
}

std::optional<fs::path> shippedMemoryFile(const fs::path& resources, std::string_view name) {
  return shippedModelsFile(resources, name, ".memory");
}

std::vector<fs::path> shippedNetworkFiles(const fs::path& resources) {
  std::vector<fs::path> files;
  std::error_code error;
  fs::directory_iterator it(resources / "models", error);
  if (error) return files;
  for (const fs::directory_entry& entry : it) {
    const fs::path& path = entry.path();
    std::error_code type_error;
    if (path.extension() == kNetworkFileExtension && isValidNetworkName(path.stem().string()) &&
        entry.is_regular_file(type_error))
      files.push_back(path);
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::string describeResourceLookup(const ResourceSearch& search) {
  if (auto found = findResourceDirectory(search)) return "resources: " + found->string();
  std::string text = "no resources directory (a folder with models/ and samples/; looked in: ";
  const std::vector<fs::path> candidates = resourceCandidates(search);
  for (size_t i = 0; i < candidates.size(); ++i) text += (i ? ", " : "") + candidates[i].string();
  if (candidates.empty()) text += "nothing: the executable's location is unknown";
  text += search.override_directory ? "; set by $" : "; override with $";
  return text + kResourcesEnvironmentVariable + ")";
}

}  // namespace motionstyle
