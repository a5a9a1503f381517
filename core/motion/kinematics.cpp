#include "motion/kinematics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "motion/rotation.h"

namespace motionstyle {
namespace {

// Where one joint's channels live within a frame line, resolved once per call.
struct JointChannels {
  RotationAxes rotation_axes;                  // rotation channels in file order
  std::array<int, 3> rotation_column{-1, -1, -1};  // column of rotation channel n (n < rotation_axes.count)
  std::array<int, 3> position_column{-1, -1, -1};  // column of the X/Y/Z position channel, or -1
};

std::vector<JointChannels> resolveChannels(const Skeleton& skeleton) {
  const std::vector<int> offsets = skeleton.channelOffsets();
  std::vector<JointChannels> result(skeleton.joints.size());
  for (size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    JointChannels& resolved = result[j];
    resolved.rotation_axes = RotationAxes::of(joint.channels);
    int rotation_index = 0;
    for (size_t c = 0; c < joint.channels.size(); ++c) {
      const int column = offsets[j] + static_cast<int>(c);
      if (isRotation(joint.channels[c]))
        resolved.rotation_column[static_cast<size_t>(rotation_index++)] = column;
      else
        resolved.position_column[static_cast<size_t>(axisOf(joint.channels[c]))] = column;
    }
  }
  return result;
}

// The cheap structural checks forward kinematics relies on (Skeleton::validate does more, and
// allocates; this runs on every call, possibly once per displayed frame).
void checkPoses(const Skeleton& skeleton, const LocalPoses& poses) {
  const int joint_count = skeleton.jointCount();
  if (joint_count == 0) throw std::invalid_argument("kinematics: skeleton has no joints");
  if (poses.joints != joint_count)
    throw std::invalid_argument("kinematics: poses have " + std::to_string(poses.joints) + " joints, skeleton has " +
                                std::to_string(joint_count));
  if (poses.frames < 0) throw std::invalid_argument("kinematics: negative frame count");
  const size_t expected = static_cast<size_t>(poses.frames) * static_cast<size_t>(joint_count);
  if (poses.rotations.size() != expected || poses.translations.size() != expected)
    throw std::invalid_argument("kinematics: poses hold " + std::to_string(poses.rotations.size()) + " rotations and " +
                                std::to_string(poses.translations.size()) + " translations, expected " +
                                std::to_string(expected));
  if (skeleton.joints[0].parent != -1) throw std::invalid_argument("kinematics: joint 0 must be the root");
  for (int j = 1; j < joint_count; ++j) {
    const int parent = skeleton.joints[static_cast<size_t>(j)].parent;
    if (parent < 0 || parent >= j)
      throw std::invalid_argument("kinematics: joint " + std::to_string(j) + " has a parent that does not precede it");
  }
}

// Euler angles of joint channels within one frame line (degrees), unused entries 0.
Eigen::Vector3d readAngles(const double* row, const JointChannels& joint) {
  Eigen::Vector3d degrees = Eigen::Vector3d::Zero();
  for (int n = 0; n < joint.rotation_axes.count; ++n) degrees[n] = row[joint.rotation_column[static_cast<size_t>(n)]];
  return degrees;
}

// Translation components without a position channel must equal the offset's, to 1e-6 relative to the
// offset's size (at least 1 file unit).
void checkFixedTranslation(const Joint& joint, const JointChannels& channels, const Eigen::Vector3d& translation,
                           int frame) {
  const double tolerance = 1e-6 * std::max(1.0, joint.offset.norm());
  for (int axis = 0; axis < 3; ++axis) {
    if (channels.position_column[static_cast<size_t>(axis)] >= 0) continue;
    if (!(std::abs(translation[axis] - joint.offset[axis]) <= tolerance))
      throw std::invalid_argument("setLocalPoses: joint '" + joint.name + "' frame " + std::to_string(frame) +
                                  " moves its translation along an axis it has no position channel for");
  }
}

}  // namespace

LocalPoses localPoses(const Motion& motion) {
  motion.validate();
  const Skeleton& skeleton = motion.skeleton;
  const std::vector<JointChannels> channels = resolveChannels(skeleton);
  LocalPoses poses;
  poses.frames = motion.frameCount();
  poses.joints = skeleton.jointCount();
  const size_t total = static_cast<size_t>(poses.frames) * static_cast<size_t>(poses.joints);
  poses.rotations.resize(total);
  poses.translations.resize(total);
  for (int f = 0; f < poses.frames; ++f) {
    const double* row = motion.values.row(f).data();  // row-major: a frame line is contiguous
    for (int j = 0; j < poses.joints; ++j) {
      const Joint& joint = skeleton.joints[static_cast<size_t>(j)];
      const JointChannels& resolved = channels[static_cast<size_t>(j)];
      Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
      for (int n = 0; n < resolved.rotation_axes.count; ++n)
        rotation = rotation * axisRotation(resolved.rotation_axes.axis[static_cast<size_t>(n)],
                                           row[resolved.rotation_column[static_cast<size_t>(n)]]);
      Eigen::Vector3d translation = joint.offset;
      for (int axis = 0; axis < 3; ++axis) {
        const int column = resolved.position_column[static_cast<size_t>(axis)];
        if (column >= 0) translation[axis] = row[column];
      }
      poses.rotation(f, j) = rotation;
      poses.translation(f, j) = translation;
    }
  }
  return poses;
}

void setLocalPoses(const LocalPoses& poses, Motion& motion) {
  const Skeleton& skeleton = motion.skeleton;
  skeleton.validate();
  checkPoses(skeleton, poses);
  const std::vector<JointChannels> channels = resolveChannels(skeleton);
  const int channel_count = skeleton.channelCount();
  // Frame 0 continues from the motion's current frame 0 when there is one, so that a round trip keeps
  // the file's own angle ranges (e.g. 270 instead of -90).
  const bool has_seed = motion.values.rows() > 0 && motion.values.cols() == channel_count &&
                        motion.values.row(0).allFinite();
  MatrixRowMajor values(poses.frames, channel_count);
  for (int f = 0; f < poses.frames; ++f) {
    double* row = values.row(f).data();
    const double* previous_row = f > 0 ? values.row(f - 1).data() : (has_seed ? motion.values.row(0).data() : nullptr);
    for (int j = 0; j < poses.joints; ++j) {
      const Joint& joint = skeleton.joints[static_cast<size_t>(j)];
      const JointChannels& resolved = channels[static_cast<size_t>(j)];
      const Eigen::Quaterniond& rotation = poses.rotation(f, j);
      const Eigen::Vector3d& translation = poses.translation(f, j);
      if (!rotation.coeffs().allFinite() || !(rotation.norm() > 0.5) || !translation.allFinite())
        throw std::invalid_argument("setLocalPoses: joint '" + joint.name + "' frame " + std::to_string(f) +
                                    " has a non-finite or zero pose");
      if (resolved.rotation_axes.count == 0) {
        if (rotationDistance(rotation, Eigen::Quaterniond::Identity()) > 1e-6)
          throw std::invalid_argument("setLocalPoses: joint '" + joint.name + "' frame " + std::to_string(f) +
                                      " is rotated but has no rotation channels");
      } else {
        const Eigen::Vector3d degrees =
            previous_row ? quaternionToEuler(rotation, resolved.rotation_axes, readAngles(previous_row, resolved))
                         : quaternionToEuler(rotation, resolved.rotation_axes);
        for (int n = 0; n < resolved.rotation_axes.count; ++n)
          row[resolved.rotation_column[static_cast<size_t>(n)]] = degrees[n];
      }
      checkFixedTranslation(joint, resolved, translation, f);
      for (int axis = 0; axis < 3; ++axis) {
        const int column = resolved.position_column[static_cast<size_t>(axis)];
        if (column >= 0) row[column] = translation[axis];
      }
    }
  }
  motion.values = std::move(values);
}

Eigen::MatrixXd worldPositions(const Skeleton& skeleton, const LocalPoses& poses) {
  checkPoses(skeleton, poses);
  const int joint_count = poses.joints;
  Eigen::MatrixXd positions(poses.frames, 3 * joint_count);
  // Scratch reused across frames: world rotation (as a matrix, cheaper to apply than a quaternion) and
  // world position of every joint of the current frame.
  std::vector<Eigen::Matrix3d> world_rotation(static_cast<size_t>(joint_count));
  std::vector<Eigen::Vector3d> world_position(static_cast<size_t>(joint_count));
  std::vector<int> parent(static_cast<size_t>(joint_count));
  for (int j = 0; j < joint_count; ++j) parent[static_cast<size_t>(j)] = skeleton.joints[static_cast<size_t>(j)].parent;

  for (int f = 0; f < poses.frames; ++f) {
    const size_t base = poses.at(f, 0);
    for (size_t j = 0; j < static_cast<size_t>(joint_count); ++j) {
      const Eigen::Matrix3d local = poses.rotations[base + j].toRotationMatrix();
      const Eigen::Vector3d& translation = poses.translations[base + j];
      const int p = parent[j];
      if (p < 0) {
        world_rotation[j] = local;
        world_position[j] = translation;
      } else {
        const auto pj = static_cast<size_t>(p);
        world_position[j].noalias() = world_position[pj] + world_rotation[pj] * translation;
        world_rotation[j].noalias() = world_rotation[pj] * local;
      }
      const Eigen::Index column = 3 * static_cast<Eigen::Index>(j);
      positions(f, column) = world_position[j].x();
      positions(f, column + 1) = world_position[j].y();
      positions(f, column + 2) = world_position[j].z();
    }
  }
  return positions;
}

std::vector<Eigen::Quaterniond> worldRotations(const Skeleton& skeleton, const LocalPoses& poses) {
  checkPoses(skeleton, poses);
  std::vector<Eigen::Quaterniond> world(poses.rotations.size());
  for (int f = 0; f < poses.frames; ++f) {
    for (int j = 0; j < poses.joints; ++j) {
      const int p = skeleton.joints[static_cast<size_t>(j)].parent;
      world[poses.at(f, j)] = p < 0 ? poses.rotation(f, j) : world[poses.at(f, p)] * poses.rotation(f, j);
    }
  }
  return world;
}

}  // namespace motionstyle
