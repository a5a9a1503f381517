#pragma once
// Private to core/ik: the clean-up problem's structure (which joints are unknowns, the kinematic tree
// they form) and the per-frame data both solvers read (cleanup_frame_solver.h, cleanup_ceres_window.h).
// Plain Eigen, no Ceres.
//
// The unknowns form a tree: node 0 is the root position P (the "origin"), node u + 1 the local
// rotation R_u of unknown joint u, whose parent node is its nearest unknown strict ancestor (or the
// origin). Between a node and its parent lie only joints whose rotation is NOT solved, so per frame
//   o_n = o_p + W_p s_n,   W_n = W_p M_n R_n        (o_0 = P, W_0 = I)
// gives the world position o_n and world rotation W_n of every node, with s_n the translation from the
// parent node's joint to node n's joint in the parent's rotated frame and M_n the product of the FIXED
// rotations met between them (identity on ordinary rigs). A canonical joint c hangs off its anchor
// node a_c (its nearest unknown strict ancestor): p_c = o_a + W_a t_c. s, M and t come from the
// content's per-frame local translations and rotations, so every bone keeps its length exactly.
// (BVH: world_j = world_parent * T(t_j) * R_j.)

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "features/feature_layout.h"
#include "motion/kinematics.h"
#include "motion/skeleton.h"

namespace motionstyle::ik_detail {

struct ChainSegment {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // s_n, file units, in the parent node's frame
  Eigen::Matrix3d fixed_rotation = Eigen::Matrix3d::Identity();  // M_n
  bool has_fixed_rotation = false;                        // M_n != I (skip the product when false)
};

struct ChainSpec {
  int tip_joint = 0;             // skeleton joint index
  std::vector<int> path;         // skeleton joints root .. tip inclusive
  std::vector<int> pivots;       // index into CleanupModel::unknown_joints of each solved ancestor, root first
};

struct CleanupModel {
  std::vector<int> unknown_joints;          // skeleton joints whose rotation is solved, parents first
  std::vector<int> unknown_index_of_joint;  // skeleton joint -> index into unknown_joints, or -1
  std::vector<int> unknown_parent;          // nearest unknown strict ancestor (index into unknown_joints), or -1
  std::vector<bool> unknown_is_canonical;   // the unknown joint is itself one of the 21 canonical joints
  std::vector<int> tree_joints;             // every joint on a path root .. mapped joint, parents first
  bool root_translation_free = false;       // the root has all three position channels
  std::array<ChainSpec, kCanonicalJointCount> chains;  // pivots.back() is the tip's anchor (none: the origin)

  int unknownCount() const { return static_cast<int>(unknown_joints.size()); }
};

// Joints whose rotation moves a mapped joint (strict ancestors of one) and that have 3 rotation
// channels become unknowns; all others keep the content's rotation.
CleanupModel buildCleanupModel(const Skeleton& skeleton, const std::array<int, kCanonicalJointCount>& mapped);

// One frame's tree: s_n and M_n of every unknown (unknown_joints order) and t_c of every canonical joint.
struct TreeSegments {
  std::vector<ChainSegment> nodes;                          // per unknown joint
  std::array<Eigen::Vector3d, kCanonicalJointCount> tips;   // t_c, in the anchor node's frame
  std::vector<ChainSegment> joints;  // workspace: every skeleton joint relative to its anchor node
};

// The tree's segments at row `frame` of `content` (the content's local poses). Resizes segments.nodes.
void treeSegmentsAt(const CleanupModel& model, const Skeleton& skeleton, const LocalPoses& content, int frame,
                    TreeSegments& segments);

// Everything the cost functors of one frame read. Functors hold a pointer to their frame's FrameData,
// which is refilled (never reallocated) before each solve.
struct FrameData {
  TreeSegments tree;
  std::array<Eigen::Vector3d, kCanonicalJointCount> targets;        // file units
  std::array<Eigen::Vector3d, kContactCount> lock_positions;        // file units
  std::array<double, kContactCount> lock_weights{};                 // contact_weight x blend, 0 = off
  std::vector<Eigen::Quaterniond> prior_rotations;                  // content rotation per unknown joint
  double smoothness_scale = 0.0;  // 1 when the two previous frames exist, else 0
};

// Problem-wide constants the functors share.
struct ProblemConstants {
  double cm_per_unit = 1.0;
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  double floor_height = 0.0;  // file units
};

}  // namespace motionstyle::ik_detail
