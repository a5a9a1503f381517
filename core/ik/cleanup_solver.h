#pragma once
// Private to core/ik: the interface between the orchestration (cleanup.cpp) and the Ceres solve
// (cleanup_solver.cpp). No Ceres types here.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <vector>

#include "ik/cleanup.h"
#include "ik/cleanup_model.h"
#include "motion/kinematics.h"

namespace motionstyle::ik_detail {

struct SolverInput {
  const CleanupModel& model;
  const Motion& content;                 // the content clip: priors, fixed joints, segments (read a block at a time)
  Eigen::Vector3d content_hips_at_frame0;  // content world position of the hips at frame 0 (warm start)
  const Eigen::MatrixXd& targets;        // frames x 63, file units
  // Per frame and contact track: the lock position (file units) and lock weight (contact_weight x blend).
  const std::vector<std::array<Eigen::Vector3d, kContactCount>>& lock_positions;
  const Eigen::MatrixXd& lock_weights;   // frames x 4
  ProblemConstants constants;
  double time_budget_seconds = 60.0;
};

struct SolverOutput {
  CleanupTermCosts costs;
  int solves = 0;
  int total_iterations = 0;
  int solves_at_iteration_cap = 0;
  int frames_unsolved = 0;
};

// Receives each frame's final solution, once, in frame order: the root position (file units) and the
// local rotation of every unknown joint (CleanupModel::unknown_joints order, unit quaternions).
using FinalFrameSink = std::function<void(int frame, const Eigen::Vector3d& root_position,
                                          const Eigen::Quaterniond* rotations)>;

// Solves frame by frame (or window by window) and hands every frame to `sink` as soon as no later
// window can change it. Holds the solutions of one window plus two frames and the content's local
// poses of one block of frames (options.block_frames), whatever the clip's length.
SolverOutput solveCleanup(const SolverInput& input, const CleanupOptions& options, const FinalFrameSink& sink);

}  // namespace motionstyle::ik_detail
