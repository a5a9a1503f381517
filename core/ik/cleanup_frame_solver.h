#pragma once
// Private to core/ik: one frame of the clean-up, solved by Levenberg-Marquardt on the kinematic tree
// of the unknowns (cleanup_model.h) with analytic Jacobians.
//
// The cost is the Ceres functors' (cost_functors.h; the tests compare the two):
//   0.5 * sum of the squared residuals of the mapped positions, contact locks, floor, root and rotation
//   accelerations and rotation priors of ONE frame, its two predecessors held constant.
// A step turns node k's subtree in WORLD axes about its joint, W_k <- exp([d_k]x) W_k (on the local
// rotation: R_k <- R_k exp([W_k' d_k]x)), so that it moves a canonical joint c below it by
//   dp_c / dd_k = -[p_c - o_k]x                (o_k, W_k: the node's world position and rotation)
// and the rotation terms r = w * 2 vec(conj(a) q) (sign chosen so that the product's w >= 0) by
//   dr / dd_k = w * sign * (e_w I + [e_v]x) W_k',   e = conj(a) q.
// J'J couples a node only with its ancestors (two nodes share a canonical joint below them only when one
// is the other's ancestor), so a block Cholesky that eliminates leaves first makes no fill-in, and its
// blocks come from sums over each subtree's joints in a few 3 x 3 operations each. Why not Ceres'
// general sparse solve of the same problem: its per-solve set-up and block bookkeeping cost more than
// the arithmetic (docs/decisions.md).
//
// The iteration follows Ceres' Levenberg-Marquardt (same radius update, step acceptance and
// function/parameter/gradient tolerances), so both solvers stop at the same kind of point.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "ik/cleanup.h"
#include "ik/cleanup_model.h"

namespace motionstyle::ik_detail {

// A solved frame: the root position (file units) and one unit quaternion per unknown joint.
struct FrameRef {
  const Eigen::Vector3d* root = nullptr;
  const Eigen::Quaterniond* rotations = nullptr;
};

struct FrameSolveResult {
  CleanupTermCosts costs;     // at the returned pose
  int iterations = 0;         // steps tried, accepted or not (Ceres' successful + unsuccessful steps)
  bool at_iteration_cap = false;
};

class FrameSolver {
 public:
  FrameSolver(const CleanupModel& model, const CleanupOptions& options, const ProblemConstants& constants);

  // Minimises the frame's cost starting from (root, rotations), which receive the solution. The two
  // previous frames enter the smoothness terms only when frame.smoothness_scale > 0.
  FrameSolveResult solve(const FrameData& frame, FrameRef before_previous, FrameRef previous, Eigen::Vector3d& root,
                         Eigen::Quaterniond* rotations);

  // The cost terms at (root, rotations) without solving.
  CleanupTermCosts costs(const FrameData& frame, FrameRef before_previous, FrameRef previous,
                         const Eigen::Vector3d& root, const Eigen::Quaterniond* rotations);

  // The cost's gradient J'r at (root, rotations) in the solver's coordinates [P; d_0; ...; d_{U-1}]
  // (zeros for P when the root position is fixed): what the tests compare with finite differences.
  Eigen::VectorXd gradient(const FrameData& frame, FrameRef before_previous, FrameRef previous,
                           const Eigen::Vector3d& root, const Eigen::Quaterniond* rotations);
  // J'J, dense, in the same coordinates (for the tests; where every residual is 0 it is the cost's
  // Hessian, which they compare with differences of the gradient).
  Eigen::MatrixXd normalMatrix(const FrameData& frame, FrameRef before_previous, FrameRef previous,
                               const Eigen::Vector3d& root, const Eigen::Quaterniond* rotations);

 private:
  struct Pose {  // a point of the search with its forward kinematics
    Eigen::Vector3d root;
    std::vector<Eigen::Quaterniond> rotations;  // per unknown
    std::vector<Eigen::Matrix3d> world_rotation;  // W_n per node (node 0: identity)
    std::vector<Eigen::Vector3d> world_position;  // o_n per node (node 0: root)
    std::array<Eigen::Vector3d, kCanonicalJointCount> joints;  // p_c
    CleanupTermCosts costs;
  };

  void prepareFrame(const FrameData& frame, FrameRef before_previous, FrameRef previous);
  void evaluate(Pose& pose) const;        // forward kinematics and costs
  void linearise(const Pose& pose);       // hessian_ and gradient_ (J'J and J'r) at pose
  bool solveDamped(double radius);        // step_ from (J'J + diag(J'J) / radius) step = -J'r
  void applyStep(const Pose& from, Pose& to) const;

  const CleanupModel& model_;
  CleanupOptions options_;
  ProblemConstants constants_;
  int nodes_ = 0;  // unknowns + 1
  std::vector<int> ancestor_offset_;  // node -> first entry in ancestors_ / off-diagonal storage
  std::vector<int> ancestor_count_;
  std::vector<int> ancestors_;        // per node: its ancestors, nearest first, ending with the origin
  std::array<int, kCanonicalJointCount> anchor_{};  // node each canonical joint hangs off
  std::array<double, kCanonicalJointCount> position_weight_{};
  std::array<int, kCanonicalJointCount> contact_of_joint_{};  // ContactLabel index, or -1
  std::vector<double> prior_weight_;  // per unknown

  // The frame being solved.
  const FrameData* frame_ = nullptr;
  std::vector<Eigen::Quaterniond> predicted_;  // constant-angular-velocity prediction per unknown
  Eigen::Vector3d root_prediction_ = Eigen::Vector3d::Zero();  // 2 P_{f-1} - P_{f-2}

  // Normal equations and their factorisation.
  std::vector<Eigen::Matrix3d> hessian_diag_, hessian_off_;
  std::vector<Eigen::Vector3d> gradient_, step_;
  std::vector<Eigen::Vector3d> damping_;  // diag(J'J) / radius, per node
  std::vector<Eigen::Matrix3d> factor_diag_, factor_off_;  // working copies, overwritten by the factor
  struct SubtreeMoments {  // sums over the canonical joints below a node (cleanup_frame_solver.cpp)
    double s0 = 0.0, f0 = 0.0;
    Eigen::Vector3d s1 = Eigen::Vector3d::Zero(), f1 = Eigen::Vector3d::Zero();
    Eigen::Matrix3d s2 = Eigen::Matrix3d::Zero(), f2 = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero(), pb = Eigen::Vector3d::Zero();
  };
  std::vector<SubtreeMoments> moments_;
  Pose current_, candidate_;
};

}  // namespace motionstyle::ik_detail
