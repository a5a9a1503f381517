#include "display_space.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ik/contacts.h"
#include "motion/resample.h"

namespace motionstyle {
namespace {

constexpr double kUnmappedDisplayHeightCm = 170.0;

bool sameRate(double a, double b) { return std::abs(a - b) <= 1e-5 * b; }

}  // namespace

Eigen::MatrixXd DisplaySpace::toDisplay(const Eigen::MatrixXd& file_positions) const {
  const Eigen::Index joints = file_positions.cols() / 3;
  const double floor_cm = convention.cm_per_unit * floor_height;
  Eigen::MatrixXd display(file_positions.rows(), file_positions.cols());
  for (Eigen::Index f = 0; f < file_positions.rows(); ++f) {
    for (Eigen::Index j = 0; j < joints; ++j) {
      Eigen::Vector3d p = convention.toCanonical(file_positions.row(f).segment<3>(3 * j).transpose());
      p.y() -= floor_cm;
      display.row(f).segment<3>(3 * j) = p.transpose();
    }
  }
  return display;
}

DisplaySpace mappedDisplaySpace(const Motion& motion, const JointMapping& mapping, const Eigen::MatrixXd& file_positions) {
  DisplaySpace space;
  Eigen::MatrixXd canonical(file_positions.rows(), 3 * kCanonicalJointCount);
  for (int c = 0; c < kCanonicalJointCount; ++c)
    canonical.middleCols<3>(3 * c) = file_positions.middleCols<3>(3 * mapping.joints[static_cast<size_t>(c)]);
  space.convention = detectSpaceConvention(motion.skeleton, canonical, mapping);
  space.floor_height = estimateFloorHeight(file_positions, contactJoints(mapping), space.convention.fileUp());
  return space;
}

DisplaySpace unmappedDisplaySpace(const Motion& motion, const Eigen::MatrixXd& file_positions) {
  DisplaySpace space;
  space.convention.unit = "unknown";
  space.convention.unit_guessed = true;
  const double height = restPoseBodyHeight(motion.skeleton, Eigen::Vector3d::UnitY());
  space.convention.cm_per_unit = height > 0.0 && std::isfinite(height) ? kUnmappedDisplayHeightCm / height : 1.0;
  double lowest = std::numeric_limits<double>::max();
  for (Eigen::Index j = 1; j < file_positions.cols(); j += 3) lowest = std::min(lowest, file_positions.col(j).minCoeff());
  space.floor_height = file_positions.size() > 0 && std::isfinite(lowest) ? lowest : 0.0;
  return space;
}

Eigen::MatrixXd rowsAtRate(const Eigen::MatrixXd& rows, double source_fps, double target_fps) {
  if (rows.rows() == 0 || sameRate(source_fps, target_fps)) return rows;
  return resampleRowsLinear(rows, 1.0 / source_fps, target_fps);
}

}  // namespace motionstyle
