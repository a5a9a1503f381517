#pragma once
// What the tools take for a motion clip file: the .bvh extension, in any case ("walk.BVH" too). One
// rule for listing folders (style/motion_dataset.h, the CLI's batch mode) and for the output checks
// (common/output_paths.h).

#include <cctype>
#include <filesystem>
#include <string>

namespace motionstyle {

inline bool isClipFile(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".bvh";
}

}  // namespace motionstyle
