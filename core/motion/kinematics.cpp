#include "motion/kinematics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <numeric>
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

// Per-frame work below runs on blocks of kLanes frames held in Eigen fixed-size arrays, so that every
// operation is one explicit vector expression over the block. Every frame (lane) therefore goes
// through the same instructions: a frame's result does not depend on where it sits in the clip (a
// decimated clip's frames equal the source's bit for bit), which loops left to the auto-vectoriser do
// not guarantee (their scalar remainder may contract multiply-adds differently).
constexpr int kLanes = 8;
using Lanes = Eigen::Array<double, kLanes, 1>;

// values[0 .. count), the last one repeated into the lanes past count (1 <= count <= kLanes).
Lanes loadLanes(const double* values, int count) {
  if (count == kLanes) return Eigen::Map<const Lanes>(values);
  Lanes lanes;
  for (int i = 0; i < kLanes; ++i) lanes[i] = values[std::min(i, count - 1)];
  return lanes;
}

// (w, v) <- (w, v) * (c + s e_A) over a block of frames, as composeAxisRotation (rotation.h). The axis
// is a template argument so that the quaternion's lanes stay in registers.
template <int A>
void composeLanes(Lanes& w, std::array<Lanes, 3>& v, const Lanes& c, const Lanes& s) {
  constexpr size_t a = A, b = (A + 1) % 3, d = (A + 2) % 3;
  const Lanes w0 = w, va = v[a], vb = v[b], vd = v[d];
  w = c * w0 - s * va;
  v[a] = c * va + s * w0;
  v[b] = c * vb + s * vd;
  v[d] = c * vd - s * vb;
}

// Local rotations of joint j over all frames from its channels' half-angle cosines and sines (one run
// of frames per channel): R = (c1 + s1 e_a1) (c2 + s2 e_a2) ...
void jointRotations(LocalPoses& poses, int j, const RotationAxes& axes, const double* const cosines[3],
                    const double* const sines[3]) {
  for (int first = 0; first < poses.frames; first += kLanes) {
    const int count = std::min(kLanes, poses.frames - first);
    Lanes w = Lanes::Ones();
    std::array<Lanes, 3> v = {Lanes::Zero(), Lanes::Zero(), Lanes::Zero()};
    for (int n = 0; n < axes.count; ++n) {
      const Lanes c = loadLanes(cosines[n] + first, count), s = loadLanes(sines[n] + first, count);
      switch (axes.axis[static_cast<size_t>(n)]) {
        case 0: composeLanes<0>(w, v, c, s); break;
        case 1: composeLanes<1>(w, v, c, s); break;
        default: composeLanes<2>(w, v, c, s); break;
      }
    }
    for (int i = 0; i < count; ++i) poses.rotation(first + i, j) = Eigen::Quaterniond(w[i], v[0][i], v[1][i], v[2][i]);
  }
}

// Forward kinematics over a block of frames at a time, one joint at a time, in structure-of-arrays form
// (lanes as above; storing a joint's world rotation per frame and reloading it at another width is
// what stalled the per-frame scalar version).
struct FkStep {
  int joint, parent;
  bool needs_rotation;  // some visited joint is its child
};

// World rotation (quaternion and row-major matrix) and position of one joint over a block of frames.
struct FkBlock {
  Lanes qw, qx, qy, qz;
  std::array<Lanes, 9> m;
  Lanes px, py, pz;
};

void forwardKinematicsStep(const LocalPoses& poses, const FkStep& step, int first, int count, FkBlock* blocks) {
  FkBlock& out = blocks[static_cast<size_t>(step.joint)];
  // Local transforms of the block's frames (lanes past the clip's end repeat its last frame).
  Lanes lw, lx, ly, lz, tx, ty, tz;
  for (int i = 0; i < kLanes; ++i) {
    const int frame = first + std::min(i, count - 1);
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
    out.px = parent.px + (m[0] * tx + m[1] * ty + m[2] * tz);
    out.py = parent.py + (m[3] * tx + m[4] * ty + m[5] * tz);
    out.pz = parent.pz + (m[6] * tx + m[7] * ty + m[8] * tz);
    if (!step.needs_rotation) return;  // a leaf of the visited tree: its position is all that is wanted
    // world = parent world * local
    out.qw = parent.qw * lw - parent.qx * lx - parent.qy * ly - parent.qz * lz;
    out.qx = parent.qw * lx + parent.qx * lw + parent.qy * lz - parent.qz * ly;
    out.qy = parent.qw * ly + parent.qy * lw + parent.qz * lx - parent.qx * lz;
    out.qz = parent.qw * lz + parent.qz * lw + parent.qx * ly - parent.qy * lx;
  }
  if (!step.needs_rotation) return;
  // Rotation matrix of a unit quaternion, as Eigen's toRotationMatrix.
  const Lanes tx2 = 2 * out.qx, ty2 = 2 * out.qy, tz2 = 2 * out.qz;
  const Lanes twx = tx2 * out.qw, twy = ty2 * out.qw, twz = tz2 * out.qw;
  const Lanes txx = tx2 * out.qx, txy = ty2 * out.qx, txz = tz2 * out.qx;
  const Lanes tyy = ty2 * out.qy, tyz = tz2 * out.qy, tzz = tz2 * out.qz;
  out.m[0] = 1 - (tyy + tzz), out.m[1] = txy - twz, out.m[2] = txz + twy;
  out.m[3] = txy + twz, out.m[4] = 1 - (txx + tzz), out.m[5] = tyz - twx;
  out.m[6] = txz - twy, out.m[7] = tyz + twx, out.m[8] = 1 - (txx + tyy);
}

LocalPoses localPosesOfValidMotion(const Motion& motion, int first, int count) {
  const Skeleton& skeleton = motion.skeleton;
  const std::vector<JointChannels> channels = resolveChannels(skeleton);
  LocalPoses poses;
  poses.frames = count;
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
    const double* row = motion.values.row(static_cast<Eigen::Index>(first) + static_cast<Eigen::Index>(f)).data();  // row-major
    size_t channel = 0;
    for (const JointChannels& resolved : channels)
      for (int n = 0; n < resolved.rotation_axes.count; ++n, ++channel)
        angles[static_cast<Eigen::Index>(channel * frames + f)] = row[resolved.rotation_column[static_cast<size_t>(n)]];
  }
  const auto angle_count = static_cast<size_t>(angles.size());
  halfAngleSinCos({angles.data(), angle_count}, {sines.data(), angle_count}, {cosines.data(), angle_count});

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
      const double* row = motion.values.row(first + f).data();
      double* translation = poses.translation(f, j).data();  // written in place: no temporary to reload
      for (size_t axis = 0; axis < 3; ++axis)
        translation[axis] = column[axis] >= 0 ? row[column[axis]] : joint.offset[static_cast<Eigen::Index>(axis)];
    }
  }
  return poses;
}

}  // namespace

LocalPoses localPoses(const Motion& motion) {
  motion.validate();
  return localPosesOfValidMotion(motion, 0, motion.frameCount());
}

LocalPoses localPoses(const Motion& motion, int first, int count) {
  if (first < 0 || count < 0 || first > motion.frameCount() - count)
    throw std::invalid_argument("localPoses: frames " + std::to_string(first) + " + " + std::to_string(count) +
                                " outside the clip's " + std::to_string(motion.frameCount()));
  Motion header;  // validates all but the values, which are checked for the range only
  header.skeleton = motion.skeleton;
  header.frame_time = motion.frame_time;
  header.values.resize(0, motion.values.cols());
  header.validate();
  if (!motion.values.middleRows(first, count).allFinite())
    throw std::invalid_argument("motion contains a non-finite channel value");
  return localPosesOfValidMotion(motion, first, count);
}

void setLocalPoses(const LocalPoses& poses, Motion& motion) {
  // Frame 0 continues from the motion's current frame 0 when there is one, so that a round trip keeps
  // the file's own angle ranges (e.g. 270 instead of -90).
  const bool has_seed = motion.values.rows() > 0 && motion.values.cols() == motion.skeleton.channelCount() &&
                        motion.values.row(0).allFinite();
  MatrixRowMajor values = channelValues(motion.skeleton, poses, has_seed ? motion.values.row(0).data() : nullptr);
  motion.values = std::move(values);
}

namespace {

// Joint j's channels of frame f of `poses` into `row`, continuing from previous_row (may be null).
void writeJointChannels(const Skeleton& skeleton, const std::vector<JointChannels>& channels, const LocalPoses& poses,
                        int f, int j, const double* previous_row, double* row) {
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
    const Eigen::Vector3d degrees = previous_row
                                        ? quaternionToEuler(rotation, resolved.rotation_axes, readAngles(previous_row, resolved))
                                        : quaternionToEuler(rotation, resolved.rotation_axes);
    for (int n = 0; n < resolved.rotation_axes.count; ++n) row[resolved.rotation_column[static_cast<size_t>(n)]] = degrees[n];
  }
  checkFixedTranslation(joint, resolved, translation, f);
  for (int axis = 0; axis < 3; ++axis) {
    const int column = resolved.position_column[static_cast<size_t>(axis)];
    if (column >= 0) row[column] = translation[axis];
  }
}

}  // namespace

void writeChannelValues(const Skeleton& skeleton, const LocalPoses& poses, std::span<const int> joints,
                        const double* seed_row, MatrixRowMajor& values) {
  skeleton.validate();
  checkPoses(skeleton, poses);
  if (values.rows() != poses.frames || values.cols() != skeleton.channelCount())
    throw std::invalid_argument("writeChannelValues: the values are not frames x channels");
  for (const int joint : joints)
    if (joint < 0 || joint >= poses.joints) throw std::invalid_argument("writeChannelValues: a joint outside the skeleton");
  const std::vector<JointChannels> channels = resolveChannels(skeleton);
  for (int f = 0; f < poses.frames; ++f) {
    const double* previous_row = f > 0 ? values.row(f - 1).data() : seed_row;
    for (const int j : joints) writeJointChannels(skeleton, channels, poses, f, j, previous_row, values.row(f).data());
  }
}

MatrixRowMajor channelValues(const Skeleton& skeleton, const LocalPoses& poses, const double* seed_row) {
  MatrixRowMajor values(poses.frames, skeleton.channelCount());
  std::vector<int> every_joint(static_cast<size_t>(std::max(poses.joints, 0)));
  std::iota(every_joint.begin(), every_joint.end(), 0);
  writeChannelValues(skeleton, poses, every_joint, seed_row, values);
  return values;
}

Eigen::MatrixXd worldPositions(const Skeleton& skeleton, const LocalPoses& poses) {
  std::vector<int> every_joint(static_cast<size_t>(std::max(skeleton.jointCount(), 0)));
  for (size_t j = 0; j < every_joint.size(); ++j) every_joint[j] = static_cast<int>(j);
  return worldPositions(skeleton, poses, every_joint);
}

Eigen::MatrixXd worldPositions(const Motion& motion, std::span<const int> wanted) {
  motion.validate();
  const int frames = motion.frameCount();
  Eigen::MatrixXd positions(frames, 3 * static_cast<Eigen::Index>(wanted.size()));
  for (int first = 0; first < frames; first += kMotionBlockFrames) {
    const int count = std::min(kMotionBlockFrames, frames - first);
    positions.middleRows(first, count) = worldPositions(motion.skeleton, localPosesOfValidMotion(motion, first, count), wanted);
  }
  if (frames == 0) positions = worldPositions(motion.skeleton, localPosesOfValidMotion(motion, 0, 0), wanted);
  return positions;
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
  for (int first = 0; first < poses.frames; first += kLanes) {
    const int count = std::min(kLanes, poses.frames - first);
    for (const FkStep& step : steps) forwardKinematicsStep(poses, step, first, count, blocks.get());
    Eigen::Index column = 0;
    for (const int joint : wanted) {  // column-major: each coordinate is a contiguous run of frames
      const FkBlock& block = blocks[static_cast<size_t>(joint)];
      for (const Lanes* lane : {&block.px, &block.py, &block.pz}) {
        double* out = positions.col(column++).data() + first;
        if (count == kLanes)
          std::copy_n(lane->data(), kLanes, out);  // a fixed-size copy: a few vector moves
        else
          std::copy_n(lane->data(), count, out);
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
