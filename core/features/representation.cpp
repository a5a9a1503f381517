#include "features/representation.h"

#include <cmath>
#include <numbers>

#include "common/errors.h"
#include "features/foot_contacts.h"
#include "features/signal_filters.h"
#include "motion/kinematics.h"
#include "motion/resample.h"

namespace motionstyle {
namespace {

constexpr int kJoints = kCanonicalJointCount;

// Rotation about +Y by angle theta applied to (x, z): +Z turns toward +X for positive theta.
Eigen::Vector2d rotateY(double theta, double x, double z) {
  const double c = std::cos(theta), s = std::sin(theta);
  return {c * x + s * z, -s * x + c * z};
}

double wrapAngle(double angle) {
  return std::remainder(angle, 2.0 * std::numbers::pi);
}

// Canonical joints of every frame in reference space (Y-up, reference cm), not yet floored:
// frames x 63.
Eigen::MatrixXd referenceJointPositions(const Eigen::MatrixXd& file_positions, const FeatureAnchor& anchor) {
  Eigen::MatrixXd reference(file_positions.rows(), file_positions.cols());
  const double factor = anchor.scale * anchor.convention.cm_per_unit;
  for (Eigen::Index f = 0; f < file_positions.rows(); ++f)
    for (int c = 0; c < kJoints; ++c)
      reference.row(f).segment<3>(3 * c) =
          (factor * (anchor.convention.axes * file_positions.row(f).segment<3>(3 * c).transpose())).transpose();
  return reference;
}

}  // namespace

Eigen::MatrixXd canonicalJointPositions(const Motion& motion, const JointMapping& mapping) {
  const Eigen::MatrixXd all = worldPositions(motion);
  Eigen::MatrixXd canonical(all.rows(), 3 * kJoints);
  for (int c = 0; c < kJoints; ++c) canonical.middleCols<3>(3 * c) = all.middleCols<3>(3 * mapping.joints[static_cast<size_t>(c)]);
  return canonical;
}

MotionFeatures extractFeatures(const Motion& motion, const JointMapping& mapping, const FeatureOptions& options) {
  if (!(options.fps > 0.0)) throw std::invalid_argument("extractFeatures: fps must be positive");
  const bool same_rate = std::abs(motion.fps() - options.fps) <= 1e-6 * options.fps;
  const Motion resampled = same_rate ? motion : resampleMotion(motion, options.fps);
  if (resampled.frameCount() < 2)
    throw InputError(motion.source, 0, "the clip is too short: it needs at least 2 frames at " +
                                           std::to_string(static_cast<int>(options.fps)) + " fps");

  MotionFeatures result;
  result.mapping = mapping;
  FeatureAnchor& anchor = result.anchor;
  anchor.fps = options.fps;
  const Eigen::MatrixXd all_positions = worldPositions(resampled);
  anchor.convention = detectSpaceConvention(resampled.skeleton, all_positions, mapping, options.unit);
  anchor.scale = kReferenceSkeletalHeightCm / (skeletalHeight(resampled.skeleton, mapping) * anchor.convention.cm_per_unit);

  Eigen::MatrixXd file_positions(all_positions.rows(), 3 * kJoints);
  for (int c = 0; c < kJoints; ++c)
    file_positions.middleCols<3>(3 * c) = all_positions.middleCols<3>(3 * mapping.joints[static_cast<size_t>(c)]);
  Eigen::MatrixXd world = referenceJointPositions(file_positions, anchor);
  const Eigen::Index frames = world.rows();

  // Floor: a soft minimum (5th percentile) of the lowest foot joint per frame.
  Eigen::VectorXd lowest_foot(frames);
  for (Eigen::Index f = 0; f < frames; ++f) {
    double lowest = INFINITY;
    for (CanonicalJoint foot : kContactJoint) lowest = std::min(lowest, world(f, 3 * index(foot) + 1));
    lowest_foot[f] = lowest;
  }
  anchor.floor_height = quantile(lowest_foot, 0.05);
  for (int c = 0; c < kJoints; ++c) world.col(3 * c + 1).array() -= anchor.floor_height;

  // Root: hips on the floor, smoothed. Facing: across hips + shoulders, crossed with up, smoothed.
  Eigen::MatrixXd root(frames, 2), facing(frames, 2);
  auto joint = [&](Eigen::Index f, CanonicalJoint c) -> Eigen::Vector3d {
    return world.row(f).segment<3>(3 * index(c)).transpose();
  };
  using C = CanonicalJoint;
  for (Eigen::Index f = 0; f < frames; ++f) {
    const Eigen::Vector3d hips = joint(f, C::Hips);
    root.row(f) << hips.x(), hips.z();
    const Eigen::Vector3d across = (joint(f, C::LeftHip) - joint(f, C::RightHip)) +
                                   (joint(f, C::LeftUpperArm) - joint(f, C::RightUpperArm));
    facing.row(f) << -across.z(), across.x();  // across x up, (x, z) components
  }
  root = gaussianSmoothRows(root, options.root_smoothing_frames);
  facing = gaussianSmoothRows(facing, options.facing_smoothing_frames);

  Eigen::VectorXd heading(frames);
  for (Eigen::Index f = 0; f < frames; ++f) {
    heading[f] = std::atan2(facing(f, 0), facing(f, 1));
    if (f > 0) heading[f] = heading[f - 1] + wrapAngle(heading[f] - heading[f - 1]);  // unwrap
  }

  result.values.resize(kFeatureCount, frames);
  for (Eigen::Index f = 0; f < frames; ++f) {
    for (int c = 0; c < kJoints; ++c) {
      const Eigen::Vector3d p = joint(f, static_cast<CanonicalJoint>(c));
      const Eigen::Vector2d local = rotateY(-heading[f], p.x() - root(f, 0), p.z() - root(f, 1));
      result.values.col(f).segment<3>(3 * c) << local.x(), p.y(), local.y();
    }
    const Eigen::Index next = f + 1 < frames ? f + 1 : f;
    const Eigen::Index step_from = f + 1 < frames ? f : f - 1;  // the last frame repeats the one before
    const Eigen::Index step_to = f + 1 < frames ? next : f;
    const Eigen::Vector2d velocity = rotateY(-heading[step_from], root(step_to, 0) - root(step_from, 0),
                                             root(step_to, 1) - root(step_from, 1));
    result.values(kSidewaysVelocity, f) = velocity.x();
    result.values(kForwardVelocity, f) = velocity.y();
    result.values(kTurningVelocity, f) = heading[step_to] - heading[step_from];
  }
  anchor.start_root = root.row(0).transpose();
  anchor.start_heading = heading[0];
  result.contacts = detectFootContacts(world, options.fps);
  return result;
}

Eigen::MatrixXd referenceWorldPositions(const Eigen::MatrixXd& features, const FeatureAnchor& anchor) {
  if (features.rows() != kFeatureCount)
    throw std::invalid_argument("referenceWorldPositions: features must have 66 rows, got " + std::to_string(features.rows()));
  const Eigen::Index frames = features.cols();
  Eigen::MatrixXd world(frames, 3 * kJoints);
  Eigen::Vector2d root = anchor.start_root;
  double heading = anchor.start_heading;
  for (Eigen::Index f = 0; f < frames; ++f) {
    for (int c = 0; c < kJoints; ++c) {
      const Eigen::Vector3d p = features.col(f).segment<3>(3 * c);
      const Eigen::Vector2d offset = rotateY(heading, p.x(), p.z());
      world.row(f).segment<3>(3 * c) << root.x() + offset.x(), p.y(), root.y() + offset.y();
    }
    root += rotateY(heading, features(kSidewaysVelocity, f), features(kForwardVelocity, f));
    heading += features(kTurningVelocity, f);
  }
  return world;
}

Eigen::MatrixXd canonicalWorldPositions(const Eigen::MatrixXd& features, const FeatureAnchor& anchor) {
  Eigen::MatrixXd world = referenceWorldPositions(features, anchor);
  const double to_file_cm = 1.0 / anchor.scale;
  for (Eigen::Index f = 0; f < world.rows(); ++f)
    for (int c = 0; c < kJoints; ++c) {
      Eigen::Vector3d p = world.row(f).segment<3>(3 * c).transpose();
      p.y() += anchor.floor_height;
      world.row(f).segment<3>(3 * c) = anchor.convention.toFile(p * to_file_cm).transpose();
    }
  return world;
}

Eigen::VectorXd canonicalBoneLengths(const Eigen::MatrixXd& features) {
  if (features.rows() != kFeatureCount) throw std::invalid_argument("canonicalBoneLengths: features must have 66 rows");
  Eigen::VectorXd lengths = Eigen::VectorXd::Zero(kJoints);
  if (features.cols() == 0) return lengths;
  for (int c = 1; c < kJoints; ++c) {
    const int parent = kCanonicalParent[static_cast<size_t>(c)];
    lengths[c] = (features.middleRows<3>(3 * c) - features.middleRows<3>(3 * parent)).colwise().norm().mean();
  }
  return lengths;
}

}  // namespace motionstyle
