#include "features/space_convention.h"

#include <Eigen/SVD>
#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "common/errors.h"
#include "features/feature_layout.h"

namespace motionstyle {
namespace {

struct UnitEntry {
  const char* name;
  double cm;
};
constexpr std::array<UnitEntry, 7> kUnits = {{
    {"cm", 1.0}, {"m", 100.0}, {"mm", 0.1}, {"inch", 2.54}, {"ft", 30.48}, {"dm", 10.0},
    {"cmu", 2.54 / 0.45},  // CMU ASF/BVH length unit: 1/0.45 inch
}};

// Skeletal height (see header) of a typical adult, in cm: the target of the unit guess.
constexpr double kTypicalSkeletalHeightCm = 130.0;

// World positions of every joint in the rest pose (offsets only, no rotation), file units.
std::vector<Eigen::Vector3d> restPositions(const Skeleton& skeleton) {
  std::vector<Eigen::Vector3d> positions(skeleton.joints.size());
  for (size_t j = 0; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    positions[j] = joint.parent < 0 ? joint.offset
                                    : Eigen::Vector3d(positions[static_cast<size_t>(joint.parent)] + joint.offset);
  }
  return positions;
}

Eigen::Matrix3d rotationTakingToY(int axis, double sign) {
  // Proper rotations (det +1) that take the file's up axis onto +Y.
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  if (axis == 1) {
    if (sign < 0) r = Eigen::Vector3d(1, -1, -1).asDiagonal();  // 180 deg about X
  } else if (axis == 2) {
    // +Z up: (x, y, z) -> (x, z, -y), a -90 deg turn about X. -Z up: (x, y, z) -> (x, -z, y).
    r << 1, 0, 0, 0, 0, sign, 0, -sign, 0;
  } else {
    // +X up: (x, y, z) -> (-y, x, z), a +90 deg turn about Z. -X up: (x, y, z) -> (y, -x, z).
    r << 0, -sign, 0, sign, 0, 0, 0, 0, 1;
  }
  return r;
}

}  // namespace

std::optional<double> centimetresPerUnit(const std::string& unit) {
  for (const UnitEntry& entry : kUnits)
    if (unit == entry.name) return entry.cm;
  return std::nullopt;
}

std::string knownUnitNames() {
  std::string names;
  for (const UnitEntry& entry : kUnits) names.append(names.empty() ? "" : ", ").append(entry.name);
  return names;
}

void requireMeasurableRestPose(const Motion& motion, const JointMapping& mapping) {
  constexpr double kCollinear = 1e-6;  // second singular value / first
  const std::vector<Eigen::Vector3d> rest = restPositions(motion.skeleton);
  Eigen::MatrixXd points(kCanonicalJointCount, 3);
  for (int c = 0; c < kCanonicalJointCount; ++c)
    points.row(c) = rest[static_cast<size_t>(mapping.joints[static_cast<size_t>(c)])].transpose();
  points.rowwise() -= points.colwise().mean();
  const Eigen::Vector3d spread = Eigen::JacobiSVD<Eigen::MatrixXd>(points).singularValues();
  const double height = skeletalHeight(motion.skeleton, mapping);
  if (!(spread[1] > kCollinear * spread[0]) || !(height > 0.0) || !std::isfinite(height))
    throw InputError(motion.source, 0,
                     "the skeleton's rest pose (its OFFSETs) has no height or width to measure: its canonical joints "
                     "lie on one line or one point, so its up axis, unit and facing are undefined");
}

double skeletalHeight(const Skeleton& skeleton, const JointMapping& mapping) {
  const std::vector<Eigen::Vector3d> rest = restPositions(skeleton);
  auto distance = [&](CanonicalJoint a, CanonicalJoint b) {
    return (rest[static_cast<size_t>(mapping.joints[static_cast<size_t>(index(a))])] -
            rest[static_cast<size_t>(mapping.joints[static_cast<size_t>(index(b))])])
        .norm();
  };
  using C = CanonicalJoint;
  const double legs = 0.5 * (distance(C::LeftHip, C::LeftKnee) + distance(C::LeftKnee, C::LeftAnkle) +
                             distance(C::RightHip, C::RightKnee) + distance(C::RightKnee, C::RightAnkle));
  const double trunk = distance(C::Hips, C::Spine) + distance(C::Spine, C::Chest) + distance(C::Chest, C::Neck) +
                       distance(C::Neck, C::Head);
  return legs + trunk;
}

SpaceConvention detectSpaceConvention(const Skeleton& skeleton, const Eigen::MatrixXd& canonical_positions,
                                      const JointMapping& mapping, const std::optional<std::string>& unit) {
  if (canonical_positions.cols() != 3 * kCanonicalJointCount)
    throw std::invalid_argument("detectSpaceConvention: canonical positions have " +
                                std::to_string(canonical_positions.cols()) + " columns, expected 63");
  if (canonical_positions.rows() == 0) throw std::invalid_argument("detectSpaceConvention: the clip has no frames");

  SpaceConvention convention;
  // Up axis: the dominant component of the mean vector from the feet to the head.
  Eigen::Vector3d up_vector = Eigen::Vector3d::Zero();
  auto column = [](CanonicalJoint c) { return 3 * index(c); };
  const std::array<CanonicalJoint, 4> feet = {CanonicalJoint::LeftAnkle, CanonicalJoint::LeftToe,
                                              CanonicalJoint::RightAnkle, CanonicalJoint::RightToe};
  for (Eigen::Index f = 0; f < canonical_positions.rows(); ++f) {
    Eigen::Vector3d feet_mean = Eigen::Vector3d::Zero();
    for (CanonicalJoint foot : feet) feet_mean += canonical_positions.row(f).segment<3>(column(foot)).transpose();
    up_vector += canonical_positions.row(f).segment<3>(column(CanonicalJoint::Head)).transpose() - feet_mean / 4.0;
  }
  Eigen::Index axis = 0;
  up_vector.cwiseAbs().maxCoeff(&axis);
  const double sign = up_vector[axis] >= 0 ? 1.0 : -1.0;
  convention.axes = rotationTakingToY(static_cast<int>(axis), sign);
  convention.up_axis = std::string(sign > 0 ? "+" : "-") + "XYZ"[axis];

  if (unit) {
    const std::optional<double> cm = centimetresPerUnit(*unit);
    if (!cm) throw std::invalid_argument("unknown length unit '" + *unit + "' (known: " + knownUnitNames() + ")");
    convention.unit = *unit;
    convention.cm_per_unit = *cm;
    convention.unit_guessed = false;
    return convention;
  }

  const double height = skeletalHeight(skeleton, mapping);
  if (!(height > 0.0) || !std::isfinite(height))
    throw std::invalid_argument("cannot guess the length unit: the skeleton has zero height");
  auto plausible = [&](double cm_per_unit) {
    const double cm = height * cm_per_unit;
    return cm >= 50.0 && cm <= 260.0;
  };
  std::pair<std::string, double> chosen;
  if (plausible(1.0)) {
    chosen = {"cm", 1.0};
  } else if (plausible(100.0)) {
    chosen = {"m", 100.0};
  } else if (plausible(0.1)) {
    chosen = {"mm", 0.1};
  } else {
    double best = INFINITY;
    for (const char* name : {"inch", "cmu", "ft"}) {
      const double cm = *centimetresPerUnit(name);
      const double distance = std::abs(std::log(height * cm / kTypicalSkeletalHeightCm));
      if (distance < best) {
        best = distance;
        chosen = {name, cm};
      }
    }
  }
  convention.unit = chosen.first;
  convention.cm_per_unit = chosen.second;
  convention.unit_guessed = true;
  return convention;
}

}  // namespace motionstyle
