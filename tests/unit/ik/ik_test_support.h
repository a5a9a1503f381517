#pragma once
// Helpers for the clean-up tests and bench: canonical positions of a clip, realistic damage to target
// positions (smooth per-joint noise, foot sliding during contact, bone-length changes), and a
// ready-made clean-up scenario for a real clip.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "features/feature_layout.h"
#include "ik/cleanup.h"
#include "ik/contacts.h"
#include "ik/metrics.h"
#include "mapping/joint_mapping.h"
#include "motion/kinematics.h"
#include "motion/motion.h"

namespace motionstyle::test {

// A hand-built humanoid in centimetres, Y-up, standing on y = 0 (ankle 7 cm, toe 2 cm above it),
// with what real rigs have beyond the canonical joints: clavicles, a finger, End Sites.
// position_channels_everywhere: every joint carries 6 channels (Bandai style).
inline Skeleton makeHumanoid(bool position_channels_everywhere = false) {
  using C = ChannelType;
  const std::vector<ChannelType> rotation = {C::Zrotation, C::Xrotation, C::Yrotation};
  const std::vector<ChannelType> six = {C::Xposition, C::Yposition, C::Zposition, C::Zrotation, C::Xrotation, C::Yrotation};
  Skeleton skeleton;
  auto add = [&](const std::string& name, const std::string& parent, Eigen::Vector3d offset, bool end = false) {
    Joint joint;
    joint.name = name;
    joint.parent = parent.empty() ? -1 : skeleton.find(parent);
    joint.offset = offset;
    joint.end_site = end;
    if (!end) joint.channels = (parent.empty() || position_channels_everywhere) ? six : rotation;
    skeleton.joints.push_back(joint);
  };
  add("Hips", "", {0, 0, 0});
  for (const auto& [side, sign] : {std::pair{std::string("Left"), 1.0}, std::pair{std::string("Right"), -1.0}}) {
    add(side + "UpLeg", "Hips", {sign * 9, -5, 0});
    add(side + "Leg", side + "UpLeg", {0, -42, 0});
    add(side + "Foot", side + "Leg", {0, -40, 0});
    add(side + "ToeBase", side + "Foot", {0, -5, 12});
    add(side + "ToeBase_End", side + "ToeBase", {0, 0, 6}, true);
  }
  add("Spine", "Hips", {0, 10, 0});
  add("Chest", "Spine", {0, 15, 0});
  add("Neck", "Chest", {0, 20, 0});
  add("Head", "Neck", {0, 10, 0});
  add("Head_End", "Head", {0, 15, 0}, true);
  for (const auto& [side, sign] : {std::pair{std::string("Left"), 1.0}, std::pair{std::string("Right"), -1.0}}) {
    add(side + "Shoulder", "Chest", {sign * 3, 15, 0});
    add(side + "Arm", side + "Shoulder", {sign * 12, 0, 0});
    add(side + "ForeArm", side + "Arm", {sign * 28, 0, 0});
    add(side + "Hand", side + "ForeArm", {sign * 25, 0, 0});
    add(side + "HandEnd", side + "Hand", {sign * 10, 0, 0}, true);
    add(side + "Thumb", side + "Hand", {sign * 3, 0, 3});
    add(side + "Thumb_End", side + "Thumb", {sign * 4, 0, 0}, true);
  }
  return skeleton;
}

// The canonical joints of makeHumanoid by name.
inline JointMapping humanoidMapping(const Skeleton& skeleton) {
  static const std::array<const char*, kCanonicalJointCount> names = {
      "Hips", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase", "RightUpLeg", "RightLeg", "RightFoot",
      "RightToeBase", "Spine", "Chest", "Neck", "Head", "LeftArm", "LeftForeArm", "LeftHand", "LeftHandEnd",
      "RightArm", "RightForeArm", "RightHand", "RightHandEnd"};
  JointMapping mapping;
  mapping.convention = "test";
  for (size_t c = 0; c < names.size(); ++c) mapping.joints[c] = skeleton.find(names[c]);
  return mapping;
}

// A clip on makeHumanoid: hips at 89 cm swaying and bobbing (the rest pose stands at 92), knees bent
// about 15 degrees, the spine, arms, clavicles and thumbs moving smoothly; angles in degrees.
inline Motion makeHumanoidClip(int frames, double fps, bool position_channels_everywhere = false) {
  Motion motion;
  motion.skeleton = makeHumanoid(position_channels_everywhere);
  motion.frame_time = 1.0 / fps;
  motion.source = "humanoid";
  const std::vector<int> offsets = motion.skeleton.channelOffsets();
  motion.values = MatrixRowMajor::Zero(frames, motion.skeleton.channelCount());
  for (int f = 0; f < frames; ++f) {
    const double t = f / fps;
    for (int j = 0; j < motion.skeleton.jointCount(); ++j) {
      const Joint& joint = motion.skeleton.joints[static_cast<size_t>(j)];
      if (joint.end_site) continue;
      int column = offsets[static_cast<size_t>(j)];
      if (joint.channels.size() == 6) {
        const Eigen::Vector3d position =
            j == 0 ? Eigen::Vector3d(3.0 * std::sin(1.1 * t), 89.0 + 1.0 * std::sin(2.3 * t), 2.0 * std::sin(0.7 * t))
                   : joint.offset;
        for (int axis = 0; axis < 3; ++axis) motion.values(f, column + axis) = position[axis];
        column += 3;
      }
      const double phase = 0.37 * j;
      const bool leg = joint.name.find("Leg") != std::string::npos || joint.name.find("Foot") != std::string::npos;
      const double amplitude = leg ? 6.0 : 12.0;
      const bool knee = joint.name == "LeftLeg" || joint.name == "RightLeg";
      for (int k = 0; k < 3; ++k)
        motion.values(f, column + k) = amplitude * std::sin((0.8 + 0.3 * k) * t + phase + k) + (knee && k == 1 ? 15.0 : 0.0);
    }
  }
  return motion;
}

// frames x 63: world positions of the 21 mapped joints, file space.
inline Eigen::MatrixXd canonicalPositions(const Eigen::MatrixXd& world, const JointMapping& mapping) {
  Eigen::MatrixXd canonical(world.rows(), 3 * kCanonicalJointCount);
  for (int c = 0; c < kCanonicalJointCount; ++c)
    canonical.middleCols<3>(3 * c) = world.middleCols<3>(3 * mapping.joints[static_cast<size_t>(c)]);
  return canonical;
}

// The quality metrics of a cleaned clip (`world`: its world positions, every joint) against the targets
// it was cleaned toward, judged by `contacts` on the content's floor: what the clean-up tests and
// bench_ik report.
inline ClipMetrics cleanedClipMetrics(const Eigen::MatrixXd& world, const Motion& clip, const JointMapping& mapping,
                                      const Eigen::MatrixXi& contacts, const Eigen::MatrixXd& targets,
                                      const Eigen::Vector3d& up, double floor_height, double cm_per_unit) {
  MetricsInput input{world, mapping.joints, skeletonBones(clip.skeleton)};
  input.contacts = contacts;
  input.targets = targets;
  input.up = up;
  input.floor_height = floor_height;
  input.cm_per_unit = cm_per_unit;
  input.fps = clip.fps();
  return computeMetrics(input);
}

struct Damage {
  double noise_cm = 2.0;          // RMS (3-D) of smooth per-joint noise, 0.5-3 Hz
  double jitter_cm = 0.3;         // RMS (3-D) of white per-frame noise
  double slide_cm_s = 6.0;        // horizontal drift speed of a foot joint during its contacts
  double bone_change = 0.03;      // each canonical bone scaled by 1 +- this
  unsigned seed = 7;
};

// Damaged copy of canonical `targets` (frames x 63, file units). contacts: frames x 4.
inline Eigen::MatrixXd damageTargets(const Eigen::MatrixXd& targets, const Eigen::MatrixXi& contacts, double fps,
                                     double cm_per_unit, const Eigen::Vector3d& up, const Damage& damage) {
  std::mt19937 rng(damage.seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Index frames = targets.rows();
  const double unit = 1.0 / cm_per_unit;

  // Bone lengths: rebuild along the canonical tree with each bone vector scaled.
  Eigen::MatrixXd out = targets;
  std::array<double, kCanonicalJointCount> scale{};
  for (double& s : scale) s = 1.0 + (uniform(rng) < 0.5 ? -1.0 : 1.0) * damage.bone_change;
  for (Eigen::Index f = 0; f < frames; ++f)
    for (int c = 1; c < kCanonicalJointCount; ++c) {
      const int parent = kCanonicalParent[static_cast<size_t>(c)];
      const Eigen::Vector3d bone = (targets.block<1, 3>(f, 3 * c) - targets.block<1, 3>(f, 3 * parent)).transpose();
      out.block<1, 3>(f, 3 * c) = out.block<1, 3>(f, 3 * parent) + scale[static_cast<size_t>(c)] * bone.transpose();
    }

  // Smooth noise: per joint and axis a sum of three sinusoids (0.5-3 Hz) with RMS noise_cm / sqrt(3).
  for (int c = 0; c < kCanonicalJointCount; ++c)
    for (int axis = 0; axis < 3; ++axis)
      for (int k = 0; k < 3; ++k) {
        const double hz = 0.5 + 2.5 * uniform(rng);
        const double phase = 2.0 * M_PI * uniform(rng);
        const double amplitude = damage.noise_cm * unit * std::sqrt(2.0 / 9.0);
        for (Eigen::Index f = 0; f < frames; ++f)
          out(f, 3 * c + axis) += amplitude * std::sin(2.0 * M_PI * hz * static_cast<double>(f) / fps + phase);
      }
  for (Eigen::Index f = 0; f < frames; ++f)
    for (Eigen::Index column = 0; column < out.cols(); ++column)
      out(f, column) += damage.jitter_cm * unit / std::sqrt(3.0) * normal(rng);

  // Foot sliding: a horizontal drift during each contact segment, easing back over 10 frames after it.
  for (int label = 0; label < kContactCount; ++label) {
    const int c = index(kContactJoint[static_cast<size_t>(label)]);
    for (const ContactSegment& segment : contactSegments(contacts, label)) {
      Eigen::Vector3d direction(normal(rng), normal(rng), normal(rng));
      direction -= up.dot(direction) * up;
      direction.normalize();
      const Eigen::Vector3d velocity = direction * damage.slide_cm_s * unit / fps;  // per frame
      const double length = segment.last - segment.first;
      for (int f = segment.first; f <= std::min<int>(static_cast<int>(frames) - 1, segment.last + 10); ++f) {
        const double t = f <= segment.last ? f - segment.first : length * (1.0 - (f - segment.last) / 10.0);
        out.block<1, 3>(f, 3 * c) += (velocity * t).transpose();
      }
    }
  }
  return out;
}

}  // namespace motionstyle::test
