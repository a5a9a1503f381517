#include "motion/resample.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/errors.h"
#include "motion/kinematics.h"

namespace motionstyle {
namespace {

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

}  // namespace

bool sameFrameRate(double a, double b) { return std::abs(a - b) <= kRateTolerance * b; }

namespace {

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

// The schedule for a matrix with one row per frame (resampleSchedule takes an int frame count).
std::vector<ResampleSample> rowSchedule(Eigen::Index frames, double source_frame_time, double target_fps) {
  if (frames > static_cast<Eigen::Index>(std::numeric_limits<int>::max()))
    throw std::invalid_argument("resample: too many frames");
  return resampleSchedule(static_cast<int>(frames), source_frame_time, target_fps);
}

}  // namespace

void requireResampleableTo(const Motion& motion, double target_fps) {
  if (target_fps * motion.frame_time <= kMaxUpsampling) return;
  char detail[200];
  std::snprintf(detail, sizeof detail, "cannot resample to %g fps: that is more than %g times the clip's %g fps (at most %g)",
                target_fps, kMaxUpsampling, motion.fps(), kMaxUpsampling * motion.fps());
  throw InputError(motion.source, 0, detail);
}

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

  const LocalPoses target = resampleLocalPoses(localPoses(motion), motion.frame_time, target_fps);
  // Seed Euler continuity with the source's first frame, which output frame 0 coincides with.
  result.values = motion.values.topRows(1);
  setLocalPoses(target, result);
  return result;
}

LocalPoses resampleLocalPoses(const LocalPoses& poses, double source_frame_time, double target_fps) {
  const size_t expected = static_cast<size_t>(std::max(poses.frames, 0)) * static_cast<size_t>(std::max(poses.joints, 0));
  if (poses.joints < 1 || poses.rotations.size() != expected || poses.translations.size() != expected)
    throw std::invalid_argument("resampleLocalPoses: poses of " + std::to_string(poses.frames) + " frames x " +
                                std::to_string(poses.joints) + " joints hold " + std::to_string(poses.rotations.size()) +
                                " rotations and " + std::to_string(poses.translations.size()) + " translations");
  const std::vector<ResampleSample> schedule = resampleSchedule(poses.frames, source_frame_time, target_fps);
  if (decimationStep(source_frame_time, target_fps) == 1) return poses;

  LocalPoses target;
  target.frames = static_cast<int>(schedule.size());
  target.joints = poses.joints;
  target.rotations.resize(schedule.size() * static_cast<size_t>(poses.joints));
  target.translations.resize(target.rotations.size());
  const auto joints = static_cast<size_t>(poses.joints);
  Eigen::ArrayXd inverse_norm(poses.joints);  // scratch of the midpoint normalisation
  for (int k = 0; k < target.frames; ++k) {
    const ResampleSample sample = schedule[static_cast<size_t>(k)];
    const size_t from = poses.at(sample.index, 0), to = target.at(k, 0);
    if (sample.fraction == 0.0) {
      std::copy_n(poses.rotations.begin() + static_cast<std::ptrdiff_t>(from), joints,
                  target.rotations.begin() + static_cast<std::ptrdiff_t>(to));
      std::copy_n(poses.translations.begin() + static_cast<std::ptrdiff_t>(from), joints,
                  target.translations.begin() + static_cast<std::ptrdiff_t>(to));
      continue;
    }
    const size_t next = from + joints;  // frame index + 1 (a fraction > 0 never samples the last frame)
    if (sample.fraction == 0.5) {
      // Normalised in a separate pass over all joints: the square roots and divisions then go
      // through vector instructions instead of one latency chain per joint.
      for (size_t j = 0; j < joints; ++j) {
        const Eigen::Vector4d& a = poses.rotations[from + j].coeffs();
        const Eigen::Vector4d& b = poses.rotations[next + j].coeffs();
        Eigen::Vector4d& sum = target.rotations[to + j].coeffs();
        sum = a.dot(b) < 0.0 ? Eigen::Vector4d(a - b) : Eigen::Vector4d(a + b);
        inverse_norm[static_cast<Eigen::Index>(j)] = sum.squaredNorm();
        target.translations[to + j] = 0.5 * poses.translations[from + j] + 0.5 * poses.translations[next + j];
      }
      inverse_norm = inverse_norm.sqrt().inverse();  // exact sqrt and division (rsqrt may be approximate)
      for (size_t j = 0; j < joints; ++j) target.rotations[to + j].coeffs() *= inverse_norm[static_cast<Eigen::Index>(j)];
      continue;
    }
    for (size_t j = 0; j < joints; ++j) {
      // Eigen's slerp takes the shortest path (it flips the second quaternion when the dot is negative).
      target.rotations[to + j] = poses.rotations[from + j].slerp(sample.fraction, poses.rotations[next + j]);
      target.translations[to + j] =
          (1.0 - sample.fraction) * poses.translations[from + j] + sample.fraction * poses.translations[next + j];
    }
  }
  return target;
}

Eigen::MatrixXd resampleRowsLinear(const Eigen::MatrixXd& rows, double source_frame_time, double target_fps) {
  const std::vector<ResampleSample> schedule = rowSchedule(rows.rows(), source_frame_time, target_fps);
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

Eigen::MatrixXi resampleRowsNearest(const Eigen::MatrixXi& rows, double source_frame_time, double target_fps) {
  const std::vector<ResampleSample> schedule = rowSchedule(rows.rows(), source_frame_time, target_fps);
  Eigen::MatrixXi result(static_cast<Eigen::Index>(schedule.size()), rows.cols());
  for (Eigen::Index k = 0; k < result.rows(); ++k) {
    const ResampleSample sample = schedule[static_cast<size_t>(k)];
    const int nearest = std::min(sample.index + (sample.fraction >= 0.5 ? 1 : 0), static_cast<int>(rows.rows()) - 1);
    result.row(k) = rows.row(nearest);
  }
  return result;
}

}  // namespace motionstyle
