#pragma once
// Training-data augmentation: the variations that clips of other studios, actors and rigs bring,
// drawn at random per clip, so that the networks learn motion rather than one studio's rig.
//
//   rig offsets   every canonical joint's OFFSET in the rig (its rest position in its rig parent's
//                 frame) turned by a random rotation: an axis uniform on the sphere, an angle uniform in
//                 [0, max]. Girdle bones (hips to hip joints, chest to shoulders, ankle to toe), whose
//                 placement differs most between rigs (a CMU rig's hip joints hang 25 degrees lower and
//                 its shoulders sit 30 degrees further out than the Bandai actor's), take
//                 girdle_offset_degrees; the others offset_degrees. Applied to the Motion's skeleton.
//   proportions   every canonical bone's offset scaled by 1 + U(-j, j) (the same factor for a left/right
//                 pair with probability 1/2, "symmetric"). Retargeting to the reference proportions
//                 (features/proportions.h) undoes bone lengths, so this only reaches the networks
//                 through the stride/leg-length relation and bones that are not canonical.
//   time warp     playback speed s drawn log-uniformly in [1/w, w]: frame time x 1/s, so the clip
//                 is resampled to the representation's rate faster or slower.
//   mirror        with probability p: left and right swapped (features: x negated, left/right joints
//                 and contacts swapped, sideways and turning velocities negated).
// Root height and heading need no augmentation: the representation puts every clip on the floor and in
// its own root frame (feature_layout.h), so both change nothing (AugmentationTest.HeightAndHeadingAreInvariant).

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "features/feature_layout.h"
#include "mapping/joint_mapping.h"
#include "motion/motion.h"
#include "style/motion_dataset.h"

namespace motionstyle::style {

struct AugmentationOptions {
  double girdle_offset_degrees = 0.0;  // max rotation of girdle bones' rig offsets
  double offset_degrees = 0.0;         // max rotation of the other canonical bones' rig offsets
  double proportion_jitter = 0.0;      // bone length factor 1 +- this
  double time_warp = 1.0;              // speed factor in [1/w, w]; 1 = off
  double mirror_probability = 0.0;     // in [0, 1]

  bool enabled() const;
  // Throws std::invalid_argument naming the field: angles in [0, 90], jitter in [0, 0.5), warp in
  // [1, 2], probability in [0, 1], all finite.
  void validate() const;
  bool operator==(const AugmentationOptions&) const = default;
};

// "girdle 30 deg, offsets 8 deg, proportions 0, warp 1.25, mirror 0.5": metadata and fingerprints.
std::string describe(const AugmentationOptions& options);

// The options the measurements chose (docs/decisions.md): for the loss network, girdle 75 degrees,
// offsets 20, mirroring 0.5 (no time warp or proportions: they changed nothing); for a style
// network's content, offsets 20 and mirroring 0.5 (its content is rig-canonicalised, which turns the
// girdle back anyway). The CLI's train-loss-network and train-style use them unless told otherwise.
AugmentationOptions defaultAugmentation();
AugmentationOptions defaultContentAugmentation();

// One draw: the parameters of one augmented copy of a clip.
struct Augmentation {
  std::array<Eigen::Quaterniond, kCanonicalJointCount> offset_rotation;  // entry 0 (hips) unused
  std::array<double, kCanonicalJointCount> bone_scale;                   // entry 0 unused
  double speed = 1.0;
  bool mirror = false;

  Augmentation();  // the identity
};

Augmentation drawAugmentation(const AugmentationOptions& options, std::mt19937& rng);

// The rig-level part (offsets, proportions, speed) on a copy of the motion; `mapping` finds the
// canonical joints' rig joints. Mirroring is applied to features (mirrorClip).
Motion augmentMotion(const Motion& motion, const JointMapping& mapping, const Augmentation& augmentation);

// Left/right swap of a clip's features, contacts and bone lengths (see the top of this file).
void mirrorClip(MotionClip& clip);

// augmentMotion, makeMotionClip, then mirrorClip when drawn: one augmented training clip.
MotionClip augmentedClip(const Motion& motion, const JointMapping& mapping, const MotionClip& original,
                         const Augmentation& augmentation, const DatasetOptions& options);

// One epoch's training clips: every clip that kept its motion (DatasetOptions::keep_motion) replaced
// by one augmented copy drawn from (seed, epoch, clip index), so an epoch's data does not depend on
// earlier epochs and a resumed run reproduces it; the others (and any copy that fails, e.g. too short
// once sped up) as they are. Clips are featurised in parallel on the nn compute pool.
std::vector<MotionClip> augmentedEpoch(const std::vector<MotionClip>& clips, const AugmentationOptions& options,
                                       std::uint32_t seed, int epoch, const DatasetOptions& dataset);

}  // namespace motionstyle::style
