#pragma once
// Fixed-length training windows cut from clips, as in the paper ("Data Representation") and the 2016
// code: windows of 240 frames at 60 fps, overlapping by half (a step of 120).
//
// Window starts: 0, step, 2*step, ... while start < frames - window/8 (the 2016 rule: a last slice
// shorter than an eighth of a window is dropped, its frames are already in the previous window), and
// always at least one window. A slice shorter than the window is PADDED by repeating its first frame
// before it (half the padding, rounded up) and its last frame after it; the three root velocities of
// padded frames are set to zero (the padded poses stand still), contacts are repeated with the pose.

#include <Eigen/Core>
#include <vector>

#include "features/feature_statistics.h"
#include "nn/tensor.h"
#include "style/motion_dataset.h"

namespace motionstyle::style {

struct WindowOptions {
  int frames = 240;  // window length, frames at the feature rate; even and >= 2
  int step = 120;    // distance between window starts, >= 1

  // Throws std::invalid_argument unless frames is even and >= 2 and step >= 1.
  void validate() const;
};

// Real frames [start, start + length) of the clip used by one window; length <= window frames.
struct WindowSpan {
  int start = 0;
  int length = 0;
  bool operator==(const WindowSpan&) const = default;
};

// The spans of a clip of `clip_frames` (>= 1) frames, per the rule above.
std::vector<WindowSpan> windowSpans(int clip_frames, const WindowOptions& options);

// The span's frames padded to `window_frames` columns (rule above). values: rows x frames (66 feature
// rows, or 4 contact rows with zero_velocities = false).
Eigen::MatrixXd cutWindow(const Eigen::MatrixXd& values, const WindowSpan& span, int window_frames,
                          bool zero_velocities);

// Every window of a set of clips, normalised and laid out as one batch matrix (nn/tensor.h).
struct WindowSet {
  int frames = 0;                 // per window
  nn::Mat<float> values;          // 66 x (count * frames), NORMALISED (x - mean) / std
  nn::Mat<float> contacts;        // 4 x (count * frames), 0/1
  nn::Mat<float> bone_lengths;    // kBoneCount x count, reference cm (the clip's own bones)
  std::vector<int> clip_index;    // per window: index of its clip in the input vector
  std::vector<WindowSpan> spans;  // per window

  int count() const { return static_cast<int>(clip_index.size()); }
};

WindowSet makeWindows(const std::vector<MotionClip>& clips, const FeatureStatistics& statistics,
                      const WindowOptions& options);

// Gathers windows `indices` of `set` into a batch (columns in the order of `indices`).
nn::Mat<float> gatherWindows(const nn::Mat<float>& source, int frames, const std::vector<int>& indices);

}  // namespace motionstyle::style
