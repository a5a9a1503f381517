#include "display_normalisation.h"

#include <Eigen/Geometry>

#include <limits>
#include <numbers>

namespace motionstyle {
namespace {

constexpr double kDisplayHeightCm = 170.0;

}  // namespace

Eigen::MatrixXd normaliseForDisplay(const Eigen::MatrixXd& file_positions) {
  const Eigen::Index frames = file_positions.rows();
  const Eigen::Index joints = file_positions.cols() / 3;
  if (frames == 0 || joints == 0) return file_positions;

  // Extent of frame 0 along each file axis.
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d high = Eigen::Vector3d::Constant(std::numeric_limits<double>::lowest());
  for (Eigen::Index j = 0; j < joints; ++j) {
    const Eigen::Vector3d p = file_positions.row(0).segment<3>(3 * j).transpose();
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const Eigen::Vector3d extent = high - low;
  // The largest extent, but Y keeps the role unless the largest beats it by more than 10%.
  int up = 0;
  extent.maxCoeff(&up);
  if (1.1 * extent[1] >= extent[up]) up = 1;

  Eigen::Matrix3d to_y_up = Eigen::Matrix3d::Identity();
  if (up == 2) to_y_up = Eigen::AngleAxisd(-std::numbers::pi / 2.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
  if (up == 0) to_y_up = Eigen::AngleAxisd(std::numbers::pi / 2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();

  const double height = extent[up];
  const double scale = height > 0.0 ? kDisplayHeightCm / height : 1.0;
  const double floor = scale * low[up];

  Eigen::MatrixXd display(frames, 3 * joints);
  for (Eigen::Index f = 0; f < frames; ++f) {
    for (Eigen::Index j = 0; j < joints; ++j) {
      Eigen::Vector3d p = scale * (to_y_up * file_positions.row(f).segment<3>(3 * j).transpose());
      p.y() -= floor;
      display.row(f).segment<3>(3 * j) = p.transpose();
    }
  }
  return display;
}

}  // namespace motionstyle
