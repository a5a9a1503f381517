#pragma once
// Where MotionStyle's shipped data lives: the resources directory holding models/ (the default
// networks, *.net) and samples/ (the demo clips, *.bvh). Used by the CLI and the desktop app, so that
// both work from a build tree and after installation without any configuration.
//
// Lookup order (the first candidate that is a resources directory wins):
//   1. $MOTIONSTYLE_RESOURCES, if set and non-empty. It is authoritative: when it does not name a
//      resources directory, nothing else is tried (a mistyped override must not silently pick up
//      another copy of the data).
//   2. The source tree's resources/ folder, only when the running program lies inside the build tree
//      it was built in (both paths are compiled in). An installed copy of the same build never reads
//      the source tree, even on the machine that built it.
//   3. <directory of the executable>/../share/motionstyle: the install prefix (/usr/bin/motionstyle
//      -> /usr/share/motionstyle). The executable is read from /proc/self/exe.
// A "resources directory" is a directory with both a models/ and a samples/ subdirectory (either may
// be empty). Nothing here throws on a missing or unreadable path: absence is an empty optional.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace motionstyle {

inline constexpr const char* kResourcesEnvironmentVariable = "MOTIONSTYLE_RESOURCES";
inline constexpr const char* kNetworkFileExtension = ".net";
// The shipped loss network's name (models/loss_network.net); every other shipped network is a style.
inline constexpr const char* kShippedLossNetworkName = "loss_network";
// Its name before the loss network had one name (models/autoencoder.net); still accepted on the command line.
inline constexpr const char* kFormerShippedLossNetworkName = "autoencoder";

// The inputs of the lookup, separated from the process so that tests can describe any layout.
struct ResourceSearch {
  std::optional<std::filesystem::path> override_directory;  // $MOTIONSTYLE_RESOURCES (nullopt: unset or empty)
  std::filesystem::path executable;        // absolute path of the running program ("" if unknown)
  std::filesystem::path build_tree;        // the CMake build directory the program was built in
  std::filesystem::path source_resources;  // <source tree>/resources
};

// The search this process would do: the environment, /proc/self/exe and the compiled-in paths.
ResourceSearch currentResourceSearch();

// True if `directory` holds both models/ and samples/.
bool isResourceDirectory(const std::filesystem::path& directory);

// The candidates in lookup order (for error messages: "looked in ..."), whether or not they exist.
std::vector<std::filesystem::path> resourceCandidates(const ResourceSearch& search);

// The first candidate that is a resources directory, or nullopt.
std::optional<std::filesystem::path> findResourceDirectory(const ResourceSearch& search);

// findResourceDirectory(currentResourceSearch()).
std::optional<std::filesystem::path> resourceDirectory();

// A shipped network's name is its file name without ".net" ("elderly", "loss_network"): letters,
// digits, '_' and '-' only, so a name can never reach outside models/.
bool isValidNetworkName(std::string_view name);

// <resources>/models/<name>.net if `name` is valid and that file exists, else nullopt.
std::optional<std::filesystem::path> shippedNetworkFile(const std::filesystem::path& resources, std::string_view name);

// <resources>/models/<name>.memory (a loss network's reconstruction memory, style/reconstruction_memory.h)
// if `name` is valid and that file exists, else nullopt.
std::optional<std::filesystem::path> shippedMemoryFile(const std::filesystem::path& resources, std::string_view name);

// The shipped network files (<resources>/models/*.net with valid names), sorted by name. Empty if
// the folder is missing or unreadable.
std::vector<std::filesystem::path> shippedNetworkFiles(const std::filesystem::path& resources);

// A one-line account of the lookup for messages, e.g.
// "resources: /usr/share/motionstyle" or "no resources directory (looked in: A, B)".
std::string describeResourceLookup(const ResourceSearch& search);

}  // namespace motionstyle
