#include "style/training_windows.h"

#include <stdexcept>
#include <string>

#include "features/feature_layout.h"
#include "nn/compute_pool.h"

namespace motionstyle::style {

void WindowOptions::validate() const {
  if (frames < 2 || frames % 2 != 0) throw std::invalid_argument("window length must be even and >= 2");
  if (step < 1) throw std::invalid_argument("window step must be >= 1");
}

std::vector<WindowSpan> windowSpans(int clip_frames, const WindowOptions& options) {
  options.validate();
  if (clip_frames < 1) throw std::invalid_argument("windowSpans: a clip needs at least one frame");
  std::vector<WindowSpan> spans;
  const int last_start = clip_frames - options.frames / 8;  // starts must be below this
  for (int start = 0; start == 0 || start < last_start; start += options.step)
    spans.push_back({start, std::min(options.frames, clip_frames - start)});
  return spans;
}

Eigen::MatrixXd cutWindow(const Eigen::MatrixXd& values, const WindowSpan& span, int window_frames,
                          bool zero_velocities) {
  if (span.length < 1 || span.start < 0 || span.start + span.length > values.cols() || span.length > window_frames)
    throw std::invalid_argument("cutWindow: span outside the clip or longer than the window");
  const int padding = window_frames - span.length;
  const int before = padding / 2 + padding % 2;
  const int after = padding / 2;
  Eigen::MatrixXd window(values.rows(), window_frames);
  window.middleCols(before, span.length) = values.middleCols(span.start, span.length);
  for (int i = 0; i < before; ++i) window.col(i) = values.col(span.start);
  for (int i = 0; i < after; ++i) window.col(before + span.length + i) = values.col(span.start + span.length - 1);
  if (zero_velocities && values.rows() == kFeatureCount) {
    window.block(kSidewaysVelocity, 0, 3, before).setZero();
    window.block(kSidewaysVelocity, before + span.length, 3, after).setZero();
  }
  return window;
}

WindowSet makeWindows(const std::vector<MotionClip>& clips, const FeatureStatistics& statistics,
                      const WindowOptions& options) {
  options.validate();
  statistics.validate();
  WindowSet set;
  set.frames = options.frames;
  for (std::size_t c = 0; c < clips.size(); ++c)
    for (const WindowSpan& span : windowSpans(clips[c].frameCount(), options)) {
      set.clip_index.push_back(static_cast<int>(c));
      set.spans.push_back(span);
    }
  const Eigen::Index count = set.count();
  const Eigen::Index frames = options.frames;
  set.values.resize(kFeatureCount, count * frames);
  set.contacts.resize(kContactCount, count * frames);
  set.bone_lengths.resize(clips.empty() ? 0 : clips.front().bone_lengths.size(), count);
  for (Eigen::Index w = 0; w < count; ++w) {
    const MotionClip& clip = clips[static_cast<std::size_t>(set.clip_index[static_cast<std::size_t>(w)])];
    const WindowSpan& span = set.spans[static_cast<std::size_t>(w)];
    Eigen::MatrixXd values = cutWindow(clip.features.values, span, options.frames, true);
    statistics.normalize(values);
    set.values.middleCols(w * frames, frames) = values.cast<float>();
    set.contacts.middleCols(w * frames, frames) =
        cutWindow(clip.features.contacts, span, options.frames, false).cast<float>();
    if (clip.bone_lengths.size() != set.bone_lengths.rows())
      throw std::invalid_argument("makeWindows: clips disagree on the bone count");
    set.bone_lengths.col(w) = clip.bone_lengths.cast<float>();
  }
  return set;
}

nn::Mat<float> gatherWindows(const nn::Mat<float>& source, int frames, const std::vector<int>& indices) {
  nn::Mat<float> batch(source.rows(), static_cast<Eigen::Index>(indices.size()) * frames);
  nn::parallelItems(static_cast<long>(indices.size()), source.rows() * frames, [&](int begin, int end) {
    for (Eigen::Index i = begin; i < end; ++i)
      batch.middleCols(i * frames, frames) =
          source.middleCols(static_cast<Eigen::Index>(indices[static_cast<std::size_t>(i)]) * frames, frames);
  });
  return batch;
}

}  // namespace motionstyle::style
