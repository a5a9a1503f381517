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

  model.unknown_parent.assign(model.unknown_joints.size(), -1);
  for (size_t u = 0; u < model.unknown_joints.size(); ++u)
    for (int j = skeleton.joints[static_cast<size_t>(model.unknown_joints[u])].parent; j >= 0;
         j = skeleton.joints[static_cast<size_t>(j)].parent)
      if (model.unknown_index_of_joint[static_cast<size_t>(j)] >= 0) {
        model.unknown_parent[u] = model.unknown_index_of_joint[static_cast<size_t>(j)];
        break;
      }

  std::vector<bool> on_tree(joint_count, false);
  for (size_t c = 0; c < mapped.size(); ++c) {
    ChainSpec& chain = model.chains[c];
    chain.tip_joint = mapped[c];
    chain.path = pathFromRoot(skeleton, chain.tip_joint);
    for (size_t k = 0; k + 1 < chain.path.size(); ++k) {
      const int unknown = model.unknown_index_of_joint[static_cast<size_t>(chain.path[k])];
      if (unknown >= 0) chain.pivots.push_back(unknown);
    }
    for (int j : chain.path) on_tree[static_cast<size_t>(j)] = true;
  }
  for (size_t j = 0; j < joint_count; ++j)
    if (on_tree[j]) model.tree_joints.push_back(static_cast<int>(j));
  return model;
}

// One pass over the tree's joints, parents first. For joint j with anchor node a (the nearest unknown
// strict ancestor, or the origin), joints[j] holds its position in a's rotated frame (translation) and
// the rotation from that frame to j's parent frame (fixed_rotation): for the root, 0 and I (its
// position is P); below an unknown parent p, t_j and I; below a fixed parent p,
//   t_j^a = t_p^a + F_p R_p t_j,   F_j = F_p R_p.
void treeSegmentsAt(const CleanupModel& model, const Skeleton& skeleton, const LocalPoses& content, int frame,
                    TreeSegments& segments) {
  segments.nodes.resize(model.unknown_joints.size());
  segments.joints.resize(skeleton.joints.size());
  for (int joint : model.tree_joints) {
    ChainSegment& here = segments.joints[static_cast<size_t>(joint)];
    const int parent = skeleton.joints[static_cast<size_t>(joint)].parent;
    if (parent < 0) {
      here = ChainSegment{};
    } else if (model.unknown_index_of_joint[static_cast<size_t>(parent)] >= 0) {
      here.translation = content.translation(frame, joint);
      here.fixed_rotation.setIdentity();
      here.has_fixed_rotation = false;
    } else {
      const ChainSegment& above = segments.joints[static_cast<size_t>(parent)];
      const Eigen::Quaterniond& rotation = content.rotation(frame, parent);
      here = above;
      if (std::abs(std::abs(rotation.w()) - 1.0) > 1e-15) {
        here.fixed_rotation = above.has_fixed_rotation ? Eigen::Matrix3d(above.fixed_rotation * rotation.toRotationMatrix())
                                                       : rotation.toRotationMatrix();
        here.has_fixed_rotation = true;
      }
      here.translation += here.has_fixed_rotation ? Eigen::Vector3d(here.fixed_rotation * content.translation(frame, joint))
                                                  : content.translation(frame, joint);
    }
  }
  for (size_t u = 0; u < model.unknown_joints.size(); ++u)
    segments.nodes[u] = segments.joints[static_cast<size_t>(model.unknown_joints[u])];
  for (size_t c = 0; c < kCanonicalJointCount; ++c)
    segments.tips[c] = segments.joints[static_cast<size_t>(model.chains[c].tip_joint)].translation;
}

}  // namespace motionstyle::ik_detail
