#include "features/foot_contacts.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "features/representation.h"
#include "features/rest_pose_frames.h"

namespace motionstyle {
namespace {

void checkPositiveFinite(double value, const char* what) {
  if (!std::isfinite(value) || !(value > 0.0))
    throw std::invalid_argument(std::string("contacts: ") + what + " must be positive and finite");
}

void checkCommon(const Eigen::MatrixXd& positions, const std::array<int, kContactCount>& foot_joints,
                 const Eigen::Vector3d& up) {
  if (positions.cols() % 3 != 0)
    throw std::invalid_argument("contacts: positions need 3 columns per joint, got " + std::to_string(positions.cols()));
  const auto joint_count = static_cast<int>(positions.cols() / 3);
  for (int joint : foot_joints)
    if (joint < 0 || joint >= joint_count)
      throw std::invalid_argument("contacts: foot joint index " + std::to_string(joint) + " outside 0.." +
                                  std::to_string(joint_count - 1));
  if (!up.allFinite() || std::abs(up.norm() - 1.0) > 1e-6)
    throw std::invalid_argument("contacts: the up axis must be a unit vector");
  if (!positions.allFinite()) throw std::invalid_argument("contacts: positions hold a non-finite value");
}

Eigen::Vector3d positionOf(const Eigen::MatrixXd& positions, Eigen::Index frame, int joint) {
  return positions.block<1, 3>(frame, 3 * static_cast<Eigen::Index>(joint)).transpose();
}

// The q-quantile (q in [0, 1]) of values; values is reordered. Empty input gives 0.
double quantile(std::vector<double>& values, double q) {
  if (values.empty()) return 0.0;
  const auto k = static_cast<size_t>(std::lround(q * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

// Fills interior gaps shorter than min_frames, then drops interior contacts shorter than min_frames.
// Runs touching the clip's ends are kept: the clip may start or stop mid-contact.
void removeFlicker(Eigen::Ref<Eigen::VectorXi> labels, int min_frames) {
  const Eigen::Index n = labels.size();
  for (int value : {0, 1}) {
    for (Eigen::Index start = 0; start < n;) {
      Eigen::Index end = start;
      while (end < n && labels[end] == labels[start]) ++end;
      if (labels[start] == value && start > 0 && end < n && end - start < min_frames)
        labels.segment(start, end - start).setConstant(1 - value);
      start = end;
    }
  }
}

}  // namespace

void ContactDetectionOptions::validate() const {
  checkPositiveFinite(height_threshold, "height_threshold");
  checkPositiveFinite(speed_threshold, "speed_threshold");
  checkPositiveFinite(max_rest_height, "max_rest_height");
  if (!std::isfinite(release_factor) || release_factor < 1.0)
    throw std::invalid_argument("contacts: release_factor must be >= 1");
  if (!std::isfinite(min_segment_seconds) || min_segment_seconds < 0.0)
    throw std::invalid_argument("contacts: min_segment_seconds must be >= 0");
  if (!(rest_height_percentile >= 0.0 && rest_height_percentile <= 1.0))
    throw std::invalid_argument("contacts: rest_height_percentile must lie in [0, 1]");
}

std::array<double, kContactCount> estimateRestHeights(const Eigen::MatrixXd& world_positions,
                                                      const std::array<int, kContactCount>& foot_joints,
                                                      const Eigen::Vector3d& up, double floor_height,
                                                      double body_height, const ContactDetectionOptions& options) {
  options.validate();
  checkCommon(world_positions, foot_joints, up);
  checkPositiveFinite(body_height, "body height");
  if (!std::isfinite(floor_height)) throw std::invalid_argument("contacts: the floor height must be finite");
  std::array<double, kContactCount> rest{};
  std::vector<double> heights(static_cast<size_t>(world_positions.rows()));
  for (size_t label = 0; label < kContactCount; ++label) {
    for (Eigen::Index f = 0; f < world_positions.rows(); ++f)
      heights[static_cast<size_t>(f)] = up.dot(positionOf(world_positions, f, foot_joints[label])) - floor_height;
    rest[label] = std::clamp(quantile(heights, options.rest_height_percentile), 0.0,
                             options.max_rest_height * body_height);
  }
  return rest;
}

ContactLabels detectContacts(const Eigen::MatrixXd& world_positions, const std::array<int, kContactCount>& foot_joints,
                             const Eigen::Vector3d& up, double floor_height, double fps, double body_height,
                             const ContactDetectionOptions& options) {
  checkPositiveFinite(fps, "fps");
  const std::array<double, kContactCount> rest =
      estimateRestHeights(world_positions, foot_joints, up, floor_height, body_height, options);
  const Eigen::Index frames = world_positions.rows();
  const double height_on = options.height_threshold * body_height;
  const double speed_on = options.speed_threshold * body_height;
  const double height_off = height_on * options.release_factor;
  const double speed_off = speed_on * options.release_factor;
  const int min_frames = std::max(1, static_cast<int>(std::lround(options.min_segment_seconds * fps)));

  ContactLabels labels = ContactLabels::Zero(frames, kContactCount);
  for (size_t label = 0; label < kContactCount; ++label) {
    const int joint = foot_joints[label];
    bool in_contact = false;
    for (Eigen::Index t = 0; t < frames; ++t) {
      // Central difference inside the clip, one-sided at its ends; the vertical part is removed.
      const Eigen::Index before = t > 0 ? t - 1 : t;
      const Eigen::Index after = t + 1 < frames ? t + 1 : t;
      double speed = 0.0;
      if (after > before) {
        Eigen::Vector3d step = positionOf(world_positions, after, joint) - positionOf(world_positions, before, joint);
        step -= up.dot(step) * up;
        speed = step.norm() * fps / static_cast<double>(after - before);
      }
      const double height = up.dot(positionOf(world_positions, t, joint)) - floor_height - rest[label];
      in_contact = in_contact ? (height < height_off && speed < speed_off) : (height < height_on && speed < speed_on);
      labels(t, static_cast<Eigen::Index>(label)) = in_contact ? 1 : 0;
    }
    removeFlicker(labels.col(static_cast<Eigen::Index>(label)), min_frames);
  }
  return labels;
}

std::array<int, kContactCount> contactJoints(const JointMapping& mapping) {
  std::array<int, kContactCount> joints{};
  for (size_t label = 0; label < kContactCount; ++label) joints[label] = mapping[kContactJoint[label]];
  return joints;
}

std::array<int, kContactCount> canonicalContactJoints() {
  std::array<int, kContactCount> joints{};
  for (size_t label = 0; label < kContactCount; ++label) joints[label] = index(kContactJoint[label]);
  return joints;
}

double restPoseBodyHeight(const Skeleton& skeleton, const Eigen::Vector3d& up) {
  // The body is the subtree of the first joint that branches (the hips): the joints above it only
  // place the body, and their offsets hold where a clip starts (Bandai's Hips under its static root:
  // 0 to 450 cm ahead), not how tall the character is.
  if (skeleton.joints.empty()) return 0.0;
  int body = 0;
  for (std::vector<int> below = skeleton.children(body);
       below.size() == 1 && !skeleton.joints[static_cast<size_t>(below[0])].end_site; below = skeleton.children(body))
    body = below[0];
  // Every joint after `body` lies below it: parents precede their children, and each joint above it
  // has it (or the next joint toward it) as its only child.
  std::vector<Eigen::Vector3d> position(skeleton.joints.size(), Eigen::Vector3d::Zero());
  Eigen::Vector3d low = Eigen::Vector3d::Zero(), high = Eigen::Vector3d::Zero();
  double up_low = 0.0, up_high = 0.0;
  for (size_t j = static_cast<size_t>(body) + 1; j < skeleton.joints.size(); ++j) {
    const Joint& joint = skeleton.joints[j];
    position[j] = position[static_cast<size_t>(joint.parent)] + joint.offset;
    low = low.cwiseMin(position[j]);
    high = high.cwiseMax(position[j]);
    up_low = std::min(up_low, up.dot(position[j]));
    up_high = std::max(up_high, up.dot(position[j]));
  }
  const double along_up = up_high - up_low;
  const double largest = (high - low).maxCoeff();
  return along_up < 0.25 * largest ? largest : along_up;
}

double estimateFloorHeight(const Eigen::MatrixXd& world_positions, const std::array<int, kContactCount>& foot_joints,
                           const Eigen::Vector3d& up) {
  checkCommon(world_positions, foot_joints, up);
  if (world_positions.rows() == 0) return 0.0;
  std::vector<double> lowest(static_cast<size_t>(world_positions.rows()));
  for (Eigen::Index f = 0; f < world_positions.rows(); ++f) {
    double low = up.dot(positionOf(world_positions, f, foot_joints[0]));
    for (int joint : foot_joints) low = std::min(low, up.dot(positionOf(world_positions, f, joint)));
    lowest[static_cast<size_t>(f)] = low;
  }
  return quantile(lowest, 0.02);
}

FileSpaceGround detectFileSpaceGround(const Motion& motion, const JointMapping& mapping,
                                      const Eigen::MatrixXd& canonical_positions, const std::optional<std::string>& unit) {
  FileSpaceGround ground;
  ground.convention = detectSpaceConvention(motion.skeleton, canonical_positions, mapping, unit);
  ground.up = ground.convention.fileUp();
  ground.floor_height = estimateFloorHeight(canonical_positions, canonicalContactJoints(), ground.up);
  ground.contacts = detectContacts(canonical_positions, canonicalContactJoints(), ground.up, ground.floor_height,
                                   motion.fps(), restPoseBodyHeight(motion.skeleton, ground.up));
  return ground;
}

FileSpaceGround detectClipGround(const Motion& motion, const JointMapping& mapping, int rest_pose_frames,
                                 const std::optional<std::string>& unit) {
  if (rest_pose_frames == 0) return detectFileSpaceGround(motion, mapping, canonicalJointPositions(motion, mapping), unit);
  Motion continued = motion;
  replaceRestPoseFrames(continued, rest_pose_frames);
  return detectFileSpaceGround(continued, mapping, canonicalJointPositions(continued, mapping), unit);
}

}  // namespace motionstyle
