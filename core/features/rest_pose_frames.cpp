#include "features/rest_pose_frames.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "features/feature_layout.h"
#include "features/space_convention.h"
#include "motion/kinematics.h"

namespace motionstyle {
namespace {

// Mean joint displacement between frames a and b of `world` (frames x 63), each relative to its hips.
double poseStep(const Eigen::MatrixXd& world, Eigen::Index a, Eigen::Index b) {
  const int hips = index(CanonicalJoint::Hips);
  const Eigen::Vector3d hips_a = world.row(a).segment<3>(3 * hips).transpose();
  const Eigen::Vector3d hips_b = world.row(b).segment<3>(3 * hips).transpose();
  double sum = 0.0;
  for (int c = 0; c < kCanonicalJointCount; ++c) {
    const Eigen::Vector3d pa = world.row(a).segment<3>(3 * c).transpose() - hips_a;
    const Eigen::Vector3d pb = world.row(b).segment<3>(3 * c).transpose() - hips_b;
    sum += (pb - pa).norm();
  }
  return sum / kCanonicalJointCount;
}

}  // namespace

int leadingRestPoseFrames(const Motion& motion, const JointMapping& mapping) {
  const int frames = motion.frameCount();
  if (frames < 3) return 0;
  const double height = skeletalHeight(motion.skeleton, mapping);
  if (!(height > 0.0) || !std::isfinite(height)) return 0;
  // Frame 0, then half a second of steps (at least one) to compare it with.
  const int compared = std::clamp(static_cast<int>(std::lround(0.5 * motion.fps())), 1, frames - 2);
  Motion head;
  head.skeleton = motion.skeleton;
  head.frame_time = motion.frame_time;
  head.values = motion.values.topRows(compared + 2);
  const Eigen::MatrixXd world = worldPositions(head, mapping.joints);
  const double jump = poseStep(world, 0, 1) / height;
  std::vector<double> steps;
  for (int t = 1; t <= compared; ++t) steps.push_back(poseStep(world, t, t + 1) / height);
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  const double median_step = steps[steps.size() / 2];
  return jump > kRestPoseJump && jump > kRestPoseJumpRatio * median_step ? 1 : 0;
}

void replaceRestPoseFrames(Motion& motion, int rest_pose_frames) {
  if (rest_pose_frames < 0 || (rest_pose_frames > 0 && rest_pose_frames + 2 > motion.frameCount()))
    throw std::invalid_argument("replaceRestPoseFrames: " + std::to_string(rest_pose_frames) +
                                " rest-pose frames in a clip of " + std::to_string(motion.frameCount()) +
                                " (the motion needs two frames after them)");
  if (rest_pose_frames == 0) return;
  // Which channels are angles (wrapped to the nearest turn when stepped).
  std::vector<bool> rotation;
  for (const Joint& joint : motion.skeleton.joints)
    for (ChannelType channel : joint.channels) rotation.push_back(isRotation(channel));
  for (int f = rest_pose_frames - 1; f >= 0; --f) {
    for (Eigen::Index c = 0; c < motion.values.cols(); ++c) {
      double step = motion.values(f + 1, c) - motion.values(f + 2, c);
      if (rotation[static_cast<std::size_t>(c)]) step = std::remainder(step, 360.0);
      motion.values(f, c) = motion.values(f + 1, c) + step;
    }
  }
}

void restoreRestPoseFrames(Motion& output, const Motion& content, int rest_pose_frames) {
  if (rest_pose_frames <= 0) return;
  if (output.values.cols() != content.values.cols())
    throw std::invalid_argument("restoreRestPoseFrames: the output has " + std::to_string(output.values.cols()) +
                                " channels, the content " + std::to_string(content.values.cols()));
  for (int f = 0; f < output.frameCount(); ++f) {
    const long source = std::lround(f * output.frame_time / content.frame_time);  // nearest content frame
    if (source >= rest_pose_frames) break;
    output.values.row(f) = content.values.row(source);
  }
}

}  // namespace motionstyle
