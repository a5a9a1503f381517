#pragma once
// Normalisation of a clip's length unit and up axis to MotionStyle's canonical space:
//   Y-up, right-handed, CENTIMETRES.
// Files differ: Bandai is Y-up in cm; the CMU/cgspeed conversions are Y-up in CMU's own unit
// (about 5.6 cm); AnimatedDrawings' zombie is Z-up in a small unit. Nothing in a BVH states its unit,
// so the unit is either given by the user or guessed from the character's skeletal height (below),
// and every tool reports which it assumed.
//
// canonical = cm_per_unit * (axes * file)

#include <Eigen/Core>
#include <optional>
#include <string>

#include "mapping/joint_mapping.h"
#include "motion/motion.h"
#include "motion/skeleton.h"

namespace motionstyle {

struct SpaceConvention {
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // proper rotation: file axes -> Y-up axes
  double cm_per_unit = 1.0;
  std::string unit = "cm";   // "cm", "m", "mm", "inch", "ft", "cmu" (CMU's 1/0.45 inch)
  bool unit_guessed = false;  // true when inferred from the skeleton's size
  std::string up_axis = "+Y";  // the file's up axis: "+Y", "+Z", "-Z", ...

  Eigen::Vector3d toCanonical(const Eigen::Vector3d& file_point) const { return cm_per_unit * (axes * file_point); }
  Eigen::Vector3d toFile(const Eigen::Vector3d& canonical_point) const {
    return axes.transpose() * canonical_point / cm_per_unit;
  }
  // The file's up direction as a unit vector in file coordinates.
  Eigen::Vector3d fileUp() const { return axes.transpose() * Eigen::Vector3d::UnitY(); }
};

// Known length units: name -> centimetres per unit. Returns nullopt for an unknown name.
std::optional<double> centimetresPerUnit(const std::string& unit);
// The known units' names for messages: "cm, m, mm, inch, ft, dm, cmu".
std::string knownUnitNames();

// Throws InputError(motion.source, 0, ...) when the rest pose (OFFSETs only) of the mapped canonical
// joints cannot be measured: they lie on one line or one point (the second singular value of their
// centred positions is below 1e-6 of the first), or the skeletal height is zero. Such a skeleton (all
// offsets zero, or all along one axis) has no up axis, unit or facing to detect, and every feature
// would be NaN. Shared by extractFeatures (info, stylize, training) and the clean-up command.
void requireMeasurableRestPose(const Motion& motion, const JointMapping& mapping);

// The character's SKELETAL HEIGHT in the skeleton's own units: the mean over both legs of the
// hip-knee and knee-ankle distances plus the hips-spine, spine-chest, chest-neck and neck-head
// distances, all measured in the rest pose (offsets only). Pose-independent, unlike standing height;
// about 0.75 of a person's standing height.
double skeletalHeight(const Skeleton& skeleton, const JointMapping& mapping);

// Detects the up axis from the animation (the dominant axis of the mean feet-to-head vector over the
// given frames of canonical_positions: frames x 63, the 21 canonical joints in file space, as
// canonicalJointPositions gives them) and the unit: `unit` if given (must be a known name, else
// std::invalid_argument), otherwise guessed from the skeleton's rest pose: cm if the skeletal height
// reads 50-260 cm, else m, else mm, else whichever of inch, cmu, ft puts it nearest 130 cm.
SpaceConvention detectSpaceConvention(const Skeleton& skeleton, const Eigen::MatrixXd& canonical_positions,
                                      const JointMapping& mapping,
                                      const std::optional<std::string>& unit = std::nullopt);

}  // namespace motionstyle
