#pragma once
// A command's outputs, checked before any work starts: nothing the user owns is overwritten by
// mistake, and a command either writes everything it was asked for or nothing (a failure discovered
// after an hour of training, or after the clip was written but before its metrics, leaves half).
//
// checkOutputPaths throws WriteError naming the output (the CLI's exit code 2: the user's path is the
// problem) when an output
// - is the same file as an input or as another output: same path, or the same file reached through a
//   symlink or a hard link (std::filesystem::equivalent), or a clip inside an input folder;
// - is a folder, or exists and is not a regular file (a device, a FIFO);
// - exists and is read-only, or lies in a folder that does not exist or cannot be written.
// Inputs that do not exist are not this check's business (reading them says so, with exit 2).

#include <filesystem>
#include <string>
#include <vector>

namespace motionstyle {

struct NamedPath {
  std::filesystem::path path;
  std::string role;  // how the user gave it, for the message: "--out", "--metrics", "the input clip"
};

void checkOutputPaths(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs);

// True if `a` and `b` name the same file: equivalent() when both exist, else the same absolute path
// once symlinks are followed (two outputs that do not exist yet).
bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace motionstyle
