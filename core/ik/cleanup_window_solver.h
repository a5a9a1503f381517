#pragma once
// Private to core/ik: what the clean-up's sweep (cleanup_solver.cpp) asks of a solver: solve a window
// of consecutive frames, the two frames before it held constant (they anchor the smoothness terms).
// Two implementations, one cost (cost_functors.h):
//   - CleanupSolver::KinematicTree: one frame at a time (window 1), cleanup_frame_solver.h;
//   - CleanupSolver::Ceres: Ceres' Levenberg-Marquardt with automatic differentiation, any window
//     (cleanup_ceres_window.cpp); the reference the tree solver is tested against.
// No Ceres types here.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>

#include "ik/cleanup.h"
#include "ik/cleanup_frame_solver.h"
#include "ik/cleanup_model.h"

namespace motionstyle::ik_detail {

struct WindowSolveStats {
  int iterations = 0;  // steps tried, accepted or not
  bool at_iteration_cap = false;
};

class WindowSolver {
 public:
  virtual ~WindowSolver() = default;
  virtual int window() const = 0;
  // The data of window frame i (0 .. window() - 1), refilled by the caller before each solve.
  virtual FrameData& frame(int i) = 0;
  // The two frames before the window, read when frame(0).smoothness_scale > 0 (frame 1 reads one of them).
  virtual void setPrevious(FrameRef before_previous, FrameRef previous) = 0;
  virtual void setStart(int i, const Eigen::Vector3d& root, const Eigen::Quaterniond* rotations) = 0;
  // Solves within `seconds` of wall clock (the Ceres solver's limit; the tree solver's frames are
  // too short to interrupt).
  virtual WindowSolveStats solve(double seconds) = 0;
  virtual void solution(int i, Eigen::Vector3d& root, Eigen::Quaterniond* rotations) const = 0;
  // Adds window frame i's cost terms at the solution.
  virtual void addCosts(int i, CleanupTermCosts& costs) const = 0;
};

// The solver options.solver names, for windows of `window` frames (1 for the kinematic tree solver).
std::unique_ptr<WindowSolver> makeWindowSolver(const CleanupModel& model, const CleanupOptions& options,
                                               const ProblemConstants& constants, int window);

// The Ceres implementation (cleanup_ceres_window.cpp).
std::unique_ptr<WindowSolver> makeCeresWindowSolver(const CleanupModel& model, const CleanupOptions& options,
                                                    const ProblemConstants& constants, int window);

}  // namespace motionstyle::ik_detail
