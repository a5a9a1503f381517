#include "features/root_path.h"

#include <cmath>
#include <stdexcept>

#include "features/feature_layout.h"
#include "features/signal_filters.h"
#include "motion/kinematics.h"

namespace motionstyle {

RootPathSummary summariseRootPath(const Eigen::MatrixXd& features) {
  if (features.rows() != kFeatureCount) throw std::invalid_argument("summariseRootPath: features must have 66 rows");
  RootPathSummary path;
  double heading = 0.0;
  for (Eigen::Index f = 0; f < features.cols(); ++f) {
    const double vx = features(kSidewaysVelocity, f), vz = features(kForwardVelocity, f);
    const double c = std::cos(heading), s = std::sin(heading);
    path.displacement += Eigen::Vector2d(c * vx + s * vz, -s * vx + c * vz);
    path.distance_cm += std::hypot(vx, vz);
    heading += features(kTurningVelocity, f);
  }
  path.heading_change = heading;
  return path;
}

RootPathSummary summariseGroundPath(const Eigen::MatrixXd& ground, double smoothing_frames) {
  if (ground.cols() != 2) throw std::invalid_argument("summariseGroundPath: ground positions must be frames x 2");
  RootPathSummary path;
  if (ground.rows() == 0) return path;
  const Eigen::MatrixXd smooth = gaussianSmoothRows(ground, smoothing_frames);
  for (Eigen::Index f = 1; f < smooth.rows(); ++f) path.distance_cm += (smooth.row(f) - smooth.row(f - 1)).norm();
  path.displacement = (smooth.row(smooth.rows() - 1) - smooth.row(0)).transpose();
  return path;
}

RootPathComparison compareRootPaths(const RootPathSummary& content, const RootPathSummary& output) {
  RootPathComparison comparison;
  const double distance = content.distance_cm;
  if (distance > 0.0) {
    comparison.distance_ratio = output.distance_cm / distance;
    comparison.end_error_fraction = (output.displacement - content.displacement).norm() / distance;
  } else if (output.distance_cm > 0.0) {
    comparison.distance_ratio = INFINITY;
    comparison.end_error_fraction = INFINITY;
  }
  comparison.heading_error = std::abs(output.heading_change - content.heading_change);
  return comparison;
}

namespace {

// The mapped hips projected on the floor, canonical cm, frames x 2.
Eigen::MatrixXd hipsOnTheFloor(const Motion& motion, const JointMapping& mapping, const SpaceConvention& convention) {
  const int hips = mapping.joints[static_cast<std::size_t>(index(CanonicalJoint::Hips))];
  const Eigen::MatrixXd world = worldPositions(motion.skeleton, localPoses(motion), std::vector<int>{hips});
  Eigen::MatrixXd ground(world.rows(), 2);
  for (Eigen::Index f = 0; f < world.rows(); ++f) {
    const Eigen::Vector3d p = convention.toCanonical(world.row(f).transpose());
    ground.row(f) << p.x(), p.z();
  }
  return ground;
}

}  // namespace

RootPathComparison compareClipPaths(const Motion& content, const Motion& output, const JointMapping& mapping,
                                    const SpaceConvention& convention) {
  const auto smoothing = [](const Motion& motion) { return 3.0 * motion.fps() / kDefaultFeatureFps; };
  return compareRootPaths(summariseGroundPath(hipsOnTheFloor(content, mapping, convention), smoothing(content)),
                          summariseGroundPath(hipsOnTheFloor(output, mapping, convention), smoothing(output)));
}

}  // namespace motionstyle
