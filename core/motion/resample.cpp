#include "motion/resample.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "motion/kinematics.h"

namespace motionstyle {
namespace {

constexpr double kMaxUpsampling = 100.0;      // target fps / source fps
constexpr double kRateTolerance = 1e-5;       // relative; BVH frame times are rounded (see resample.h)
constexpr double kFrameCountSlack = 1e-6;     // frames, absorbs rounding in the output frame count

void checkTiming(int source_frames, double source_frame_time, double target_fps) {
  if (source_frames < 1) throw std::invalid_argument("resample: the source has no frames");
  if (!(std::isfinite(source_frame_time) && source_frame_time > 0.0))
    throw std::invalid_argument("resample: source frame time must be positive and finite, got " +
                                std::to_string(source_frame_time));
  if (!(std::isfinite(target_fps) && target_fps > 0.0))
    throw std::invalid_argument("resample: target fps must be positive and finite, got " + std::to_string(target_fps));
  if (!(target_fps * source_frame_time <= kMaxUpsampling))
    throw std::invalid_argument("resample: target rate " + std::to_string(target_fps) + " fps is more than " +
                                std::to_string(static_cast<int>(kMaxUpsampling)) + " times the source rate " +
                                std::to_string(1.0 / source_frame_time) + " fps");
}

// `ratio` rounded to a whole number n >= 1 when it is one to within kRateTolerance (relative), else 0.
int wholeNumber(double ratio) {
  const double nearest = std::round(ratio);
  if (nearest < 1.0 || std::abs(ratio - nearest) > kRateTolerance * ratio) return 0;
  return nearest > 1e9 ? 1000000000 : static_cast<int>(nearest);  // caps keep the conversion defined
}

// Source frames per output frame when that is a whole number (2 = halving the rate), else 0.
int decimationStep(double source_frame_time, double target_fps) {
  return wholeNumber(1.0 / (source_frame_time * target_fps));
}

}  // namespace

std::vector<ResampleSample> resampleSchedule(int source_frames, double source_frame_time, double target_fps) {
  checkTiming(source_frames, source_frame_time, target_fps);
  const int last = source_frames - 1;
  const double output_per_source = source_frame_time * target_fps;  // <= kMaxUpsampling, checked
  std::vector<ResampleSample> schedule;
  if (const int n = decimationStep(source_frame_time, target_fps); n > 0) {
    schedule.resize(static_cast<size_t>(last / n + 1));
    for (size_t k = 0; k < schedule.size(); ++k) schedule[k] = {static_cast<int>(k) * n, 0.0};
    return schedule;
  }
  if (const int n = wholeNumber(output_per_source); n > 0) {  // n >= 2 here: exact subdivision
    schedule.resize(static_cast<size_t>(last) * static_cast<size_t>(n) + 1);
    for (size_t k = 0; k < schedule.size(); ++k)
      schedule[k] = {static_cast<int>(k / static_cast<size_t>(n)), static_cast<double>(k % static_cast<size_t>(n)) / n};
    return schedule;
  }
  const double count =
      std::floor(last * output_per_source * (1.0 + kRateTolerance) + kFrameCountSlack) + 1.0;
  schedule.resize(static_cast<size_t>(count));
  for (size_t k = 0; k < schedule.size(); ++k) {
    double position = static_cast<double>(k) / output_per_source;  // in source frames
    const double nearest = std::round(position);
    if (std::abs(position - nearest) < 1e-9) position = nearest;  // land exactly on shared frames
    if (position >= last) {
      schedule[k] = {last, 0.0};
      continue;
    }
    const double index = std::floor(position);
    schedule[k] = {static_cast<int>(index), position - index};
  }
  return schedule;
}

Motion resampleMotion(const Motion& motion, double target_fps) {
  motion.validate();
  const std::vector<ResampleSample> schedule = resampleSchedule(motion.frameCount(), motion.frame_time, target_fps);
  if (decimationStep(motion.frame_time, target_fps) == 1) return motion;

  Motion result;
  result.skeleton = motion.skeleton;
  result.source = motion.source;
  result.frame_time = 1.0 / target_fps;
  const auto frames = static_cast<Eigen::Index>(schedule.size());
  if (decimationStep(motion.frame_time, target_fps) > 1) {
    result.values.resize(frames, motion.values.cols());
    for (Eigen::Index k = 0; k < frames; ++k) result.values.row(k) = motion.values.row(schedule[static_cast<size_t>(k)].index);
    return result;
  }

  const LocalPoses source = localPoses(motion);
  LocalPoses target;
  target.frames = static_cast<int>(frames);
  target.joints = source.joints;
  target.rotations.resize(schedule.size() * static_cast<size_t>(source.joints));
  target.translations.resize(target.rotations.size());
  for (int k = 0; k < target.frames; ++k) {
    const ResampleSample sample = schedule[static_cast<size_t>(k)];
    for (int j = 0; j < source.joints; ++j) {
      if (sample.fraction == 0.0) {
        target.rotation(k, j) = source.rotation(sample.index, j);
        target.translation(k, j) = source.translation(sample.index, j);
        continue;
      }
      // Eigen's slerp takes the shortest path (it flips the second quaternion when the dot is negative).
      target.rotation(k, j) = source.rotation(sample.index, j).slerp(sample.fraction, source.rotation(sample.index + 1, j));
      target.translation(k, j) = (1.0 - sample.fraction) * source.translation(sample.index, j) +
                                 sample.fraction * source.translation(sample.index + 1, j);
    }
  }
  // Seed Euler continuity with the source's first frame, which output frame 0 coincides with.
  result.values = motion.values.topRows(1);
  setLocalPoses(target, result);
  return result;
}

Eigen::MatrixXd resampleRowsLinear(const Eigen::MatrixXd& rows, double source_frame_time, double target_fps) {
  if (rows.rows() > static_cast<Eigen::Index>(std::numeric_limits<int>::max()))
    throw std::invalid_argument("resample: too many frames");
  const std::vector<ResampleSample> schedule =
      resampleSchedule(static_cast<int>(rows.rows()), source_frame_time, target_fps);
  Eigen::MatrixXd result(static_cast<Eigen::Index>(schedule.size()), rows.cols());
  for (Eigen::Index k = 0; k < result.rows(); ++k) {
    const ResampleSample sample = schedule[static_cast<size_t>(k)];
    if (sample.fraction == 0.0)
      result.row(k) = rows.row(sample.index);
    else
      result.row(k) = (1.0 - sample.fraction) * rows.row(sample.index) + sample.fraction * rows.row(sample.index + 1);
  }
  return result;
}

}  // namespace motionstyle
