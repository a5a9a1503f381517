#pragma once
// Private to core/ik: the interface between the orchestration (cleanup.cpp) and the sweep over the clip
// (cleanup_solver.cpp), which runs a WindowSolver (cleanup_window_solver.h) chunk by chunk.

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
  int hips_joint = 0;                    // skeleton joint of the hips (warm start)
  const Eigen::MatrixXd& targets;        // frames x 63, file units
  // Per frame and contact track: the lock position (file units) and lock weight (contact_weight x blend).
  const std::vector<std::array<Eigen::Vector3d, kContactCount>>& lock_positions;
  const Eigen::MatrixXd& lock_weights;   // frames x 4
  ProblemConstants constants;
  double time_budget_seconds = 60.0;
  CleanupControl control;
};

struct SolverOutput {
  CleanupTermCosts costs;
  int solves = 0;  // lead-in frames included
  int total_iterations = 0;
  int solves_at_iteration_cap = 0;
  int frames_unsolved = 0;
  int chunks = 0, chunks_reused = 0, chunks_warm = 0;
};

// Receives each frame's final solution, once, in frame order: the root position (file units) and the
// local rotation of every unknown joint (CleanupModel::unknown_joints order, unit quaternions).
using FinalFrameSink = std::function<void(int frame, const Eigen::Vector3d& root_position,
                                          const Eigen::Quaterniond* rotations)>;

// Solves the clip chunk by chunk (options.chunk_frames, options.threads chunks at a time), each chunk
// frame by frame (or window by window) from its lead-in, and hands every frame to `sink` in frame
// order, on the calling thread. Holds, per chunk in flight, its solutions and the content's local
// poses of one block of frames (options.block_frames), whatever the clip's length.
SolverOutput solveCleanup(const SolverInput& input, const CleanupOptions& options, const FinalFrameSink& sink);

}  // namespace motionstyle::ik_detail
