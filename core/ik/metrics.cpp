#include "ik/metrics.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "features/signal_filters.h"
#include "mapping/canonical_joints.h"

namespace motionstyle {
namespace {

Eigen::Vector3d at(const Eigen::MatrixXd& positions, Eigen::Index frame, int joint) {
  return positions.block<1, 3>(frame, 3 * static_cast<Eigen::Index>(joint)).transpose();
}

}  // namespace

std::vector<BoneReference> skeletonBones(const Skeleton& skeleton) {
  std::vector<BoneReference> bones;
  for (int j = 1; j < skeleton.jointCount(); ++j) {
    const Joint& joint = skeleton.joints[static_cast<size_t>(j)];
    const bool has_position = std::any_of(joint.channels.begin(), joint.channels.end(),
                                          [](ChannelType c) { return !isRotation(c); });
    if (!has_position) bones.push_back({j, joint.parent, joint.offset.norm()});
  }
  return bones;
}

std::vector<BoneReference> canonicalBones(const Eigen::MatrixXd& content_world, const JointMapping& mapping) {
  std::vector<BoneReference> bones;
  for (int c = 1; c < kCanonicalJointCount; ++c) {
    const int parent = kCanonicalParent[static_cast<size_t>(c)];
    const int joint_a = mapping.joints[static_cast<size_t>(c)];
    const int joint_b = mapping.joints[static_cast<size_t>(parent)];
    if (joint_a < 0 || joint_b < 0 || 3 * std::max(joint_a, joint_b) + 3 > content_world.cols())
      throw std::invalid_argument("canonicalBones: mapping index outside the content's positions");
    std::vector<double> lengths(static_cast<size_t>(content_world.rows()));
    for (Eigen::Index f = 0; f < content_world.rows(); ++f)
      lengths[static_cast<size_t>(f)] = (at(content_world, f, joint_a) - at(content_world, f, joint_b)).norm();
    bones.push_back({c, parent, median(std::move(lengths))});
  }
  return bones;
}

std::array<int, kCanonicalJointCount> identityCanonicalJoints() {
  std::array<int, kCanonicalJointCount> joints{};
  for (int c = 0; c < kCanonicalJointCount; ++c) joints[static_cast<size_t>(c)] = c;
  return joints;
}

void MetricsInput::validate() const {
  if (positions.cols() % 3 != 0 || positions.cols() == 0)
    throw std::invalid_argument("metrics: positions need 3 columns per joint, got " + std::to_string(positions.cols()));
  const auto joints = static_cast<int>(positions.cols() / 3);
  const auto frames = positions.rows();
  auto checkJoint = [&](int joint, const char* what) {
    if (joint < 0 || joint >= joints)
      throw std::invalid_argument(std::string("metrics: ") + what + " joint index " + std::to_string(joint) +
                                  " outside 0.." + std::to_string(joints - 1));
  };
  for (int joint : canonical_joints) checkJoint(joint, "canonical");
  for (const BoneReference& bone : bones) {
    checkJoint(bone.joint, "bone");
    checkJoint(bone.parent, "bone parent");
    if (!std::isfinite(bone.length) || bone.length < 0.0) throw std::invalid_argument("metrics: bad bone length");
  }
  if (!positions.allFinite()) throw std::invalid_argument("metrics: positions hold a non-finite value");
  if (contacts.size() > 0) {
    if (contacts.rows() != frames || contacts.cols() != kContactCount)
      throw std::invalid_argument("metrics: contacts must be frames x 4 (" + std::to_string(frames) + " frames)");
    if ((contacts.array() < 0).any() || (contacts.array() > 1).any())
      throw std::invalid_argument("metrics: contact labels must be 0 or 1");
  }
  if (targets.size() > 0) {
    if (targets.rows() != frames || targets.cols() != 3 * kCanonicalJointCount)
      throw std::invalid_argument("metrics: targets must be frames x 63 (" + std::to_string(frames) + " frames)");
    if (!targets.allFinite()) throw std::invalid_argument("metrics: targets hold a non-finite value");
  }
  if (!up.allFinite() || std::abs(up.norm() - 1.0) > 1e-6)
    throw std::invalid_argument("metrics: the up axis must be a unit vector");
  if (!std::isfinite(floor_height)) throw std::invalid_argument("metrics: the floor height must be finite");
  if (!std::isfinite(cm_per_unit) || !(cm_per_unit > 0.0))
    throw std::invalid_argument("metrics: cm_per_unit must be positive");
  if (!std::isfinite(fps) || !(fps > 0.0)) throw std::invalid_argument("metrics: fps must be positive");
}

ClipMetrics computeMetrics(const MetricsInput& input) {
  MetricsAccumulator accumulator;
  accumulator.add(input);
  return accumulator.finish();
}

void MetricsAccumulator::add(const MetricsInput& block) {
  block.validate();
  if (!started_) {
    started_ = true;
    canonical_joints_ = block.canonical_joints;
    bones_ = block.bones;
    up_ = block.up;
    floor_height_ = block.floor_height;
    cm_per_unit_ = block.cm_per_unit;
    fps_ = block.fps;
    columns_ = block.positions.cols();
    has_contacts_ = block.contacts.size() > 0;
    has_targets_ = block.targets.size() > 0;
  } else if (block.canonical_joints != canonical_joints_ || block.bones.size() != bones_.size() || block.up != up_ ||
             block.floor_height != floor_height_ || block.cm_per_unit != cm_per_unit_ || block.fps != fps_ ||
             block.positions.cols() != columns_ || (block.contacts.size() > 0) != has_contacts_ ||
             (block.targets.size() > 0) != has_targets_) {
    throw std::invalid_argument("metrics: a block's joints, bones, space, rate, contacts or targets differ from the first block's");
  }
  const Eigen::Index kept = history_.rows();
  const Eigen::Index added = block.positions.rows();
  if (added == 0) return;
  // The kept frames, then this block's: row r of p is frame (partial_.frames - kept + r).
  Eigen::MatrixXd p(kept + added, columns_);
  if (kept > 0) p.topRows(kept) = history_;  // (history_ starts 0 x 0: no block assignment then)
  p.bottomRows(added) = block.positions;
  const int base = partial_.frames - static_cast<int>(kept);
  const double cm = cm_per_unit_;
  ClipMetrics& m = partial_;
  m.frames += static_cast<int>(added);
  if (keep_tracks_) {
    m.skate_track_cm_s.resize(static_cast<size_t>(m.frames), 0.0);
    m.bone_error_track_cm.resize(static_cast<size_t>(m.frames), 0.0);
  }
  std::array<int, kContactCount> feet{};
  for (size_t label = 0; label < kContactCount; ++label)
    feet[label] = canonical_joints_[static_cast<size_t>(index(kContactJoint[label]))];

  // Foot skate: the steps t -> t+1 that end in this block.
  if (has_contacts_) {
    auto inContact = [&](Eigen::Index row, Eigen::Index label) {
      return row < kept ? last_contacts_(label) != 0 : block.contacts(row - kept, label) != 0;
    };
    for (Eigen::Index t = std::max<Eigen::Index>(kept - 1, 0); t + 1 < kept + added; ++t) {
      double frame_sum = 0.0;
      int frame_count = 0;
      // Per foot, the slower of its joints in contact at t and t + 1 (metrics.h).
      std::array<double, kContactCount / 2> foot_speed{-1.0, -1.0};
      for (Eigen::Index label = 0; label < kContactCount; ++label) {
        if (!inContact(t, label) || !inContact(t + 1, label)) continue;
        Eigen::Vector3d step = at(p, t + 1, feet[static_cast<size_t>(label)]) - at(p, t, feet[static_cast<size_t>(label)]);
        step -= up_.dot(step) * up_;
        const double speed = step.norm() * cm * fps_;
        double& foot = foot_speed[static_cast<size_t>(label / 2)];  // ContactLabel order: heel, toe per foot
        foot = foot < 0.0 ? speed : std::min(foot, speed);
      }
      for (double speed : foot_speed)
        if (speed >= 0.0) {
          frame_sum += speed;
          ++frame_count;
        }
      skate_sum_ += frame_sum;
      m.contact_steps += frame_count;
      if (keep_tracks_ && frame_count > 0) m.skate_track_cm_s[static_cast<size_t>(base + t)] = frame_sum / frame_count;
    }
    last_contacts_ = block.contacts.row(added - 1);
  }

  for (Eigen::Index t = kept; t < kept + added; ++t) {
    // Floor penetration.
    for (int joint : feet) {
      const double depth = (floor_height_ - up_.dot(at(p, t, joint))) * cm;
      if (depth <= 0.0) continue;
      m.penetration_max_cm = std::max(m.penetration_max_cm, depth);
      depth_sum_ += depth;
      ++m.penetrating_samples;
    }
    // Bone lengths.
    double worst = 0.0;
    for (const BoneReference& bone : bones_) {
      const double error = std::abs((at(p, t, bone.joint) - at(p, t, bone.parent)).norm() - bone.length) * cm;
      bone_sum_ += error;
      worst = std::max(worst, error);
    }
    if (keep_tracks_) m.bone_error_track_cm[static_cast<size_t>(base + t)] = worst;
    m.bone_error_max_cm = std::max(m.bone_error_max_cm, worst);
    // Position residual.
    if (has_targets_) {
      for (int c = 0; c < kCanonicalJointCount; ++c) {
        const Eigen::Vector3d target = block.targets.block<1, 3>(t - kept, 3 * c).transpose();
        const double error = (at(p, t, canonical_joints_[static_cast<size_t>(c)]) - target).norm() * cm;
        residual_sum_ += error;
        if (error > m.residual_max_cm || m.residual_max_frame < 0) {
          m.residual_max_cm = error;
          m.residual_max_frame = base + static_cast<int>(t);
          m.residual_max_joint = c;
        }
      }
    }
    // Jerk: the window of four frames that ends here.
    if (t >= 3)
      for (int joint : canonical_joints_)
        jerk_sum_ += (at(p, t, joint) - 3.0 * at(p, t - 1, joint) + 3.0 * at(p, t - 2, joint) - at(p, t - 3, joint)).norm();
  }
  const Eigen::Index keep = std::min<Eigen::Index>(3, p.rows());
  history_ = p.bottomRows(keep);
}

ClipMetrics MetricsAccumulator::finish() const {
  ClipMetrics m = partial_;
  const double frames = m.frames;
  if (!keep_tracks_ || !started_) {
    m.skate_track_cm_s.assign(keep_tracks_ ? static_cast<size_t>(m.frames) : 0, 0.0);
    m.bone_error_track_cm.assign(keep_tracks_ ? static_cast<size_t>(m.frames) : 0, 0.0);
  }
  if (m.contact_steps > 0) m.foot_skate_cm_s = skate_sum_ / m.contact_steps;
  if (m.penetrating_samples > 0) m.penetration_mean_cm = depth_sum_ / m.penetrating_samples;
  if (!bones_.empty() && m.frames > 0) m.bone_error_mean_cm = bone_sum_ / (frames * static_cast<double>(bones_.size()));
  if (has_targets_ && m.frames > 0) {
    m.has_residual = true;
    m.residual_mean_cm = residual_sum_ / (frames * kCanonicalJointCount);
  }
  const double jerk_scale = cm_per_unit_ * fps_ * fps_ * fps_;
  if (m.frames >= 4) m.jerk_mean_cm_s3 = jerk_sum_ * jerk_scale / ((frames - 3) * kCanonicalJointCount);
  return m;
}

std::string metricsToJson(const ClipMetrics& metrics, bool include_tracks) {
  nlohmann::ordered_json json;
  json["format"] = "motionstyle-metrics";
  json["version"] = 1;
  json["frames"] = metrics.frames;
  json["foot_skate_cm_s"] = metrics.foot_skate_cm_s;
  json["contact_steps"] = metrics.contact_steps;
  json["floor_penetration_max_cm"] = metrics.penetration_max_cm;
  json["floor_penetration_mean_cm"] = metrics.penetration_mean_cm;
  json["penetrating_samples"] = metrics.penetrating_samples;
  json["bone_error_mean_cm"] = metrics.bone_error_mean_cm;
  json["bone_error_max_cm"] = metrics.bone_error_max_cm;
  if (metrics.has_residual) {
    json["position_residual_mean_cm"] = metrics.residual_mean_cm;
    json["position_residual_max_cm"] = metrics.residual_max_cm;
    json["position_residual_max_frame"] = metrics.residual_max_frame;
    json["position_residual_max_joint"] =
        std::string(canonicalJointName(static_cast<CanonicalJoint>(metrics.residual_max_joint)));
  }
  json["jerk_mean_cm_s3"] = metrics.jerk_mean_cm_s3;
  if (include_tracks) {
    json["skate_track_cm_s"] = metrics.skate_track_cm_s;
    json["bone_error_track_cm"] = metrics.bone_error_track_cm;
  }
  return json.dump(2) + "\n";
}

}  // namespace motionstyle
