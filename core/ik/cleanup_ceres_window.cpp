// The Ceres window solver: one ceres::Problem for a window of frames, built once and re-solved as the
// window slides over the clip.
//
// Slots: the problem holds window + 2 frame slots. Slots 0 and 1 are the two frames before the window
// (already solved, held constant: they anchor the smoothness terms); slots 2 .. window + 1 are solved.
// Functors point at their slot's FrameData, which is refilled before every solve, so the problem's
// structure never changes and nothing is reallocated per frame.

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <mutex>
#include <vector>

#include "ik/cleanup_window_solver.h"
#include "ik/cost_functors.h"

namespace motionstyle::ik_detail {
namespace {

// Jet width of the dynamic chain functors: a chain of up to 8 pivots (35 parameters) needs 5 passes.
constexpr int kChainStride = 8;

enum Term : size_t { kPositionTerm, kContactTerm, kFloorTerm, kSmoothnessTerm, kPriorTerm, kTermCount };

// Ceres 2.1 reports evaluation trouble (a residual or Jacobian that is not finite, a failed line search)
// through glog's LOG(WARNING) and LOG(ERROR) whatever Solver::Options::logging_type says: one hostile
// clip then writes megabytes to stderr. The clean-up reports what the user needs itself (CleanupReport,
// cleanup_warnings.h), so glog keeps only FATAL messages. Process-wide and once, not around each solve:
// MotionStyle logs nothing through glog, and solves may run on several threads at a time.
void keepCeresLogOffStderr() {
  static std::once_flag once;
  std::call_once(once, [] {
    FLAGS_minloglevel = google::GLOG_FATAL;
    FLAGS_stderrthreshold = google::GLOG_FATAL;
  });
}

ceres::Problem::Options problemOptions() {
  ceres::Problem::Options options;
  options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;  // one manifold shared by all rotations
  return options;
}

class CeresWindowSolver final : public WindowSolver {
 public:
  CeresWindowSolver(const CleanupModel& model, const CleanupOptions& options, const ProblemConstants& constants,
                    int window)
      : model_(model), window_(window), unknowns_(model.unknownCount()), constants_(constants),
        roots_(static_cast<size_t>(3 * slotCount())), rotations_(static_cast<size_t>(4 * unknowns_ * slotCount())),
        frames_(static_cast<size_t>(slotCount())), problem_(problemOptions()) {
    for (int s = 0; s < slotCount(); ++s) {
      problem_.AddParameterBlock(root(s), 3);
      if (s < 2 || !model.root_translation_free) problem_.SetParameterBlockConstant(root(s));
      for (int u = 0; u < unknowns_; ++u) {
        problem_.AddParameterBlock(rotation(s, u), 4, &manifold_);
        if (s < 2) problem_.SetParameterBlockConstant(rotation(s, u));
      }
      frames_[static_cast<size_t>(s)].prior_rotations.resize(static_cast<size_t>(unknowns_));
    }
    blocks_.resize(static_cast<size_t>(slotCount()));
    for (int s = 2; s < slotCount(); ++s) addSlotTerms(s, options);

    solver_options_.max_num_iterations = options.max_iterations;
    solver_options_.num_threads = 1;
    // Measured on the CMU fixture (75 tangent parameters, ~250 residuals per frame): sparse normal
    // Cholesky 1950 frames/s of CPU, dense normal Cholesky 1150, dense QR 500 (the LM-augmented QR
    // dominates). Without SuiteSparse, Eigen's sparse Cholesky performs about the same.
    solver_options_.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE))
      solver_options_.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
    else if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::EIGEN_SPARSE))
      solver_options_.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
    else
      solver_options_.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    solver_options_.logging_type = ceres::SILENT;
    solver_options_.minimizer_progress_to_stdout = false;
    keepCeresLogOffStderr();
  }

  int window() const override { return window_; }
  FrameData& frame(int i) override { return frames_[static_cast<size_t>(2 + i)]; }

  void setPrevious(FrameRef before_previous, FrameRef previous) override {
    setSlot(0, *before_previous.root, before_previous.rotations);
    setSlot(1, *previous.root, previous.rotations);
  }
  void setStart(int i, const Eigen::Vector3d& root_position, const Eigen::Quaterniond* rotations) override {
    setSlot(2 + i, root_position, rotations);
  }

  WindowSolveStats solve(double seconds) override {
    solver_options_.max_solver_time_in_seconds = std::clamp(seconds, 1e-3, 1e9);  // Ceres' own default cap
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options_, &problem_, &summary);
    return {summary.num_successful_steps + summary.num_unsuccessful_steps,
            summary.termination_type == ceres::NO_CONVERGENCE};
  }

  void solution(int i, Eigen::Vector3d& root_position, Eigen::Quaterniond* rotations) const override {
    const int slot = 2 + i;
    root_position = Eigen::Map<const Eigen::Vector3d>(&roots_[static_cast<size_t>(3 * slot)]);
    for (int u = 0; u < unknowns_; ++u) {
      const double* block = &rotations_[static_cast<size_t>(4 * (slot * unknowns_ + u))];
      rotations[u] = Eigen::Quaterniond(block[0], block[1], block[2], block[3]).normalized();
    }
  }

  void addCosts(int i, CleanupTermCosts& costs) const override {
    double* totals[kTermCount] = {&costs.position, &costs.contact, &costs.floor, &costs.smoothness, &costs.prior};
    for (size_t term = 0; term < kTermCount; ++term) {
      for (ceres::ResidualBlockId id : blocks_[static_cast<size_t>(2 + i)][term]) {
        double cost = 0.0;
        if (problem_.EvaluateResidualBlock(id, false, &cost, nullptr, nullptr)) *totals[term] += cost;
      }
    }
  }

 private:
  int slotCount() const { return window_ + 2; }
  double* root(int slot) { return &roots_[static_cast<size_t>(3 * slot)]; }
  double* rotation(int slot, int unknown) { return &rotations_[static_cast<size_t>(4 * (slot * unknowns_ + unknown))]; }

  void setSlot(int slot, const Eigen::Vector3d& root_position, const Eigen::Quaterniond* rotations) {
    Eigen::Map<Eigen::Vector3d>(root(slot)) = root_position;
    for (int u = 0; u < unknowns_; ++u) {
      const Eigen::Quaterniond q = rotations[u].normalized();
      double* block = rotation(slot, u);
      block[0] = q.w(); block[1] = q.x(); block[2] = q.y(); block[3] = q.z();
    }
  }

  template <typename Functor>
  void addChainTerm(int slot, Term term, Functor* functor, int canonical, int residuals) {
    const ChainSpec& chain = model_.chains[static_cast<size_t>(canonical)];
    auto* cost = new ceres::DynamicAutoDiffCostFunction<Functor, kChainStride>(functor);
    std::vector<double*> blocks = {root(slot)};
    cost->AddParameterBlock(3);
    for (int pivot : chain.pivots) {
      cost->AddParameterBlock(4);
      blocks.push_back(rotation(slot, pivot));
    }
    cost->SetNumResiduals(residuals);
    blocks_[static_cast<size_t>(slot)][term].push_back(problem_.AddResidualBlock(cost, nullptr, blocks));
  }

  void addSlotTerms(int s, const CleanupOptions& options) {
    const FrameData* data = &frames_[static_cast<size_t>(s)];
    for (int c = 0; c < kCanonicalJointCount; ++c) {
      const double weight = c == index(CanonicalJoint::Hips) ? options.hips_weight : options.position_weight;
      addChainTerm(s, kPositionTerm, new MappedPositionCost{&model_, data, &constants_, c, weight}, c, 3);
    }
    for (int i = 0; i < kContactCount; ++i) {
      const int canonical = index(kContactJoint[static_cast<size_t>(i)]);
      if (options.lock_contacts)
        addChainTerm(s, kContactTerm, new ContactLockCost{&model_, data, &constants_, canonical, i}, canonical, 3);
      if (options.keep_above_floor)
        addChainTerm(s, kFloorTerm, new FloorCost{&model_, data, &constants_, canonical, options.floor_weight},
                     canonical, 1);
    }
    auto& smooth = blocks_[static_cast<size_t>(s)][kSmoothnessTerm];
    smooth.push_back(problem_.AddResidualBlock(
        new ceres::AutoDiffCostFunction<RootAccelerationCost, 3, 3, 3, 3>(
            new RootAccelerationCost{data, &constants_, options.root_smoothness_weight}),
        nullptr, root(s - 2), root(s - 1), root(s)));
    for (int u = 0; u < unknowns_; ++u) {
      smooth.push_back(problem_.AddResidualBlock(
          new ceres::AutoDiffCostFunction<RotationAccelerationCost, 3, 4, 4, 4>(
              new RotationAccelerationCost{data, options.rotation_smoothness_weight}),
          nullptr, rotation(s - 2, u), rotation(s - 1, u), rotation(s, u)));
      const double prior_weight = model_.unknown_is_canonical[static_cast<size_t>(u)] ? options.prior_weight_mapped
                                                                                      : options.prior_weight_unmapped;
      blocks_[static_cast<size_t>(s)][kPriorTerm].push_back(problem_.AddResidualBlock(
          new ceres::AutoDiffCostFunction<RotationPriorCost, 3, 4>(new RotationPriorCost{data, u, prior_weight}),
          nullptr, rotation(s, u)));
    }
  }

  const CleanupModel& model_;
  int window_;
  int unknowns_;
  ProblemConstants constants_;
  std::vector<double> roots_;
  std::vector<double> rotations_;
  std::vector<FrameData> frames_;  // sized once: functors keep pointers into it
  ceres::QuaternionManifold manifold_;
  ceres::Problem problem_;
  std::vector<std::array<std::vector<ceres::ResidualBlockId>, kTermCount>> blocks_;
  ceres::Solver::Options solver_options_;
};

}  // namespace

std::unique_ptr<WindowSolver> makeCeresWindowSolver(const CleanupModel& model, const CleanupOptions& options,
                                                    const ProblemConstants& constants, int window) {
  return std::make_unique<CeresWindowSolver>(model, options, constants, window);
}

}  // namespace motionstyle::ik_detail
