#include "ik/metrics.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "common/atomic_file.h"

namespace motionstyle {
namespace {

Eigen::Vector3d at(const Eigen::MatrixXd& positions, Eigen::Index frame, int joint) {
  return positions.block<1, 3>(frame, 3 * static_cast<Eigen::Index>(joint)).transpose();
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle), values.end());
  return values[middle];
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
  input.validate();
  const Eigen::MatrixXd& p = input.positions;
  const Eigen::Index frames = p.rows();
  const double cm = input.cm_per_unit;
  ClipMetrics m;
  m.frames = static_cast<int>(frames);
  m.skate_track_cm_s.assign(static_cast<size_t>(frames), 0.0);
  m.bone_error_track_cm.assign(static_cast<size_t>(frames), 0.0);
  std::array<int, kContactCount> feet{};
  for (size_t label = 0; label < kContactCount; ++label)
    feet[label] = input.canonical_joints[static_cast<size_t>(index(kContactJoint[label]))];

  // Foot skate.
  if (input.contacts.size() > 0) {
    double sum = 0.0;
    for (Eigen::Index t = 0; t + 1 < frames; ++t) {
      double frame_sum = 0.0;
      int frame_count = 0;
      for (Eigen::Index label = 0; label < kContactCount; ++label) {
        if (input.contacts(t, label) == 0 || input.contacts(t + 1, label) == 0) continue;
        Eigen::Vector3d step = at(p, t + 1, feet[static_cast<size_t>(label)]) - at(p, t, feet[static_cast<size_t>(label)]);
        step -= input.up.dot(step) * input.up;
        const double speed = step.norm() * cm * input.fps;
        frame_sum += speed;
        ++frame_count;
      }
      sum += frame_sum;
      m.contact_steps += frame_count;
      if (frame_count > 0) m.skate_track_cm_s[static_cast<size_t>(t)] = frame_sum / frame_count;
    }
    if (m.contact_steps > 0) m.foot_skate_cm_s = sum / m.contact_steps;
  }

  // Floor penetration.
  double depth_sum = 0.0;
  for (Eigen::Index t = 0; t < frames; ++t) {
    for (int joint : feet) {
      const double depth = (input.floor_height - input.up.dot(at(p, t, joint))) * cm;
      if (depth <= 0.0) continue;
      m.penetration_max_cm = std::max(m.penetration_max_cm, depth);
      depth_sum += depth;
      ++m.penetrating_samples;
    }
  }
  if (m.penetrating_samples > 0) m.penetration_mean_cm = depth_sum / m.penetrating_samples;

  // Bone lengths.
  if (!input.bones.empty() && frames > 0) {
    double sum = 0.0;
    for (Eigen::Index t = 0; t < frames; ++t) {
      double worst = 0.0;
      for (const BoneReference& bone : input.bones) {
        const double error = std::abs((at(p, t, bone.joint) - at(p, t, bone.parent)).norm() - bone.length) * cm;
        sum += error;
        worst = std::max(worst, error);
      }
      m.bone_error_track_cm[static_cast<size_t>(t)] = worst;
      m.bone_error_max_cm = std::max(m.bone_error_max_cm, worst);
    }
    m.bone_error_mean_cm = sum / (static_cast<double>(frames) * static_cast<double>(input.bones.size()));
  }

  // Position residual.
  if (input.targets.size() > 0 && frames > 0) {
    m.has_residual = true;
    double sum = 0.0;
    for (Eigen::Index t = 0; t < frames; ++t) {
      for (int c = 0; c < kCanonicalJointCount; ++c) {
        const Eigen::Vector3d target = input.targets.block<1, 3>(t, 3 * c).transpose();
        const double error = (at(p, t, input.canonical_joints[static_cast<size_t>(c)]) - target).norm() * cm;
        sum += error;
        m.residual_max_cm = std::max(m.residual_max_cm, error);
      }
    }
    m.residual_mean_cm = sum / (static_cast<double>(frames) * kCanonicalJointCount);
  }

  // Jerk.
  if (frames >= 4) {
    double sum = 0.0;
    const double scale = cm * input.fps * input.fps * input.fps;
    for (Eigen::Index t = 0; t + 3 < frames; ++t)
      for (int joint : input.canonical_joints)
        sum += (at(p, t + 3, joint) - 3.0 * at(p, t + 2, joint) + 3.0 * at(p, t + 1, joint) - at(p, t, joint)).norm();
    m.jerk_mean_cm_s3 = sum * scale / (static_cast<double>(frames - 3) * kCanonicalJointCount);
  }
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
  }
  json["jerk_mean_cm_s3"] = metrics.jerk_mean_cm_s3;
  if (include_tracks) {
    json["skate_track_cm_s"] = metrics.skate_track_cm_s;
    json["bone_error_track_cm"] = metrics.bone_error_track_cm;
  }
  return json.dump(2) + "\n";
}

void writeMetricsJson(const ClipMetrics& metrics, const std::filesystem::path& file, bool include_tracks) {
  writeFileAtomically(file, metricsToJson(metrics, include_tracks));
}

}  // namespace motionstyle
