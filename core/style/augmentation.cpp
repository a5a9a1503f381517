#include "style/augmentation.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include "mapping/canonical_joints.h"
#include "nn/compute_pool.h"
#include "nn/losses.h"

namespace motionstyle::style {
namespace {

using C = CanonicalJoint;

bool isGirdleBone(int joint) {
  switch (static_cast<C>(joint)) {
    case C::LeftHip: case C::RightHip: case C::LeftUpperArm: case C::RightUpperArm: case C::LeftToe: case C::RightToe:
      return true;
    default:
      return false;
  }
}

Eigen::Quaterniond randomRotation(double max_degrees, std::mt19937& rng) {
  if (max_degrees <= 0.0) return Eigen::Quaterniond::Identity();
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector3d axis(normal(rng), normal(rng), normal(rng));
  if (axis.norm() < 1e-12) axis = Eigen::Vector3d::UnitX();
  std::uniform_real_distribution<double> angle(0.0, max_degrees * std::numbers::pi / 180.0);
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle(rng), axis.normalized()));
}

void requireRange(double value, double low, double high, const char* name) {
  if (!(value >= low && value <= high))
    throw std::invalid_argument(std::string("augmentation: ") + name + " must be in [" + std::to_string(low) + ", " +
                                std::to_string(high) + "]");
}

}  // namespace

bool AugmentationOptions::enabled() const {
  return girdle_offset_degrees > 0.0 || offset_degrees > 0.0 || proportion_jitter > 0.0 || time_warp > 1.0 ||
         mirror_probability > 0.0;
}

void AugmentationOptions::validate() const {
  requireRange(girdle_offset_degrees, 0.0, 90.0, "girdle_offset_degrees");
  requireRange(offset_degrees, 0.0, 90.0, "offset_degrees");
  requireRange(proportion_jitter, 0.0, 0.49, "proportion_jitter");
  requireRange(time_warp, 1.0, 2.0, "time_warp");
  requireRange(mirror_probability, 0.0, 1.0, "mirror_probability");
}

std::string describe(const AugmentationOptions& options) {
  char text[160];
  std::snprintf(text, sizeof text, "girdle %g deg, offsets %g deg, proportions %g, warp %g, mirror %g",
                options.girdle_offset_degrees, options.offset_degrees, options.proportion_jitter, options.time_warp,
                options.mirror_probability);
  return text;
}

AugmentationOptions defaultAugmentation() {
  AugmentationOptions options;
  options.girdle_offset_degrees = 75.0;
  options.offset_degrees = 20.0;
  options.mirror_probability = 0.5;
  return options;
}

AugmentationOptions defaultContentAugmentation() {
  AugmentationOptions options;
  options.offset_degrees = 20.0;
  options.mirror_probability = 0.5;
  return options;
}

Augmentation::Augmentation() {
  offset_rotation.fill(Eigen::Quaterniond::Identity());
  bone_scale.fill(1.0);
}

Augmentation drawAugmentation(const AugmentationOptions& options, std::mt19937& rng) {
  options.validate();
  Augmentation a;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int c = 1; c < kCanonicalJointCount; ++c)
    a.offset_rotation[static_cast<std::size_t>(c)] =
        randomRotation(isGirdleBone(c) ? options.girdle_offset_degrees : options.offset_degrees, rng);
  if (options.proportion_jitter > 0.0) {
    std::uniform_real_distribution<double> jitter(-options.proportion_jitter, options.proportion_jitter);
    for (int c = 1; c < kCanonicalJointCount; ++c) a.bone_scale[static_cast<std::size_t>(c)] = 1.0 + jitter(rng);
    if (unit(rng) < 0.5)  // symmetric: each right bone takes its left twin's factor
      for (const auto& [left, right] : kMirrorPairs)
        a.bone_scale[static_cast<std::size_t>(index(right))] = a.bone_scale[static_cast<std::size_t>(index(left))];
  }
  if (options.time_warp > 1.0) {
    std::uniform_real_distribution<double> log_speed(-std::log(options.time_warp), std::log(options.time_warp));
    a.speed = std::exp(log_speed(rng));
  }
  a.mirror = unit(rng) < options.mirror_probability;
  return a;
}

Motion augmentMotion(const Motion& motion, const JointMapping& mapping, const Augmentation& augmentation) {
  Motion out = motion;
  const std::vector<int> channel_offsets = out.skeleton.channelOffsets();
  for (int c = 1; c < kCanonicalJointCount; ++c) {
    const int joint = mapping.joints[static_cast<std::size_t>(c)];
    if (joint <= 0 || joint >= out.skeleton.jointCount()) continue;
    const Eigen::Matrix3d change = augmentation.bone_scale[static_cast<std::size_t>(c)] *
                                   augmentation.offset_rotation[static_cast<std::size_t>(c)].toRotationMatrix();
    Joint& rig_joint = out.skeleton.joints[static_cast<std::size_t>(joint)];
    rig_joint.offset = change * rig_joint.offset;
    // A joint with position channels takes its translation from them (motion/kinematics.h): change
    // those too, frame by frame, when all three are there (a joint with only some keeps its offset's
    // other components and is left as it is).
    std::array<int, 3> column{-1, -1, -1};
    for (std::size_t k = 0; k < rig_joint.channels.size(); ++k)
      if (!isRotation(rig_joint.channels[k]))
        column[static_cast<std::size_t>(axisOf(rig_joint.channels[k]))] = channel_offsets[static_cast<std::size_t>(joint)] + static_cast<int>(k);
    if (column[0] < 0 || column[1] < 0 || column[2] < 0) continue;
    for (Eigen::Index f = 0; f < out.values.rows(); ++f) {
      const Eigen::Vector3d t = change * Eigen::Vector3d(out.values(f, column[0]), out.values(f, column[1]), out.values(f, column[2]));
      for (int axis = 0; axis < 3; ++axis) out.values(f, column[static_cast<std::size_t>(axis)]) = t[axis];
    }
  }
  out.frame_time = motion.frame_time / augmentation.speed;
  return out;
}

void mirrorClip(MotionClip& clip) {
  Eigen::MatrixXd& x = clip.features.values;
  for (int c = 0; c < kCanonicalJointCount; ++c) x.row(3 * c) *= -1.0;
  for (const auto& [left, right] : kMirrorPairs)
    for (int axis = 0; axis < 3; ++axis) x.row(3 * index(left) + axis).swap(x.row(3 * index(right) + axis));
  x.row(kSidewaysVelocity) *= -1.0;
  x.row(kTurningVelocity) *= -1.0;
  Eigen::MatrixXd& contacts = clip.features.contacts;
  using L = ContactLabel;
  contacts.row(static_cast<int>(L::LeftHeel)).swap(contacts.row(static_cast<int>(L::RightHeel)));
  contacts.row(static_cast<int>(L::LeftToe)).swap(contacts.row(static_cast<int>(L::RightToe)));
  if (clip.bone_lengths.size() == nn::kBoneCount)
    for (const auto& [left, right] : kMirrorPairs) std::swap(clip.bone_lengths[index(left) - 1], clip.bone_lengths[index(right) - 1]);
}

MotionClip augmentedClip(const Motion& motion, const JointMapping& mapping, const MotionClip& original,
                         const Augmentation& augmentation, const DatasetOptions& options) {
  MotionClip clip = makeMotionClip(augmentMotion(motion, mapping, augmentation), mapping, original.file, options);
  clip.labels = original.labels;
  if (augmentation.mirror) mirrorClip(clip);
  return clip;
}

std::vector<MotionClip> augmentedEpoch(const std::vector<MotionClip>& clips, const AugmentationOptions& options,
                                       std::uint32_t seed, int epoch, const DatasetOptions& dataset) {
  options.validate();
  std::vector<MotionClip> out(clips.size());
  nn::computePool().run(static_cast<int>(clips.size()), [&](int i) {
    const MotionClip& clip = clips[static_cast<std::size_t>(i)];
    MotionClip& result = out[static_cast<std::size_t>(i)];
    if (!options.enabled() || !clip.motion) {
      result = clip;
      return;
    }
    std::seed_seq sequence{seed, static_cast<std::uint32_t>(epoch), 3u, static_cast<std::uint32_t>(i)};
    std::mt19937 rng(sequence);
    try {
      result = augmentedClip(*clip.motion, clip.features.mapping, clip, drawAugmentation(options, rng), dataset);
      result.motion = clip.motion;
    } catch (const std::exception&) {
      result = clip;  // e.g. too short once sped up: the clip as it is
    }
  });
  return out;
}

}  // namespace motionstyle::style
