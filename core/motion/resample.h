#pragma once
// Frame-rate conversion of motions and per-frame matrices (computed results from editable data).
//
// Timing: source frame f is at time f * source_frame_time seconds; the output covers
// [0, (N - 1) * source_frame_time] with frames at k / target_fps, k = 0 .. M - 1, where
//   M = floor((N - 1) * source_frame_time * target_fps) + 1,
// and nothing is extrapolated (a sample that would fall past the last source frame takes it).
//
// BVH files round the frame time (".0083333" for 120 fps is 4e-6 off 1/120, ".0333333" for 30 fps
// 1e-6), so rates are compared to within 1e-5 relative:
//   - same rate: resampleMotion returns an identical copy;
//   - whole-number decimation (n = 2, 3, ... source frames per output frame): output frame k is
//     EXACTLY source frame k * n, M = floor((N - 1) / n) + 1 (120 -> 60 fps keeps the captured frames
//     instead of blending neighbours by 0.0004%);
//   - whole-number subdivision (n = 2, 3, ... output frames per source frame): output frame k samples
//     k / n source frames exactly, M = (N - 1) * n + 1 (30 -> 60 fps of 128 frames gives 255 frames,
//     of which every second one is a source frame);
//   - other ratios: M uses (N - 1) * source_frame_time * target_fps scaled by (1 + 1e-5) inside the
//     floor, so a duration within rounding of a whole output frame keeps that frame.
//
// Limits: target_fps must be positive and finite, and at most kMaxUpsampling (100) times the source
// rate (more would allocate far beyond what the data justifies); the source needs at least one frame.
// std::invalid_argument otherwise (these are programmer-supplied values, not file input): a rate the
// user asks for goes through requireResampleableTo first.

#include <Eigen/Core>
#include <vector>

#include "motion/kinematics.h"
#include "motion/motion.h"

namespace motionstyle {

inline constexpr double kMaxUpsampling = 100.0;  // target fps / source fps

// Whether two frame rates are the same for resampling: |a - b| <= 1e-5 * b, the tolerance above, so
// a caller that skips resampling when this holds gets what resampleMotion would return (a copy).
bool sameFrameRate(double a, double b);

// For a rate the user asks for (--fps): throws InputError(motion.source, 0, ...) naming the clip's rate
// and the fastest allowed when resampleMotion(motion, target_fps) would refuse it (more than
// kMaxUpsampling x the clip's rate). Does nothing for an allowed rate.
void requireResampleableTo(const Motion& motion, double target_fps);

// Where output frame k samples the source: between frames `index` and `index + 1` with weight
// `fraction` in [0, 1) on the latter (fraction 0 means exactly source frame `index`).
struct ResampleSample {
  int index = 0;
  double fraction = 0.0;
};

// The sample positions of every output frame (size M above). source_frame_time in seconds, target in
// frames per second. Throws std::invalid_argument as described above.
std::vector<ResampleSample> resampleSchedule(int source_frames, double source_frame_time, double target_fps);

// The motion at target_fps: rotations slerped along the shortest path, translations (position
// channels) interpolated linearly, Euler angles re-derived per frame in each joint's own channel order
// with continuity (kinematics.h setLocalPoses). Keeps the skeleton, channel layout and source; the
// frame time becomes 1 / target_fps. A target rate within 1e-5 relative of the source's returns an
// identical copy (frame time included). Validates the motion (Motion::validate).
Motion resampleMotion(const Motion& motion, double target_fps);

// The same resampling on local transforms, without going through Euler angles: rotations slerped along
// the shortest path (the midpoint of an exact 2x subdivision is the normalised sum of the two
// sign-aligned quaternions, which is what slerp gives at 1/2, without its transcendentals), translations
// linear, a fraction of 0 a copy. Same schedule as resampleMotion (resampleSchedule), so that
// localPoses(resampleMotion(m, fps)) equals resampleLocalPoses(localPoses(m), m.frame_time, fps) to
// rounding (1e-12 rad, 1e-12 relative), except on joints with two rotation channels, to which
// resampleMotion gives the projection of the slerp. source_frame_time in seconds, target in frames per
// second; translations keep their units. std::invalid_argument as resampleSchedule, and for poses whose
// arrays do not match frames x joints.
LocalPoses resampleLocalPoses(const LocalPoses& poses, double source_frame_time, double target_fps);

// Linear resampling of a per-frame matrix (one ROW per frame, e.g. world positions or features) with
// the same timing rules. Do not use it for angles (they wrap) or quaternions (use slerp).
Eigen::MatrixXd resampleRowsLinear(const Eigen::MatrixXd& rows, double source_frame_time, double target_fps);

// The same for per-frame labels (one ROW per frame, e.g. contact labels or their overrides): each
// output frame takes the row of the source frame nearest to it in time (ties to the later one).
Eigen::MatrixXi resampleRowsNearest(const Eigen::MatrixXi& rows, double source_frame_time, double target_fps);

}  // namespace motionstyle
