#pragma once
// Training and evaluation clips: BVH files found in folders, mapped to the canonical joints and turned
// into the paper's 66-value representation at 60 fps (features/representation.h), with their labels
// (clip_labels.h) and bone lengths.
//
// Bad data is reported as InputError naming the file: a folder without any .bvh file, a file the BVH
// reader rejects (including NaN values), a rig mapJoints cannot map, features that are not finite, a
// clip shorter than DatasetOptions::minimum_frames. In a folder, the default is to FAIL on the first bad
// file; BadFilePolicy::Skip skips it and records a warning instead (files named explicitly always
// fail, since the user asked for exactly that file).

#include <atomic>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "features/representation.h"
#include "style/clip_labels.h"

namespace motionstyle::style {

enum class BadFilePolicy { Fail, Skip };

struct DatasetOptions {
  FeatureOptions features;  // fps (default 60) and an optional unit override
  BadFilePolicy bad_files = BadFilePolicy::Fail;
  // Clips with fewer frames AT THE FEATURE RATE are rejected (InputError naming the file). Style clips
  // use the loss network's filter width (25): a shorter clip gives no full receptive field.
  int minimum_frames = 2;
  // Keep each clip's Motion (MotionClip::motion) for training-time augmentation (augmentation.h).
  bool keep_motion = false;
};

// The options for a STYLE clip: `base` with rig canonicalisation off (features/rig_canonicalisation.h:
// a style clip's girdle posture is part of its style) and at least `minimum_frames` frames (the loss
// network's filter width: a shorter clip gives no full receptive field).
DatasetOptions styleClipOptions(const DatasetOptions& base, int minimum_frames);

// One clip ready for training or evaluation (computed data; the BVH file is the editable source).
struct MotionClip {
  std::filesystem::path file;
  ClipLabels labels;
  MotionFeatures features;       // values 66 x frames (representation units), contacts 4 x frames
  Eigen::VectorXd bone_lengths;  // nn::kBoneCount (20): bone c-1 = canonical joint c to its parent, reference cm
  std::shared_ptr<const Motion> motion;  // the source, only with DatasetOptions::keep_motion (augmentation)

  int frameCount() const { return features.frameCount(); }
};

// The .bvh files (extension compared case-insensitively) named by `inputs`: a folder contributes every
// .bvh below it (recursively), a file itself. Folders are listed sorted by path, so the result is
// deterministic; files keep their position in `inputs`. Throws InputError naming the folder when a
// folder holds no .bvh file, or naming the path when it does not exist. A folder below an input folder
// that is one of `skipped_folders` (compared once symlinks are resolved) is not searched: a batch's
// output folder inside its input folder, whose clips are the last run's outputs, not inputs.
std::vector<std::filesystem::path> findBvhFiles(const std::vector<std::filesystem::path>& inputs,
                                                const std::vector<std::filesystem::path>& skipped_folders = {});

// Reads, maps and featurises one file. Throws InputError naming the file (see the top of this file).
MotionClip loadMotionClip(const std::filesystem::path& file, const DatasetOptions& options = {});

// The same for a clip already in memory (`file` names it in errors and gives its labels).
MotionClip makeMotionClip(const Motion& motion, const JointMapping& mapping, const std::filesystem::path& file,
                          const DatasetOptions& options = {});

// loadMotionClip over findBvhFiles(inputs). With BadFilePolicy::Skip, files from a folder that fail
// are skipped and a line "skipped FILE: reason" is appended to *warnings (if given); if every file is
// skipped, InputError. Polls `cancel` before each file (throws OperationCancelled) and calls
// on_file(done, total) after each one (for progress; may be empty).
std::vector<MotionClip> loadMotionClips(const std::vector<std::filesystem::path>& inputs,
                                        const DatasetOptions& options = {},
                                        std::vector<std::string>* warnings = nullptr,
                                        const std::atomic<bool>* cancel = nullptr,
                                        const std::function<void(int, int)>& on_file = {});

// Deterministic hold-out split for evaluation: with every = N >= 2, the files at positions N-1, 2N-1,
// ... of `files` (sorted order from findBvhFiles) are held out, the rest are for training; every = 0
// holds nothing out. Throws std::invalid_argument for every == 1 or < 0.
struct HoldoutSplit {
  std::vector<std::filesystem::path> training;
  std::vector<std::filesystem::path> held_out;
};
HoldoutSplit splitHoldout(const std::vector<std::filesystem::path>& files, int every);

}  // namespace motionstyle::style
