#pragma once
// The 21 canonical joints of the paper's representation: which anatomical point each one is.
//
// The enum, its order (= the feature order) and the canonical parent table live in
// features/feature_layout.h; this header defines what each joint MEANS on a user's rig, names them and
// pairs them left/right. joint_mapping.h finds them on a rig; mapping_file.h lets the user state them.
//
// Definitions (a "joint" is a point: the origin of a BVH JOINT or End Site):
//   Hips          the pelvis: the root of both legs and of the spine (the lowest joint that is an
//                 ancestor of both thighs and of the spine). Not a "joint_Root" placed above it.
//   LeftHip       the thigh's root, i.e. the hip BALL joint (CMU "LeftHip", Mixamo "LeftUpLeg",
//                 Bandai "UpperLeg_L"). Not CMU's zero-length "LHipJoint" connector.
//   LeftKnee      the knee (the shin's root).
//   LeftAnkle     the ankle (the foot's root).
//   LeftToe       the ball of the foot / toe base (CMU "LeftToe", Mixamo "LeftToeBase"). The toe tip End
//                 Site is used only when the foot has no toe joint at all.
//   Spine         the first spine joint above the hips with a non-zero offset (the lower back).
//   Chest         the last spine joint below the neck: the joint the arms (clavicles) branch off.
//   Neck          the base of the neck: the first joint above the chest with a non-zero offset.
//   Head          the head joint (the skull's root), not the head's End Site or "HeadTop_End".
//   LeftUpperArm  the shoulder BALL joint (the upper arm's root), not the clavicle: CMU 131 names it
//                 "LeftShoulder", Mixamo "LeftArm" (Mixamo's "LeftShoulder" is the clavicle).
//   LeftElbow     the elbow (the forearm's root).
//   LeftWrist     the wrist (the hand's root).
//   LeftHandEnd   the tip of the hand chain, pointing along the fingers: the deepest joint of the
//                 hand's main chain (index or middle finger, else the longest) that lies away from the
//                 wrist (CMU "LFingers", cgspeed "LeftHandIndex1", AnimatedDrawings "LeftHandEnd").
//                 When the hand ends in an End Site with a zero offset (Bandai), that End Site is used,
//                 so this bone has zero length on such rigs.
// Right-side joints mirror the left ones. Left/right is the CHARACTER's left/right, read from the rig's
// joint names (never from geometry).
//
// The paper's 2016 code kept the same set: hips; per leg hip, knee, ankle, toe; spine, spine1, neck1,
// head; per arm arm, forearm, hand, hand index. No clavicles.

#include <array>
#include <optional>
#include <string_view>
#include <utility>

#include "features/feature_layout.h"

namespace motionstyle {

enum class BodySide { Center, Left, Right };

// Every canonical joint, in feature order (for range-for loops).
constexpr std::array<CanonicalJoint, kCanonicalJointCount> kAllCanonicalJoints = [] {
  std::array<CanonicalJoint, kCanonicalJointCount> all{};
  for (int j = 0; j < kCanonicalJointCount; ++j) all[static_cast<size_t>(j)] = static_cast<CanonicalJoint>(j);
  return all;
}();

// Left/right pairs, left first.
constexpr std::array<std::pair<CanonicalJoint, CanonicalJoint>, 8> kMirrorPairs = {{
    {CanonicalJoint::LeftHip, CanonicalJoint::RightHip},
    {CanonicalJoint::LeftKnee, CanonicalJoint::RightKnee},
    {CanonicalJoint::LeftAnkle, CanonicalJoint::RightAnkle},
    {CanonicalJoint::LeftToe, CanonicalJoint::RightToe},
    {CanonicalJoint::LeftUpperArm, CanonicalJoint::RightUpperArm},
    {CanonicalJoint::LeftElbow, CanonicalJoint::RightElbow},
    {CanonicalJoint::LeftWrist, CanonicalJoint::RightWrist},
    {CanonicalJoint::LeftHandEnd, CanonicalJoint::RightHandEnd},
}};

// "Hips", "LeftHip", ..., "RightHandEnd": the enumerator's name, used in mapping files and messages.
std::string_view canonicalJointName(CanonicalJoint joint);

// "left heel", "left toe", "right heel", "right toe": a contact label (ContactLabel order) as messages
// name it; "?" outside 0..kContactCount - 1.
std::string_view contactLabelName(int label);

// The canonical joint with this name, compared ASCII case-insensitively; nullopt for anything else.
std::optional<CanonicalJoint> canonicalJointFromName(std::string_view name);

// The other side's joint (LeftKnee <-> RightKnee); centre joints map to themselves.
CanonicalJoint mirrorJoint(CanonicalJoint joint);

BodySide sideOf(CanonicalJoint joint);

// The canonical parent (kCanonicalParent), or nullopt for the hips.
std::optional<CanonicalJoint> canonicalParent(CanonicalJoint joint);

}  // namespace motionstyle
