#include "display_space.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ik/contacts.h"
#include "motion/resample.h"

#include <utility>

namespace motionstyle {
namespace {

constexpr double kUnmappedDisplayHeightCm = 170.0;

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

Eigen::MatrixXd rowsAtRate(Eigen::MatrixXd rows, double source_fps, double target_fps) {
  if (rows.rows() == 0 || sameFrameRate(source_fps, target_fps)) return rows;
  return resampleRowsLinear(rows, 1.0 / source_fps, target_fps);
}

std::vector<float> trackAtRate(const std::vector<double>& track, double track_fps, double fps) {
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(track.size()), 1);
  for (size_t i = 0; i < track.size(); ++i) rows(static_cast<Eigen::Index>(i), 0) = track[i];
  const Eigen::MatrixXd at_rate = rowsAtRate(std::move(rows), track_fps, fps);
  std::vector<float> values(static_cast<size_t>(at_rate.rows()));
  for (Eigen::Index i = 0; i < at_rate.rows(); ++i) values[static_cast<size_t>(i)] = static_cast<float>(at_rate(i, 0));
  return values;
}

}  // namespace motionstyle
