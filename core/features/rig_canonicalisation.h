#pragma once
// Rig canonicalisation: where a rig places its GIRDLE joints (the hip joints below the hips, the
// shoulders beside the chest, the toe joints before the ankles) made the reference actor's, so that
// content clips of any rig meet the networks with the geometry they learnt. The inverse puts the
// clip's own placement back, so the output keeps it.
//
// Why: after proportion retargeting (proportions.h) bone LENGTHS match, but girdle bone DIRECTIONS
// still differ by rig: a CMU rig's hip joints hang 29-40 degrees lower and further forward than the
// Bandai actor's, its shoulders sit 25-38 degrees further out; Bandai's own styles move these bones by
// at most 7 (hips) and 24-26 degrees (shoulders, toes). A style network compares Gram matrices, which
// carry that geometry, so on other rigs it spent its effort on geometry the rig cannot change
// (docs/decisions.md). Style clips keep their girdle posture (an elderly actor's forward shoulders are
// style): they are not canonicalised (FeatureOptions::canonical_rig).
//
// On root-frame features (66 x frames, reference cm): for each girdle bone c, m_c is the clip's mean
// unit bone direction and r_c the reference direction; Q_c is the shortest rotation taking m_c to r_c.
// Every frame's bone vector is turned by Q_c and the joints are rebuilt from the hips outward (children
// follow their parent). The inverse turns by Q_c^-1 the same way; the round trip is exact up to rounding.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>

#include "features/feature_layout.h"

namespace motionstyle {

// The girdle bones (a canonical joint and its canonical parent): hip joints, shoulders, toes.
constexpr std::array<CanonicalJoint, 6> kGirdleBones = {
    CanonicalJoint::LeftHip,       CanonicalJoint::RightHip, CanonicalJoint::LeftUpperArm,
    CanonicalJoint::RightUpperArm, CanonicalJoint::LeftToe,  CanonicalJoint::RightToe};

// The reference actor's mean direction of each canonical bone in the root frame (feature_layout.h:
// +X left, +Y up, +Z forward), for the girdle bones; other entries are zero. Measured over the Bandai
// dataset-2 normal-style walks, runs and turns after proportion retargeting, left and mirrored right
// averaged (the reference is symmetric, so mirroring a canonical clip keeps it canonical).
const std::array<Eigen::Vector3d, kCanonicalJointCount>& referenceGirdleDirections();

struct RigCorrection {
  std::array<Eigen::Quaterniond, kCanonicalJointCount> rotation;  // per bone; identity but for the girdle
  RigCorrection();                                                 // the identity
  bool isIdentity() const;
};

// The correction of a clip: features 66 x frames (at least one frame, reference proportions). A girdle
// bone without a direction (shorter than kMinimumBoneLengthCm in every frame) is left as it is.
// Throws std::invalid_argument for another row count or no frames.
RigCorrection measureRigCorrection(const Eigen::MatrixXd& features);

// Applies the correction (or its inverse) to features in place (see the top of this file).
void applyRigCorrection(Eigen::MatrixXd& features, const RigCorrection& correction, bool inverse = false);

}  // namespace motionstyle
