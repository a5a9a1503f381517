#pragma once
// The paper's per-frame motion representation ("Data Representation"): 66 values per frame.
//
//   values [3j, 3j+1, 3j+2], j = 0..20 : canonical joint j's position (x, y, z) in the ROOT FRAME:
//        the root is the hips projected on the floor (y = 0); the frame is rotated so that the
//        character faces +Z; +Y is up; +X is the character's left. Units: centimetres at the
//        reference scale (the character scaled to kReferenceBodyHeightCm, see features.h).
//   values [63] : sideways root velocity  (local +X), cm per frame at the representation's fps
//   values [64] : forward root velocity   (local +Z), cm per frame
//   values [65] : turning velocity about +Y, radians per frame (positive turns +Z toward +X)
//
// Velocities at frame t describe the step from t to t+1, expressed in frame t's root frame:
//   v(t) = R(t)^-1 (r(t+1) - r(t)),  w(t) = theta(t+1) - theta(t)   (the last frame repeats t-1).
// R(t) is the rotation about +Y by the facing angle theta(t) = atan2(facing.x, facing.z).
// So a joint's world position is P_j(t) = r(t) + R(t) p_j(t), and the root is recovered by
// integrating v and w from an anchor (the first frame's root position and heading).
//
// Foot contacts are per-frame labels beside the 66 values, not part of them: see kContact*.

#include <array>

namespace motionstyle {

// The skeletal height (see space_convention.h) every character is scaled to before features are
// computed. Chosen as the mean skeletal height of the Bandai Namco actors, so their clips scale by ~1.
constexpr double kReferenceSkeletalHeightCm = 127.0;
// Frames per second of the representation: input at other rates is resampled.
constexpr double kDefaultFeatureFps = 60.0;

constexpr int kCanonicalJointCount = 21;
constexpr int kFeatureCount = 3 * kCanonicalJointCount + 3;  // 66
constexpr int kSidewaysVelocity = 63;
constexpr int kForwardVelocity = 64;
constexpr int kTurningVelocity = 65;

// Canonical joints, in feature order. See core/mapping/canonical_joints.h for their definitions.
enum class CanonicalJoint : int {
  Hips = 0,
  LeftHip, LeftKnee, LeftAnkle, LeftToe,
  RightHip, RightKnee, RightAnkle, RightToe,
  Spine, Chest, Neck, Head,
  LeftUpperArm, LeftElbow, LeftWrist, LeftHandEnd,
  RightUpperArm, RightElbow, RightWrist, RightHandEnd,
};

constexpr int index(CanonicalJoint j) { return static_cast<int>(j); }

// Parent of each canonical joint in the canonical tree (-1 for the hips). Bones for the bone-length
// loss are the (joint, parent) pairs.
constexpr std::array<int, kCanonicalJointCount> kCanonicalParent = {
    -1,                                     // Hips
    0, 1, 2, 3,                             // left leg
    0, 5, 6, 7,                             // right leg
    0, 9, 10, 11,                           // spine, chest, neck, head
    10, 13, 14, 15,                         // left arm hangs off the chest
    10, 17, 18, 19,                         // right arm
};

// Foot-contact labels: 4 per frame, 1 = in contact. Heel = ankle joint, toe = toe joint.
constexpr int kContactCount = 4;
enum class ContactLabel : int { LeftHeel = 0, LeftToe, RightHeel, RightToe };
constexpr std::array<CanonicalJoint, kContactCount> kContactJoint = {
    CanonicalJoint::LeftAnkle, CanonicalJoint::LeftToe, CanonicalJoint::RightAnkle, CanonicalJoint::RightToe};

}  // namespace motionstyle
