#pragma once
// The paper's motion representation ("Data Representation"), computed from a clip and inverted back.
// Layout of the 66 values: see feature_layout.h. Pipeline of extractFeatures():
//   0. a leading rest-pose frame (CMU's T-pose frame 0) replaced by the motion continued backward
//      (rest_pose_frames.h),
//   1. resample to `fps` (default 60; slerp rotations, linear positions),
//   2. forward kinematics, canonical joints only, converted to canonical space (Y-up, cm),
//   3. scaled by kReferenceSkeletalHeightCm / the character's skeletal height, so that characters of
//      any size and unit meet the networks at one reference scale,
//   4. floor: the clip is lowered so that a soft minimum of its feet's heights is at y = 0,
//   5. root: the hips projected on the floor, Gaussian-smoothed (sigma 3 frames at 60 fps);
//      facing: (left - right across the hips and across the shoulders) x up, Gaussian-smoothed
//      (sigma 20 frames) - as in Holden et al. 2016's preprocessing,
//   6. joints expressed in the root frame; root velocities (sideways, forward, turning) per frame,
//   7. retargeted from the clip's own proportions to the reference proportions (proportions.h): the
//      networks see every rig with one actor's bone lengths; the clip's own are kept in the anchor;
//   8. content clips: the rig's girdle placement (hip joints, shoulders, toes) turned to the reference
//      actor's (rig_canonicalisation.h); the correction is kept in the anchor;
//   9. heights shifted so that the planted toes stand as high as the reference actor's
//      (kReferenceStanceToeHeightCm; their median over the clip's toe contacts), or, in a clip whose
//      toes are never planted, so that the feet's soft minimum is on the floor again.
// Contacts are detected on the clip's own positions (step 5's frame, before 7). The inverse undoes 8,
// retargets back to the clip's proportions, integrates the velocities from the anchor and undoes steps 2-4,
// giving world positions of the canonical joints in the clip's own file space (units and axes).

#include <Eigen/Core>
#include <optional>
#include <string>

#include "features/feature_layout.h"
#include "features/proportions.h"
#include "features/rig_canonicalisation.h"
#include "features/space_convention.h"
#include "mapping/joint_mapping.h"
#include "motion/motion.h"

namespace motionstyle {

// Everything needed to map features back to the clip's file space.
struct FeatureAnchor {
  SpaceConvention convention;
  double scale = 1.0;               // reference cm per canonical cm (features = scale * canonical)
  double floor_height = 0.0;        // height of the floor before it was moved to y = 0, reference cm
  Eigen::Vector2d start_root = Eigen::Vector2d::Zero();  // root (x, z) at frame 0, reference cm
  double start_heading = 0.0;       // facing angle at frame 0, radians (0 = +Z, positive toward +X)
  double fps = kDefaultFeatureFps;
  // The clip's own proportions (reference cm), which the inverse retargets the features back to. The
  // reference proportions when the features were not retargeted (the inverse then changes nothing).
  Proportions proportions = referenceProportions();
  // The girdle correction of step 8 (identity when off).
  RigCorrection rig;
  // Added to every height after steps 7 and 8 (step 9), reference cm: new bone lengths and girdle
  // placement move the planted feet up or down (CMU's hip joints hang 4 cm lower than the actor's), and
  // where a capture's floor lies under the feet differs by studio. The inverse subtracts it before
  // undoing 7 and 8.
  double retarget_height_shift = 0.0;
  // Leading frames of the clip that are its rig's rest pose, not motion (rest_pose_frames.h): the
  // features see the motion continued backward over them, and the clean-up puts them back.
  int rest_pose_frames = 0;
};

struct FeatureOptions {
  double fps = kDefaultFeatureFps;
  std::optional<std::string> unit;  // override the guessed length unit ("cm", "m", "inch", "cmu", ...)
  double root_smoothing_frames = 3.0;
  double facing_smoothing_frames = 20.0;
  bool retarget_proportions = true;  // step 7; off only to reproduce networks trained without it
  // Step 8, for content clips (what the networks transform, and how familiar it is); off for style
  // clips, whose girdle posture is part of the style, and the loss network's own training data.
  bool canonical_rig = true;
  // A clip derived from another on the same skeleton (a cleaned or edited result of it): that clip's
  // anchor. Its floor (step 4), proportions (7), girdle correction (8) and height shift (9) are used
  // instead of being measured on this clip, so that the two are compared in one frame: measured anew,
  // a cleaned run's few toe contacts moved its step-9 shift by 6 cm and its style distance 4x
  // (docs/decisions.md, "The lock at the stance's minimax point").
  std::optional<FeatureAnchor> derived_from;
};

// Step 9's target: the planted toes' height above the floor in the reference actor's clips, reference
// cm (the median over the 184 Bandai dataset-2 normal-style clips of each clip's median, after steps
// 1-8 with the soft-minimum floor; their 10th-90th percentiles 0.15-0.48). Why not the soft minimum
// alone: CMU clips' lowest foot joint wanders 3-4 cm over a clip (uneven floors, toe markers), so their
// planted feet stood 3-4 cm higher than any training clip's and the style networks, which learnt the
// actor's stance heights, sank them by as much (docs/decisions.md).
constexpr double kReferenceStanceToeHeightCm = 0.34;

// Computed result for one clip.
struct MotionFeatures {
  Eigen::MatrixXd values;    // kFeatureCount x frames (each column a frame), units per feature_layout.h
  Eigen::MatrixXd contacts;  // kContactCount x frames, 0 or 1
  FeatureAnchor anchor;
  JointMapping mapping;

  int frameCount() const { return static_cast<int>(values.cols()); }
};

// Full pipeline. Throws InputError (naming motion.source) when the rig cannot be mapped or the clip is
// too short (fewer than 2 frames after resampling).
MotionFeatures extractFeatures(const Motion& motion, const JointMapping& mapping, const FeatureOptions& options = {});

// Inverse: features -> world positions of the 21 canonical joints, frames x 63, in the clip's FILE
// space (file units and axes), by integrating the root velocities from anchor.start_root/heading.
Eigen::MatrixXd canonicalWorldPositions(const Eigen::MatrixXd& features, const FeatureAnchor& anchor);

// Same, but in reference canonical space (Y-up, reference cm, floor at 0): used by metrics and the
// viewport. Columns as above.
Eigen::MatrixXd referenceWorldPositions(const Eigen::MatrixXd& features, const FeatureAnchor& anchor);

// The stylizer's stance hold (enforceBoneLengths with contacts, proportions.h) done again where the
// output lands: in the clip's own rig and proportions (steps 9-7 undone, then redone). Why: retargeting
// a bent leg scales its thigh and shin apart, so a stance held in the reference proportions slides
// again in the clip's own (CMU 131_01's kneel: 3.8 cm held, 9.6 cm after). The content's planted toes'
// height there (the median over its toe contacts) is the lowest a planted toe may stand. features: 66 x
// the content's frames, of the content (its anchor and contacts; none: nothing to hold). Throws
// std::invalid_argument for features or contacts of another shape.
void holdStancesInOwnRig(Eigen::MatrixXd& features, const MotionFeatures& content);

// World positions (file space, frames x 63) of the canonical joints of a clip at its own rate,
// straight from forward kinematics: the ground truth that the inverse must reproduce.
Eigen::MatrixXd canonicalJointPositions(const Motion& motion, const JointMapping& mapping);

// Mean length of each canonical bone (joint c to kCanonicalParent[c]; 0 for the hips) over the clip,
// in reference cm, from its features (measureProportions as a vector). For retargeted features these
// are the reference proportions'.
Eigen::VectorXd canonicalBoneLengths(const Eigen::MatrixXd& features);

}  // namespace motionstyle
