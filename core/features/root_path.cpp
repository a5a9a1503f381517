#include "features/root_path.h"

#include <cmath>
#include <stdexcept>

#include "features/feature_layout.h"
#include "features/signal_filters.h"
#include "motion/kinematics.h"

namespace motionstyle {

Eigen::Vector2d RootFrame::toWorld(double x, double z) const {
  const double c = std::cos(heading), s = std::sin(heading);
  return {place.x() + (c * x + s * z), place.y() + (-s * x + c * z)};
}

Eigen::Vector2d RootFrame::toRootFrame(const Eigen::Vector2d& q) const {
  const double c = std::cos(heading), s = std::sin(heading);
  const Eigen::Vector2d d = q - place;
  return {c * d.x() - s * d.y(), s * d.x() + c * d.y()};
}

std::vector<RootFrame> rootFrames(const Eigen::MatrixXd& features, const Eigen::Vector2d& start_place, double start_heading) {
  if (features.rows() != kFeatureCount) throw std::invalid_argument("rootFrames: features must have 66 rows");
  std::vector<RootFrame> frames(static_cast<std::size_t>(features.cols()) + 1);
  frames[0] = {start_place, start_heading};
  for (Eigen::Index f = 0; f < features.cols(); ++f) {
    const RootFrame& now = frames[static_cast<std::size_t>(f)];
    RootFrame& next = frames[static_cast<std::size_t>(f) + 1];
    next.place = now.toWorld(features(kSidewaysVelocity, f), features(kForwardVelocity, f));
    next.heading = now.heading + features(kTurningVelocity, f);
  }
  return frames;
}

RootPathSummary summariseRootPath(const Eigen::MatrixXd& features) {
  if (features.rows() != kFeatureCount) throw std::invalid_argument("summariseRootPath: features must have 66 rows");
  RootPathSummary path;
  for (Eigen::Index f = 0; f < features.cols(); ++f)
    path.distance_cm += std::hypot(features(kSidewaysVelocity, f), features(kForwardVelocity, f));
  const RootFrame end = rootFrames(features).back();
  path.displacement = end.place;
  path.heading_change = end.heading;
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
