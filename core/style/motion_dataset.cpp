#include "style/motion_dataset.h"

#include <algorithm>
#include <stdexcept>

#include "bvh/bvh_reader.h"
#include "common/clip_files.h"
#include "common/errors.h"
#include "mapping/joint_mapping.h"
#include "nn/losses.h"
#include "style/cancellation.h"

namespace motionstyle::style {
namespace {

namespace fs = std::filesystem;

struct FoundFile {
  fs::path path;
  bool from_folder = false;
};

// The path with symlinks resolved, for comparing folders; the path itself when that fails.
fs::path resolvedFolder(const fs::path& folder) {
  std::error_code error;
  fs::path resolved = fs::weakly_canonical(folder, error);
  return error ? folder.lexically_normal() : resolved;
}

std::vector<FoundFile> findFiles(const std::vector<fs::path>& inputs, const std::vector<fs::path>& skipped_folders) {
  std::vector<fs::path> skipped;
  for (const fs::path& folder : skipped_folders) skipped.push_back(resolvedFolder(folder));
  std::vector<FoundFile> found;
  for (const fs::path& input : inputs) {
    std::error_code error;
    if (fs::is_directory(input, error)) {
      std::vector<fs::path> in_folder;
      for (fs::recursive_directory_iterator it(input, fs::directory_options::skip_permission_denied, error), end;
           !error && it != end; it.increment(error)) {
        if (it->is_directory(error) && !skipped.empty() &&
            std::find(skipped.begin(), skipped.end(), resolvedFolder(it->path())) != skipped.end()) {
          it.disable_recursion_pending();
          continue;
        }
        if (it->is_regular_file(error) && isClipFile(it->path())) in_folder.push_back(it->path());
      }
      if (error) throw InputError(input.string(), 0, "cannot list the folder: " + error.message());
      if (in_folder.empty()) throw InputError(input.string(), 0, "the folder holds no .bvh file (searched recursively)");
      std::sort(in_folder.begin(), in_folder.end());
      for (fs::path& file : in_folder) found.push_back({std::move(file), true});
    } else if (fs::is_regular_file(input, error)) {
      found.push_back({input, false});
    } else {
      throw InputError(input.string(), 0, "no such file or folder");
    }
  }
  return found;
}

}  // namespace

DatasetOptions styleClipOptions(const DatasetOptions& base, int minimum_frames) {
  DatasetOptions options = base;
  options.features.canonical_rig = false;
  options.minimum_frames = std::max(options.minimum_frames, minimum_frames);
  return options;
}

std::vector<fs::path> findBvhFiles(const std::vector<fs::path>& inputs, const std::vector<fs::path>& skipped_folders) {
  std::vector<fs::path> files;
  for (FoundFile& file : findFiles(inputs, skipped_folders)) files.push_back(std::move(file.path));
  return files;
}

MotionClip loadMotionClip(const fs::path& file, const DatasetOptions& options) {
  auto motion = std::make_shared<const Motion>(readBvh(file, /*minimum_frames=*/1));  // InputError with the line
  const JointMapping mapping = mapJoints(motion->skeleton, file.string());  // InputError naming the file
  MotionClip clip = makeMotionClip(*motion, mapping, file, options);
  if (options.keep_motion) clip.motion = std::move(motion);
  return clip;
}

MotionClip makeMotionClip(const Motion& motion, const JointMapping& mapping, const fs::path& file,
                          const DatasetOptions& options) {
  const std::string name = file.string();
  MotionClip clip;
  clip.file = file;
  clip.labels = parseClipLabels(file);
  try {
    clip.features = extractFeatures(motion, mapping, options.features);
  } catch (const std::invalid_argument& error) {  // e.g. an unknown unit override
    throw InputError(name, 0, error.what());
  }
  if (!clip.features.values.allFinite() || !clip.features.contacts.allFinite())
    throw InputError(name, 0, "the motion features are not finite (NaN or infinity): the clip's poses are "
                              "degenerate (coincident hips or shoulders?)");
  if (clip.frameCount() < options.minimum_frames)
    throw InputError(name, 0, "the clip is too short: " + std::to_string(clip.frameCount()) + " frames at " +
                                  std::to_string(static_cast<int>(options.features.fps)) + " fps, at least " +
                                  std::to_string(options.minimum_frames) + " needed");
  clip.bone_lengths = canonicalBoneLengths(clip.features.values).tail(nn::kBoneCount);
  return clip;
}

std::vector<MotionClip> loadMotionClips(const std::vector<fs::path>& inputs, const DatasetOptions& options,
                                        std::vector<std::string>* warnings, const std::atomic<bool>* cancel,
                                        const std::function<void(int, int)>& on_file) {
  std::vector<MotionClip> clips;
  const std::vector<FoundFile> files = findFiles(inputs, {});
  for (const FoundFile& file : files) {
    throwIfCancelled(cancel);
    try {
      clips.push_back(loadMotionClip(file.path, options));
    } catch (const InputError& error) {
      if (options.bad_files == BadFilePolicy::Fail || !file.from_folder) throw;
      if (warnings) warnings->push_back("skipped " + file.path.string() + ": " + error.detail());
    }
    if (on_file) on_file(static_cast<int>(&file - files.data()) + 1, static_cast<int>(files.size()));
  }
  if (clips.empty())
    throw InputError(inputs.empty() ? std::string() : inputs.front().string(), 0,
                     inputs.empty() ? "no input files or folders given" : "every .bvh file was skipped as unreadable");
  return clips;
}

HoldoutSplit splitHoldout(const std::vector<fs::path>& files, int every) {
  if (every < 0 || every == 1) throw std::invalid_argument("splitHoldout: every must be 0 (none) or >= 2");
  HoldoutSplit split;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const bool held = every > 0 && (i + 1) % static_cast<std::size_t>(every) == 0;
    (held ? split.held_out : split.training).push_back(files[i]);
  }
  return split;
}

}  // namespace motionstyle::style
