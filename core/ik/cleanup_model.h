#pragma once
// Private to core/ik: the clean-up problem's structure (which joints are unknowns, the kinematic chain
// of every canonical joint) and the per-frame data the cost functors read. Plain Eigen, no Ceres, so
// that cleanup.cpp (orchestration) and cleanup_solver.cpp (Ceres) share it.
//
// Forward kinematics of a chain, root first (BVH: world_j = world_parent * T(t_j) * R_j):
//   p_tip = P + s_0 + M_0 R_0 (s_1 + M_1 R_1 (s_2 + ... + M_{n-1} R_{n-1} s_n))
// where P is the root translation (an unknown when the root has position channels), R_k the unknown
// local rotation of the k-th solved ancestor ("pivot"), s_k the translation from pivot k-1 (or the
// root position) to pivot k (or the tip), and M_k the product of the FIXED rotations met between them
// (joints whose rotation is not solved; identity on ordinary rigs). s_k and M_k come from the content's
// per-frame local translations and rotations, so every bone keeps its length exactly.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "features/feature_layout.h"
#include "motion/kinematics.h"
#include "motion/skeleton.h"

namespace motionstyle::ik_detail {

struct ChainSegment {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  // s_k, file units, in pivot k-1's frame
  Eigen::Matrix3d fixed_rotation = Eigen::Matrix3d::Identity();  // M_k
  bool has_fixed_rotation = false;                        // M_k != I (skip the product when false)
};

struct ChainSpec {
  int tip_joint = 0;             // skeleton joint index
  std::vector<int> path;         // skeleton joints root .. tip inclusive
  std::vector<int> pivots;       // index into CleanupModel::unknown_joints of each solved ancestor, root first
};

struct CleanupModel {
  std::vector<int> unknown_joints;          // skeleton joints whose rotation is solved, parents first
  std::vector<int> unknown_index_of_joint;  // skeleton joint -> index into unknown_joints, or -1
  std::vector<bool> unknown_is_canonical;   // the unknown joint is itself one of the 21 canonical joints
  bool root_translation_free = false;       // the root has all three position channels
  std::array<ChainSpec, kCanonicalJointCount> chains;

  int unknownCount() const { return static_cast<int>(unknown_joints.size()); }
};

// Joints whose rotation moves a mapped joint (strict ancestors of one) and that have 3 rotation
// channels become unknowns; all others keep the content's rotation.
CleanupModel buildCleanupModel(const Skeleton& skeleton, const std::array<int, kCanonicalJointCount>& mapped);

// s_k and M_k of `chain` at `frame`, from the content's local poses. `segments` is resized to
// chain.pivots.size() + 1.
void chainSegmentsAt(const CleanupModel& model, const ChainSpec& chain, const LocalPoses& content, int frame,
                     std::vector<ChainSegment>& segments);

// Everything the cost functors of one frame read. Functors hold a pointer to their frame's FrameData,
// which is refilled (never reallocated) before each solve.
struct FrameData {
  std::array<std::vector<ChainSegment>, kCanonicalJointCount> segments;
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
