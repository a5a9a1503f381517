#pragma once
// Body proportions of the 21 canonical joints, and the retargeting between a character's own
// proportions and the REFERENCE proportions every clip is given before it meets the networks.
//
// Why: scaling every character to one skeletal height (feature_layout.h) leaves its proportions. Rigs
// differ a lot at that scale: CMU's hip joints sit 13 cm apart where the Bandai actor's sit 6.8 cm;
// the zombie rig's legs are 69 cm long against 80; spine, chest and neck are split differently; some
// exports have hand ends and some do not. Networks trained on one actor then see other rigs out of
// distribution: before this step the loss network reconstructed held-out Bandai clips with a mean
// joint error of 0.79 cm but the CMU and zombie samples with 5.2 and 5.0 cm, and the stylized output
// of those rigs had 3 cm bone errors that the clean-up could only spread around (residual 3.3-4.1 cm).
// With it (networks retrained): 0.83 cm on Bandai, 4.6 and 3.8 cm on CMU and zombie; what is left is
// motion the dataset lacks (both samples are stylised walks; resources/models/README.md).
//
// The retargeting, on root-frame features (66 x frames, reference cm; feature_layout.h), from
// proportions A to B:
//   - every bone vector d_c = p_c - p_parent(c) is scaled by B.bone_length[c] / A.bone_length[c] and the
//     joints are rebuilt from the hips outward, so each bone keeps its direction (and any per-frame
//     variation of a non-rigid bone, such as chest to shoulder, keeps its relative size);
//   - the hips' offset from the root and the sideways and forward root velocities are scaled by
//     B.legLength() / A.legLength(), so that feet stay on the floor and strides fit the new legs;
//   - the turning velocity is unchanged.
// Retargeting A -> B -> A is the identity (up to rounding) wherever both have a length. A bone with no
// length in the target proportions collapses onto its parent; a bone with no length in the source
// proportions (no direction: a rig without hand ends going to proportions with hands) is laid along
// its parent bone. The reference proportions have every bone, so any rig's bones keep their
// directions through the networks and back.

#include <Eigen/Core>
#include <array>
#include <limits>

#include "features/feature_layout.h"

namespace motionstyle {

struct Proportions {
  // Length of the bone from joint c to kCanonicalParent[c], reference cm; entry 0 (the hips) is 0.
  std::array<double, kCanonicalJointCount> bone_length{};

  // Mean over both legs of hip-knee + knee-ankle, reference cm.
  double legLength() const;
  // Throws std::invalid_argument unless every length is finite and >= 0 and the legs have a length.
  void validate() const;
};

// Bones shorter than this (reference cm) have no usable direction.
constexpr double kMinimumBoneLengthCm = 1e-3;

// The reference: the Bandai Namco Research dataset's actor at the reference skeletal height (both parts
// of the dataset share the skeleton), mean bone lengths over the dataset-2 normal-style clips rounded to
// 0.01 cm (canonicalBoneLengths of extractFeatures without retargeting). The dataset-2 exports end the
// arms at the wrists; the hand ends (wrist to hand tip, 4.98 cm) are those of the dataset-1 exports
// that have them, so that rigs with hands keep their wrists' bend through the networks.
const Proportions& referenceProportions();

// The mean bone lengths of root-frame features (66 x frames, at least one frame).
Proportions measureProportions(const Eigen::MatrixXd& features);

// Retargets root-frame features (66 x frames) in place from proportions `from` to `to` (see above).
// Throws std::invalid_argument for features that are not 66 rows or invalid proportions.
void retargetFeatures(Eigen::MatrixXd& features, const Proportions& from, const Proportions& to);

// Sets every bone of root-frame features (66 x frames) to its length in `proportions`, frame by frame,
// keeping its direction: joints are rebuilt from the hips outward, p_c = p_parent + l_c * unit(p_c -
// p_parent) with the bone as the features had it (a bone without direction, shorter than
// kMinimumBoneLengthCm, is laid along its parent bone as in retargetFeatures). Network outputs get it
// so that their targets are reachable by the character's own limbs (the IK clean-up keeps bones
// exact: a target 2 cm beyond reach is a 2 cm residual). Throws std::invalid_argument as retargetFeatures.
void enforceBoneLengths(Eigen::MatrixXd& features, const Proportions& proportions);

// A stance is one where the foot joint stays within this radius of its median place over the contact
// (horizontally, cm: the reference character's in features, below; the clip's own in the clean-up);
// further, the style moved the step: the stylizer does not hold it (below) and the clean-up does not
// lock it (style/stylized_cleanup.cpp says why).
inline constexpr double kLockableSpreadCm = 20.0;
// How far a kept heel or toe may stray from its stance's place (below), cm. Why not 0: a stance held
// still takes style with it (the network's foot wanders a little within a stance as part of it); at 3
// cm the style ratios moved by at most 2.6 % (docs/decisions.md, "Stances held in the stylizer").
inline constexpr double kKeptFootRadiusCm = 3.0;

// The same, keeping planted feet in place: rebuilt from the hips outward, a leg carries the sum of its
// bones' errors to the foot (the network's decoded thigh is 35-42 cm where the reference's is 38.9),
// so a foot that stood still through a contact slides once the lengths are set. Here, after
// enforceBoneLengths, each leg's knee is solved again (two-bone IK in the plane of the enforced knee,
// the bones' lengths exact) so that the ankle takes back its horizontal place from before, by weight
// w = 1 on a contact frame of the ankle or toe, falling linearly to 0 over kKeptFootRampFrames either
// side; that place lies between the ankle's from before and the one that keeps the toe's, by the toe's
// share of the two weights (only the toe planted: the toe's place; both: halfway). Where the heel or
// toe has a stance (kLockableSpreadCm) over the frame or the ramp next to it, its place from before is
// first pulled, on the floor (the root path integrated from the features' root velocities), to within
// kKeptFootRadiusCm of the stance's place, the median of its places over the stance's contact frames:
// the manifold's contact projection (style/contact_projection.h) plants most of a slide, not all. Its height
// takes back its changes from before, and its level only where the enforcement sank it: over each
// span of frames with w > 0 the ankle rises by w (d - min(mean d, 0)), d the height from before less
// the enforced one, the mean over the span's contact frames. A planted foot keeps a still height; where
// the enforcement raised it the knee's mean bend, which is style, stays the enforced one (keeping that
// level too weakened elderly, sad and exhausted); where it sank it, into the floor the projection had
// planted it on, the clean-up lifted it back and the depth was residual (docs/decisions.md, "A planted
// foot the bones sank"). A place out of the leg's reach is pulled in to it. contacts: 4 x frames (0/1,
// ContactLabel order), or empty for enforceBoneLengths alone. Throws std::invalid_argument as
// enforceBoneLengths, and for contacts of another shape.
//
// planted_toe_height (NaN: none): the lowest a planted toe may stand. On a frame with the toe's weight
// w > 0 whose toe, from the kept ankle's height along the foot's direction, would stand lower, the
// foot is turned up about the ankle (its heading kept) by w toward the direction that puts the toe
// there, and the ankle placed from the toe's place along it as above. Why: in a rig whose toe bone
// points lower than the reference's, a foot the style tips onto its toe puts the toe through the floor
// (the zombie with happy: 4-8 cm under its planted height), where the clean-up's lock cannot follow.
inline constexpr int kKeptFootRampFrames = 4;
void enforceBoneLengths(Eigen::MatrixXd& features, const Proportions& proportions, const Eigen::MatrixXd& contacts,
                        double planted_toe_height = std::numeric_limits<double>::quiet_NaN());

}  // namespace motionstyle
