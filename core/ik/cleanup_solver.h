#pragma once
// Private to core/ik: the interface between the orchestration (cleanup.cpp) and the Ceres solve
// (cleanup_solver.cpp). No Ceres types here.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "ik/cleanup.h"
#include "ik/cleanup_model.h"
#include "motion/kinematics.h"

namespace motionstyle::ik_detail {

struct SolverInput {
  const CleanupModel& model;
  const LocalPoses& content_poses;       // the content's local transforms (priors, fixed joints, segments)
  const Eigen::MatrixXd& content_world;  // frames x 3J, content world positions (warm start of frame 0)
  const Eigen::MatrixXd& targets;        // frames x 63, file units
  // Per frame and contact track: the lock position (file units) and lock weight (contact_weight x blend).
  const std::vector<std::array<Eigen::Vector3d, kContactCount>>& lock_positions;
  const Eigen::MatrixXd& lock_weights;   // frames x 4
  ProblemConstants constants;
  double time_budget_seconds = 60.0;
};

struct SolverOutput {
  std::vector<Eigen::Vector3d> root_positions;  // per frame, file units
  std::vector<Eigen::Quaterniond> rotations;    // [frame * unknownCount + unknown], local, unit
  CleanupTermCosts costs;
  int solves = 0;
  int total_iterations = 0;
  int solves_at_iteration_cap = 0;
  int frames_unsolved = 0;
};

SolverOutput solveCleanup(const SolverInput& input, const CleanupOptions& options);

}  // namespace motionstyle::ik_detail
