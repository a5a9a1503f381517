#include "motion/kinematics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
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

// Local rotations of joint j over all frames when its three rotation axes are A, B and the remaining
// one, D (known at compile time: the composition is then straight-line code). With half-angle cosines
// c and sines s per channel: (c0 + s0 e_A)(c1 + s1 e_B) = c0 c1 + s0 c1 e_A + c0 s1 e_B + s0 s1 e_A e_B,
// where e_A e_B = sigma e_D (sigma = +1 when A, B, D is cyclic), then times (c2 + s2 e_D).
template <int A, int B>
void threeAxisRotations(LocalPoses& poses, int j, const double* const cosines[3], const double* const sines[3]) {
  constexpr int D = 3 - A - B;
  constexpr double sigma = B == (A + 1) % 3 ? 1.0 : -1.0;
  for (int f = 0; f < poses.frames; ++f) {
    Eigen::Quaterniond q;
    q.w() = cosines[0][f] * cosines[1][f];
    q.vec()[A] = sines[0][f] * cosines[1][f];
    q.vec()[B] = cosines[0][f] * sines[1][f];
    q.vec()[D] = sigma * sines[0][f] * sines[1][f];
    poses.rotation(f, j) = composeAxisRotation(q, D, cosines[2][f], sines[2][f]);
  }
}

// Any other axis layout (0, 1 or 2 axes): channel by channel.
void generalRotations(LocalPoses& poses, int j, const RotationAxes& axes, const double* const cosines[3],
                      const double* const sines[3]) {
  for (int f = 0; f < poses.frames; ++f) {
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    for (int n = 0; n < axes.count; ++n)
      q = composeAxisRotation(q, axes.axis[static_cast<size_t>(n)], cosines[n][f], sines[n][f]);
    poses.rotation(f, j) = q;
  }
}

void jointRotations(LocalPoses& poses, int j, const RotationAxes& axes, const double* const cosines[3],
                    const double* const sines[3]) {
  if (axes.count == 3) {
    const int first = axes.axis[0], second = axes.axis[1];
    if (first == 0 && second == 1) return threeAxisRotations<0, 1>(poses, j, cosines, sines);
    if (first == 0 && second == 2) return threeAxisRotations<0, 2>(poses, j, cosines, sines);
    if (first == 1 && second == 0) return threeAxisRotations<1, 0>(poses, j, cosines, sines);
    if (first == 1 && second == 2) return threeAxisRotations<1, 2>(poses, j, cosines, sines);
    if (first == 2 && second == 0) return threeAxisRotations<2, 0>(poses, j, cosines, sines);
    if (first == 2 && second == 1) return threeAxisRotations<2, 1>(poses, j, cosines, sines);
  }
  generalRotations(poses, j, axes, cosines, sines);
}

// Forward kinematics over a block of frames at a time, one joint at a time, in structure-of-arrays form:
// every operation is a loop over the block's frames, which the compiler turns into vector instructions
// (and no value is stored and reloaded at another width, which stalls per-frame scalar code).
constexpr int kFkBlock = 8;
using FkLane = std::array<double, kFkBlock>;

struct FkStep {
  int joint, parent;
  bool needs_rotation;  // some visited joint is its child
};

// World rotation (quaternion and row-major matrix) and position of one joint over a block of frames.
struct FkBlock {
  FkLane qw, qx, qy, qz;
  std::array<FkLane, 9> m;
  FkLane px, py, pz;
};

void forwardKinematicsStep(const LocalPoses& poses, const FkStep& step, int first, int count,
                           FkBlock* blocks) {
  FkBlock& out = blocks[static_cast<size_t>(step.joint)];
  // Local transforms of the block's frames (lanes past the clip's end repeat its last frame).
  FkLane lw, lx, ly, lz, tx, ty, tz;
  for (size_t i = 0; i < static_cast<size_t>(kFkBlock); ++i) {
    const int frame = first + std::min(static_cast<int>(i), count - 1);
    const Eigen::Quaterniond& q = poses.rotation(frame, step.joint);
    const Eigen::Vector3d& t = poses.translation(frame, step.joint);
    lw[i] = q.w(), lx[i] = q.x(), ly[i] = q.y(), lz[i] = q.z();
    tx[i] = t.x(), ty[i] = t.y(), tz[i] = t.z();
  }
  if (step.parent < 0) {
    out.px = tx, out.py = ty, out.pz = tz;
    out.qw = lw, out.qx = lx, out.qy = ly, out.qz = lz;
  } else {
    const FkBlock& parent = blocks[static_cast<size_t>(step.parent)];
    const auto& m = parent.m;
    for (size_t i = 0; i < static_cast<size_t>(kFkBlock); ++i) {
      out.px[i] = parent.px[i] + (m[0][i] * tx[i] + m[1][i] * ty[i] + m[2][i] * tz[i]);
      out.py[i] = parent.py[i] + (m[3][i] * tx[i] + m[4][i] * ty[i] + m[5][i] * tz[i]);
      out.pz[i] = parent.pz[i] + (m[6][i] * tx[i] + m[7][i] * ty[i] + m[8][i] * tz[i]);
    }
    if (!step.needs_rotation) return;  // a leaf of the visited tree: its position is all that is wanted
    for (size_t i = 0; i < static_cast<size_t>(kFkBlock); ++i) {  // world = parent world * local
      const double aw = parent.qw[i], ax = parent.qx[i], ay = parent.qy[i], az = parent.qz[i];
      out.qw[i] = aw * lw[i] - ax * lx[i] - ay * ly[i] - az * lz[i];
      out.qx[i] = aw * lx[i] + ax * lw[i] + ay * lz[i] - az * ly[i];
      out.qy[i] = aw * ly[i] + ay * lw[i] + az * lx[i] - ax * lz[i];
      out.qz[i] = aw * lz[i] + az * lw[i] + ax * ly[i] - ay * lx[i];
    }
  }
  if (!step.needs_rotation) return;
  for (size_t i = 0; i < static_cast<size_t>(kFkBlock); ++i) {  // as Eigen's toRotationMatrix
    const double w = out.qw[i], x = out.qx[i], y = out.qy[i], z = out.qz[i];
    const double tx2 = 2 * x, ty2 = 2 * y, tz2 = 2 * z;
    const double twx = tx2 * w, twy = ty2 * w, twz = tz2 * w;
    const double txx = tx2 * x, txy = ty2 * x, txz = tz2 * x;
    const double tyy = ty2 * y, tyz = tz2 * y, tzz = tz2 * z;
    out.m[0][i] = 1 - (tyy + tzz), out.m[1][i] = txy - twz, out.m[2][i] = txz + twy;
    out.m[3][i] = txy + twz, out.m[4][i] = 1 - (txx + tzz), out.m[5][i] = tyz - twx;
    out.m[6][i] = txz - twy, out.m[7][i] = tyz + twx, out.m[8][i] = 1 - (txx + tyy);
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
  const auto frames = static_cast<size_t>(poses.frames);

  // Every rotation angle of the clip, one contiguous run of frames per rotation channel, so that their
  // half-angle sines and cosines come from one vectorised pass (libm's sin and cos, twice per angle,
  // used to dominate the whole feature pipeline).
  size_t rotation_channels = 0;
  for (const JointChannels& resolved : channels) rotation_channels += static_cast<size_t>(resolved.rotation_axes.count);
  Eigen::ArrayXd angles(static_cast<Eigen::Index>(rotation_channels * frames));  // uninitialised: all written
  Eigen::ArrayXd sines(angles.size()), cosines(angles.size());
  for (size_t f = 0; f < frames; ++f) {
    const double* row = motion.values.row(static_cast<Eigen::Index>(f)).data();  // row-major: contiguous
    size_t channel = 0;
    for (const JointChannels& resolved : channels)
      for (int n = 0; n < resolved.rotation_axes.count; ++n, ++channel)
        angles[static_cast<Eigen::Index>(channel * frames + f)] = row[resolved.rotation_column[static_cast<size_t>(n)]];
  }
  const auto count = static_cast<size_t>(angles.size());
  halfAngleSinCos({angles.data(), count}, {sines.data(), count}, {cosines.data(), count});

  size_t channel = 0;
  for (int j = 0; j < poses.joints; ++j) {
    const Joint& joint = skeleton.joints[static_cast<size_t>(j)];
    const JointChannels& resolved = channels[static_cast<size_t>(j)];
    const double* joint_cosines[3] = {nullptr, nullptr, nullptr};
    const double* joint_sines[3] = {nullptr, nullptr, nullptr};
    for (int n = 0; n < resolved.rotation_axes.count; ++n, ++channel) {
      joint_cosines[n] = cosines.data() + channel * frames;
      joint_sines[n] = sines.data() + channel * frames;
    }
    jointRotations(poses, j, resolved.rotation_axes, joint_cosines, joint_sines);
    const std::array<int, 3>& column = resolved.position_column;
    for (int f = 0; f < poses.frames; ++f) {
      const double* row = motion.values.row(f).data();
      double* translation = poses.translation(f, j).data();  // written in place: no temporary to reload
      for (size_t axis = 0; axis < 3; ++axis)
        translation[axis] = column[axis] >= 0 ? row[column[axis]] : joint.offset[static_cast<Eigen::Index>(axis)];
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
  std::vector<int> every_joint(static_cast<size_t>(std::max(skeleton.jointCount(), 0)));
  for (size_t j = 0; j < every_joint.size(); ++j) every_joint[j] = static_cast<int>(j);
  return worldPositions(skeleton, poses, every_joint);
}

Eigen::MatrixXd worldPositions(const Skeleton& skeleton, const LocalPoses& poses, std::span<const int> wanted) {
  checkPoses(skeleton, poses);
  const int joint_count = poses.joints;
  for (const int joint : wanted)
    if (joint < 0 || joint >= joint_count)
      throw std::invalid_argument("worldPositions: wanted joint " + std::to_string(joint) + " is not in the skeleton (" +
                                  std::to_string(joint_count) + " joints)");
  // The joints forward kinematics must visit: the wanted ones and their ancestors, in skeleton order
  // (parents first). Only those with a visited child need a world rotation.
  std::vector<char> visited(static_cast<size_t>(joint_count), 0), has_child(static_cast<size_t>(joint_count), 0);
  for (int joint : wanted)
    for (int j = joint; j >= 0 && !visited[static_cast<size_t>(j)]; j = skeleton.joints[static_cast<size_t>(j)].parent)
      visited[static_cast<size_t>(j)] = 1;
  std::vector<FkStep> steps;
  for (int j = 0; j < joint_count; ++j) {
    if (!visited[static_cast<size_t>(j)]) continue;
    const int parent = skeleton.joints[static_cast<size_t>(j)].parent;
    if (parent >= 0) has_child[static_cast<size_t>(parent)] = 1;
    steps.push_back({j, parent, false});
  }
  for (FkStep& step : steps) step.needs_rotation = has_child[static_cast<size_t>(step.joint)] != 0;

  Eigen::MatrixXd positions(poses.frames, 3 * static_cast<Eigen::Index>(wanted.size()));
  const std::unique_ptr<FkBlock[]> blocks(new FkBlock[static_cast<size_t>(joint_count)]);  // uninitialised scratch
  for (int first = 0; first < poses.frames; first += kFkBlock) {
    const int count = std::min(kFkBlock, poses.frames - first);
    for (const FkStep& step : steps) forwardKinematicsStep(poses, step, first, count, blocks.get());
    Eigen::Index column = 0;
    for (const int joint : wanted) {  // column-major: each coordinate is a contiguous run of frames
      const FkBlock& block = blocks[static_cast<size_t>(joint)];
      for (const FkLane* lane : {&block.px, &block.py, &block.pz}) {
        double* out = positions.col(column++).data() + first;
        if (count == kFkBlock)
          std::copy_n(lane->begin(), kFkBlock, out);  // a fixed-size copy: two vector moves
        else
          std::copy_n(lane->begin(), count, out);
      }
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
