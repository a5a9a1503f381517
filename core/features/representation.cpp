#include "features/representation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <vector>

#include "common/errors.h"
#include "features/foot_contacts.h"
#include "features/rest_pose_frames.h"
#include "features/root_path.h"
#include "features/signal_filters.h"
#include "motion/kinematics.h"
#include "motion/resample.h"

namespace motionstyle {
namespace {

constexpr int kJoints = kCanonicalJointCount;

double wrapAngle(double angle) {
  return std::remainder(angle, 2.0 * std::numbers::pi);
}

// Canonical joints of every frame in reference space (Y-up, reference cm), not yet floored, from their
// file-space positions (both frames x 63), in place. Column by column: contiguous, vectorised.
void toReferenceSpace(Eigen::MatrixXd& positions, const FeatureAnchor& anchor) {
  const Eigen::Matrix3d to_reference = anchor.scale * anchor.convention.cm_per_unit * anchor.convention.axes;
  const Eigen::Index frames = positions.rows();
  for (int c = 0; c < kJoints; ++c) {
    double* x = positions.col(3 * c).data();
    double* y = positions.col(3 * c + 1).data();
    double* z = positions.col(3 * c + 2).data();
    for (Eigen::Index f = 0; f < frames; ++f) {
      const double px = x[f], py = y[f], pz = z[f];
      x[f] = to_reference(0, 0) * px + to_reference(0, 1) * py + to_reference(0, 2) * pz;
      y[f] = to_reference(1, 0) * px + to_reference(1, 1) * py + to_reference(1, 2) * pz;
      z[f] = to_reference(2, 0) * px + to_reference(2, 1) * py + to_reference(2, 2) * pz;
    }
  }
}

// The floor rule of extractFeatures on features (66 x frames): the 5th percentile over frames of the
// lowest foot joint's height.
double softFloor(const Eigen::MatrixXd& features) {
  Eigen::VectorXd lowest = Eigen::VectorXd::Constant(features.cols(), std::numeric_limits<double>::infinity());
  for (CanonicalJoint foot : kContactJoint) lowest = lowest.cwiseMin(features.row(3 * index(foot) + 1).transpose());
  return quantile(lowest, 0.05);
}

// The toes' height while they are planted (contacts: kContactCount x frames), the median over those
// frames, reference cm; NaN when no toe is ever planted.
double stanceToeHeight(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts) {
  std::vector<double> heights;
  for (ContactLabel label : {ContactLabel::LeftToe, ContactLabel::RightToe}) {
    const int joint = index(kContactJoint[static_cast<std::size_t>(label)]);
    for (Eigen::Index f = 0; f < features.cols(); ++f)
      if (contacts(static_cast<int>(label), f) > 0.5) heights.push_back(features(3 * joint + 1, f));
  }
  return heights.empty() ? std::numeric_limits<double>::quiet_NaN() : median(std::move(heights));
}

void shiftHeights(Eigen::MatrixXd& features, double shift) {
  for (int c = 0; c < kJoints; ++c) features.row(3 * c + 1).array() += shift;
}

}  // namespace

Eigen::MatrixXd canonicalJointPositions(const Motion& motion, const JointMapping& mapping) {
  return worldPositions(motion, mapping.joints);
}

MotionFeatures extractFeatures(const Motion& clip, const JointMapping& mapping, const FeatureOptions& options) {
  if (!(options.fps > 0.0)) throw std::invalid_argument("extractFeatures: fps must be positive");
  const int rest_pose_frames = leadingRestPoseFrames(clip, mapping);
  std::optional<Motion> replaced;
  if (rest_pose_frames > 0) {
    replaced = clip;
    replaceRestPoseFrames(*replaced, rest_pose_frames);
  }
  const Motion& motion = replaced ? *replaced : clip;
  const bool same_rate = sameFrameRate(motion.fps(), options.fps);
  // Resampled as local transforms (what resampleMotion does before it returns to Euler angles), so that
  // the only Euler -> quaternion conversion is the vectorised one in localPoses.
  LocalPoses poses = localPoses(motion);
  if (!same_rate) poses = resampleLocalPoses(poses, motion.frame_time, options.fps);
  if (poses.frames < 2)
    throw InputError(motion.source, 0, "the clip is too short: it needs at least 2 frames at " +
                                           std::to_string(static_cast<int>(options.fps)) + " fps");

  requireMeasurableRestPose(motion, mapping);  // InputError before anything divides by its height
  MotionFeatures result;
  result.mapping = mapping;
  FeatureAnchor& anchor = result.anchor;
  anchor.fps = options.fps;
  anchor.rest_pose_frames = rest_pose_frames;
  Eigen::MatrixXd world = worldPositions(motion.skeleton, poses, mapping.joints);  // file space for now
  anchor.convention = detectSpaceConvention(motion.skeleton, world, mapping, options.unit);
  anchor.scale = kReferenceSkeletalHeightCm / (skeletalHeight(motion.skeleton, mapping) * anchor.convention.cm_per_unit);
  toReferenceSpace(world, anchor);
  const Eigen::Index frames = world.rows();

  // Floor: a soft minimum (5th percentile) of the lowest foot joint per frame.
  Eigen::VectorXd lowest_foot = Eigen::VectorXd::Constant(frames, std::numeric_limits<double>::infinity());
  for (CanonicalJoint foot : kContactJoint) lowest_foot = lowest_foot.cwiseMin(world.col(3 * index(foot) + 1));
  anchor.floor_height = options.derived_from ? options.derived_from->floor_height : quantile(lowest_foot, 0.05);
  for (int c = 0; c < kJoints; ++c) world.col(3 * c + 1).array() -= anchor.floor_height;

  // Root: hips on the floor, smoothed. Facing: across hips + shoulders, crossed with up, smoothed.
  // Column-major frames x 2, so each smoothed signal is contiguous.
  using C = CanonicalJoint;
  auto column = [&](C joint, int axis) { return world.col(3 * index(joint) + axis); };
  Eigen::MatrixXd root(frames, 2), facing(frames, 2);
  root.col(0) = column(C::Hips, 0);
  root.col(1) = column(C::Hips, 2);
  // across = (left - right hip) + (left - right upper arm); facing (x, z) = (-across.z, across.x).
  auto across = [&](int axis) -> Eigen::VectorXd {
    return (column(C::LeftHip, axis) - column(C::RightHip, axis)) +
           (column(C::LeftUpperArm, axis) - column(C::RightUpperArm, axis));
  };
  facing.col(0) = -across(2);
  facing.col(1) = across(0);
  root = gaussianSmoothRows(root, options.root_smoothing_frames);
  facing = gaussianSmoothRows(facing, options.facing_smoothing_frames);

  // Heading, unwrapped, and its cosine and sine (the facing direction normalised: no sin/cos calls).
  Eigen::VectorXd heading(frames), heading_cos(frames), heading_sin(frames);
  for (Eigen::Index f = 0; f < frames; ++f) {
    const double x = facing(f, 0), z = facing(f, 1);
    heading[f] = std::atan2(x, z);
    const double length = std::sqrt(x * x + z * z);
    if (length > 0.0 && std::isfinite(length)) {
      heading_cos[f] = z / length;
      heading_sin[f] = x / length;
    } else {
      heading_cos[f] = std::cos(heading[f]);
      heading_sin[f] = std::sin(heading[f]);
    }
    if (f > 0) heading[f] = heading[f - 1] + wrapAngle(heading[f] - heading[f - 1]);  // unwrap
  }

  // Joints in the root frame: rotated by -heading about +Y, i.e. local x = cos dx - sin dz and
  // local z = sin dx + cos dz.
  result.values.resize(kFeatureCount, frames);
  for (Eigen::Index f = 0; f < frames; ++f) {
    const double cos_h = heading_cos[f], sin_h = heading_sin[f];
    const double root_x = root(f, 0), root_z = root(f, 1);
    double* out = result.values.col(f).data();
    for (int c = 0; c < kJoints; ++c) {
      const double dx = world(f, 3 * c) - root_x, dz = world(f, 3 * c + 2) - root_z;
      out[3 * c] = cos_h * dx - sin_h * dz;
      out[3 * c + 1] = world(f, 3 * c + 1);
      out[3 * c + 2] = sin_h * dx + cos_h * dz;
    }
    const Eigen::Index step_from = f + 1 < frames ? f : f - 1;  // the last frame repeats the one before
    const Eigen::Index step_to = step_from + 1;
    const double dx = root(step_to, 0) - root(step_from, 0), dz = root(step_to, 1) - root(step_from, 1);
    out[kSidewaysVelocity] = heading_cos[step_from] * dx - heading_sin[step_from] * dz;
    out[kForwardVelocity] = heading_sin[step_from] * dx + heading_cos[step_from] * dz;
    out[kTurningVelocity] = heading[step_to] - heading[step_from];
  }
  anchor.start_root = root.row(0).transpose();
  anchor.start_heading = heading[0];
  // Contacts from the project's one detector (foot_contacts.h), here in reference space: Y-up, the floor
  // at 0, and the body height of the character's rest pose converted to reference cm, so the labels
  // are the ones the clean-up finds on the clip in its own space.
  const double body_height = restPoseBodyHeight(motion.skeleton, anchor.convention.fileUp()) *
                             anchor.convention.cm_per_unit * anchor.scale;
  result.contacts = detectContacts(world, canonicalContactJoints(), Eigen::Vector3d::UnitY(), 0.0, options.fps,
                                   body_height)
                        .transpose()
                        .cast<double>();
  if (options.retarget_proportions) {
    try {
      const FeatureAnchor* source = options.derived_from ? &*options.derived_from : nullptr;
      anchor.proportions = source ? source->proportions : measureProportions(result.values);
      retargetFeatures(result.values, anchor.proportions, referenceProportions());
      if (options.canonical_rig) {
        anchor.rig = source ? source->rig : measureRigCorrection(result.values);
        applyRigCorrection(result.values, anchor.rig);
      }
      if (source) {
        anchor.retarget_height_shift = source->retarget_height_shift;
        shiftHeights(result.values, anchor.retarget_height_shift);
      } else {
        anchor.retarget_height_shift = -softFloor(result.values);
        shiftHeights(result.values, anchor.retarget_height_shift);
        const double stance = stanceToeHeight(result.values, result.contacts);
        if (std::isfinite(stance)) {
          anchor.retarget_height_shift += kReferenceStanceToeHeightCm - stance;
          shiftHeights(result.values, kReferenceStanceToeHeightCm - stance);
        }
      }
    } catch (const std::invalid_argument& error) {
      throw InputError(motion.source, 0, std::string("cannot retarget the skeleton's proportions: ") + error.what());
    }
  }
  return result;
}

namespace {

// Steps 9, 8 and 7 undone: root-frame features in the clip's own rig and proportions.
Eigen::MatrixXd toOwnRig(const Eigen::MatrixXd& features, const FeatureAnchor& anchor) {
  Eigen::MatrixXd own = features;
  shiftHeights(own, -anchor.retarget_height_shift);
  applyRigCorrection(own, anchor.rig, /*inverse=*/true);
  retargetFeatures(own, referenceProportions(), anchor.proportions);
  return own;
}

}  // namespace

void holdStancesInOwnRig(Eigen::MatrixXd& features, const MotionFeatures& content) {
  if (features.rows() != kFeatureCount || features.cols() != content.values.cols())
    throw std::invalid_argument("holdStancesInOwnRig: features must be 66 x the content's frames");
  if (content.contacts.size() == 0) return;  // no stances to hold
  if (content.contacts.rows() != kContactCount || content.contacts.cols() != content.values.cols())
    throw std::invalid_argument("holdStancesInOwnRig: the content's contacts must be 4 x its frames");
  const FeatureAnchor& anchor = content.anchor;
  Eigen::MatrixXd own = toOwnRig(features, anchor);
  enforceBoneLengths(own, anchor.proportions, content.contacts, stanceToeHeight(toOwnRig(content.values, anchor), content.contacts));
  retargetFeatures(own, anchor.proportions, referenceProportions());
  applyRigCorrection(own, anchor.rig);
  shiftHeights(own, anchor.retarget_height_shift);
  // The hold moves joints only: the root velocities stay bit for bit (the round trip would round them).
  own.middleRows<3>(kSidewaysVelocity) = features.middleRows<3>(kSidewaysVelocity);
  features = std::move(own);
}

Eigen::MatrixXd referenceWorldPositions(const Eigen::MatrixXd& features, const FeatureAnchor& anchor) {
  if (features.rows() != kFeatureCount)
    throw std::invalid_argument("referenceWorldPositions: features must have 66 rows, got " + std::to_string(features.rows()));
  const Eigen::Index frames = features.cols();
  const Eigen::MatrixXd own = toOwnRig(features, anchor);  // back to the clip's own rig and proportions
  Eigen::MatrixXd world(frames, 3 * kJoints);
  const std::vector<RootFrame> roots = rootFrames(own, anchor.start_root, anchor.start_heading);
  for (Eigen::Index f = 0; f < frames; ++f)
    for (int c = 0; c < kJoints; ++c) {
      const Eigen::Vector3d p = own.col(f).segment<3>(3 * c);
      const Eigen::Vector2d floor = roots[static_cast<std::size_t>(f)].toWorld(p.x(), p.z());
      world.row(f).segment<3>(3 * c) << floor.x(), p.y(), floor.y();
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
  if (features.cols() == 0) return Eigen::VectorXd::Zero(kJoints);
  const Proportions proportions = measureProportions(features);
  return Eigen::Map<const Eigen::VectorXd>(proportions.bone_length.data(), kJoints);
}

}  // namespace motionstyle
