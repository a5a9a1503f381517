// The two WindowSolver implementations behind one factory: the tree solver (one frame) here, Ceres in
// cleanup_ceres_window.cpp.

#include "ik/cleanup_window_solver.h"

#include <algorithm>
#include <memory>
#include <vector>

namespace motionstyle::ik_detail {
namespace {

class TreeWindowSolver final : public WindowSolver {
 public:
  TreeWindowSolver(const CleanupModel& model, const CleanupOptions& options, const ProblemConstants& constants)
      : solver_(model, options, constants), rotations_(static_cast<size_t>(model.unknownCount())) {
    frame_.prior_rotations.resize(rotations_.size());
  }
  int window() const override { return 1; }
  FrameData& frame(int) override { return frame_; }
  void setPrevious(FrameRef before_previous, FrameRef previous) override {
    before_previous_ = before_previous;
    previous_ = previous;
  }
  void setStart(int, const Eigen::Vector3d& root, const Eigen::Quaterniond* rotations) override {
    root_ = root;
    std::copy(rotations, rotations + rotations_.size(), rotations_.begin());
  }
  WindowSolveStats solve(double) override {
    const FrameSolveResult result = solver_.solve(frame_, before_previous_, previous_, root_, rotations_.data());
    costs_ = result.costs;
    return {result.iterations, result.at_iteration_cap};
  }
  void solution(int, Eigen::Vector3d& root, Eigen::Quaterniond* rotations) const override {
    root = root_;
    std::copy(rotations_.begin(), rotations_.end(), rotations);
  }
  void addCosts(int, CleanupTermCosts& costs) const override {
    costs.position += costs_.position;
    costs.contact += costs_.contact;
    costs.floor += costs_.floor;
    costs.smoothness += costs_.smoothness;
    costs.prior += costs_.prior;
  }

 private:
  FrameSolver solver_;
  FrameData frame_;
  FrameRef before_previous_, previous_;
  Eigen::Vector3d root_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::Quaterniond> rotations_;
  CleanupTermCosts costs_;
};

}  // namespace

std::unique_ptr<WindowSolver> makeWindowSolver(const CleanupModel& model, const CleanupOptions& options,
                                               const ProblemConstants& constants, int window) {
  if (options.solver == CleanupSolver::Ceres) return makeCeresWindowSolver(model, options, constants, window);
  return std::make_unique<TreeWindowSolver>(model, options, constants);
}

}  // namespace motionstyle::ik_detail
