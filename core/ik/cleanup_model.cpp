#include "ik/cleanup_model.h"

#include <algorithm>
#include <cmath>

namespace motionstyle::ik_detail {
namespace {

int rotationChannelCount(const Joint& joint) {
  return static_cast<int>(std::count_if(joint.channels.begin(), joint.channels.end(), isRotation));
}

int positionChannelCount(const Joint& joint) {
  return static_cast<int>(joint.channels.size()) - rotationChannelCount(joint);
}

std::vector<int> pathFromRoot(const Skeleton& skeleton, int joint) {
  std::vector<int> path;
  for (int j = joint; j >= 0; j = skeleton.joints[static_cast<size_t>(j)].parent) path.push_back(j);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace

CleanupModel buildCleanupModel(const Skeleton& skeleton, const std::array<int, kCanonicalJointCount>& mapped) {
  const auto joint_count = static_cast<size_t>(skeleton.jointCount());
  CleanupModel model;
  model.root_translation_free = positionChannelCount(skeleton.joints[0]) == 3;

  // A joint's rotation moves a mapped joint exactly when it is a strict ancestor of one. Joints with
  // fewer than three rotation channels cannot hold an arbitrary rotation and stay as in the content.
  std::vector<bool> moves_mapped(joint_count, false);
  for (int tip : mapped)
    for (int j = skeleton.joints[static_cast<size_t>(tip)].parent; j >= 0; j = skeleton.joints[static_cast<size_t>(j)].parent)
      moves_mapped[static_cast<size_t>(j)] = true;

  std::vector<bool> is_canonical(joint_count, false);
  for (int tip : mapped) is_canonical[static_cast<size_t>(tip)] = true;

  model.unknown_index_of_joint.assign(joint_count, -1);
  for (size_t j = 0; j < joint_count; ++j) {
    if (!moves_mapped[j] || rotationChannelCount(skeleton.joints[j]) != 3) continue;
    model.unknown_index_of_joint[j] = model.unknownCount();
    model.unknown_joints.push_back(static_cast<int>(j));
    model.unknown_is_canonical.push_back(is_canonical[j]);
  }

  for (size_t c = 0; c < mapped.size(); ++c) {
    ChainSpec& chain = model.chains[c];
    chain.tip_joint = mapped[c];
    chain.path = pathFromRoot(skeleton, chain.tip_joint);
    for (size_t k = 0; k + 1 < chain.path.size(); ++k) {
      const int unknown = model.unknown_index_of_joint[static_cast<size_t>(chain.path[k])];
      if (unknown >= 0) chain.pivots.push_back(unknown);
    }
  }
  return model;
}

void chainSegmentsAt(const CleanupModel& model, const ChainSpec& chain, const LocalPoses& content, int frame,
                     std::vector<ChainSegment>& segments) {
  segments.resize(chain.pivots.size() + 1);
  size_t segment = 0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d fixed = Eigen::Matrix3d::Identity();
  bool has_fixed = false;
  for (size_t k = 0; k < chain.path.size(); ++k) {
    const int joint = chain.path[k];
    // The root's translation is the parameter P, not part of s_0.
    if (k > 0) position += has_fixed ? Eigen::Vector3d(fixed * content.translation(frame, joint))
                                     : content.translation(frame, joint);
    if (k + 1 == chain.path.size()) break;  // the tip's own rotation moves nothing mapped
    if (model.unknown_index_of_joint[static_cast<size_t>(joint)] >= 0) {
      segments[segment].translation = position;
      segments[segment].fixed_rotation = fixed;
      segments[segment].has_fixed_rotation = has_fixed;
      ++segment;
      position.setZero();
      fixed.setIdentity();
      has_fixed = false;
    } else {
      const Eigen::Quaterniond& rotation = content.rotation(frame, joint);
      if (std::abs(std::abs(rotation.w()) - 1.0) > 1e-15) {
        fixed = fixed * rotation.toRotationMatrix();
        has_fixed = true;
      }
    }
  }
  segments[segment].translation = position;
  segments[segment].fixed_rotation.setIdentity();
  segments[segment].has_fixed_rotation = false;
}

}  // namespace motionstyle::ik_detail
