// The Ceres side of the clean-up: one problem for a window of frames (a single frame by default),
// built once and re-solved as the window slides over the clip.
//
// Slots: the problem holds window + 2 frame slots. Slots 0 and 1 are the two frames before the window
// (already solved, held constant: they anchor the smoothness terms); slots 2 .. window + 1 are solved.
// Functors point at their slot's FrameData, which is refilled before every solve, so the problem's
// structure never changes and nothing is reallocated per frame.

#include "ik/cleanup_solver.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <mutex>

#include "ik/cost_functors.h"

namespace motionstyle::ik_detail {
namespace {

using Clock = std::chrono::steady_clock;

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

class WindowProblem {
 public:
  WindowProblem(const SolverInput& input, const CleanupOptions& options, int window)
      : input_(input), window_(window), unknowns_(input.model.unknownCount()),
        roots_(static_cast<size_t>(3 * slotCount())), rotations_(static_cast<size_t>(4 * unknowns_ * slotCount())),
        frames_(static_cast<size_t>(slotCount())), problem_(problemOptions()) {
    constants_ = input.constants;
    for (int s = 0; s < slotCount(); ++s) {
      problem_.AddParameterBlock(root(s), 3);
      if (s < 2 || !input.model.root_translation_free) problem_.SetParameterBlockConstant(root(s));
      for (int u = 0; u < unknowns_; ++u) {
        problem_.AddParameterBlock(rotation(s, u), 4, &manifold_);
        if (s < 2) problem_.SetParameterBlockConstant(rotation(s, u));
      }
      frames_[static_cast<size_t>(s)].prior_rotations.resize(static_cast<size_t>(unknowns_));
    }
    blocks_.resize(static_cast<size_t>(slotCount()));
    for (int s = 2; s < slotCount(); ++s) addSlotTerms(s, options);

    solver_options_.max_num_iterations = options.max_iterations;
    solver_options_.num_threads = options.threads;
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

  int slotCount() const { return window_ + 2; }
  double* root(int slot) { return &roots_[static_cast<size_t>(3 * slot)]; }
  double* rotation(int slot, int unknown) { return &rotations_[static_cast<size_t>(4 * (slot * unknowns_ + unknown))]; }

  // Loads the content data and targets of `frame` into the slot's FrameData.
  void loadFrameData(int slot, int frame) {
    FrameData& data = frames_[static_cast<size_t>(slot)];
    for (size_t c = 0; c < kCanonicalJointCount; ++c) {
      chainSegmentsAt(input_.model, input_.model.chains[c], input_.content_poses, frame, data.segments[c]);
      data.targets[c] = input_.targets.block<1, 3>(frame, static_cast<Eigen::Index>(3 * c)).transpose();
    }
    for (size_t i = 0; i < kContactCount; ++i) {
      data.lock_positions[i] = input_.lock_positions[static_cast<size_t>(frame)][i];
      data.lock_weights[i] = input_.lock_weights(frame, static_cast<Eigen::Index>(i));
    }
    for (int u = 0; u < unknowns_; ++u)
      data.prior_rotations[static_cast<size_t>(u)] =
          input_.content_poses.rotation(frame, input_.model.unknown_joints[static_cast<size_t>(u)]);
    data.smoothness_scale = frame >= 2 ? 1.0 : 0.0;
  }

  void setSlot(int slot, const Eigen::Vector3d& root_position, const Eigen::Quaterniond* rotations) {
    Eigen::Map<Eigen::Vector3d>(root(slot)) = root_position;
    for (int u = 0; u < unknowns_; ++u) {
      const Eigen::Quaterniond q = rotations[u].normalized();
      double* block = rotation(slot, u);
      block[0] = q.w(); block[1] = q.x(); block[2] = q.y(); block[3] = q.z();
    }
  }

  void getSlot(int slot, Eigen::Vector3d& root_position, Eigen::Quaterniond* rotations) {
    root_position = Eigen::Map<const Eigen::Vector3d>(root(slot));
    for (int u = 0; u < unknowns_; ++u) {
      const double* block = rotation(slot, u);
      rotations[u] = Eigen::Quaterniond(block[0], block[1], block[2], block[3]).normalized();
    }
  }

  ceres::Solver::Summary solve(double seconds) {
    solver_options_.max_solver_time_in_seconds = std::clamp(seconds, 1e-3, 1e9);  // Ceres' own default cap
    ceres::Solver::Summary summary;
    ceres::Solve(solver_options_, &problem_, &summary);
    return summary;
  }

  void addCosts(int slot, CleanupTermCosts& costs) const {
    double* totals[kTermCount] = {&costs.position, &costs.contact, &costs.floor, &costs.smoothness, &costs.prior};
    for (size_t term = 0; term < kTermCount; ++term) {
      for (ceres::ResidualBlockId id : blocks_[static_cast<size_t>(slot)][term]) {
        double cost = 0.0;
        if (problem_.EvaluateResidualBlock(id, false, &cost, nullptr, nullptr)) *totals[term] += cost;
      }
    }
  }

 private:
  template <typename Functor>
  void addChainTerm(int slot, Term term, Functor* functor, int canonical, int residuals) {
    const ChainSpec& chain = input_.model.chains[static_cast<size_t>(canonical)];
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
      addChainTerm(s, kPositionTerm, new MappedPositionCost{data, &constants_, c, weight}, c, 3);
    }
    for (int i = 0; i < kContactCount; ++i) {
      const int canonical = index(kContactJoint[static_cast<size_t>(i)]);
      if (options.lock_contacts)
        addChainTerm(s, kContactTerm, new ContactLockCost{data, &constants_, canonical, i}, canonical, 3);
      if (options.keep_above_floor)
        addChainTerm(s, kFloorTerm, new FloorCost{data, &constants_, canonical, options.floor_weight}, canonical, 1);
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
      const double prior_weight = input_.model.unknown_is_canonical[static_cast<size_t>(u)]
                                      ? options.prior_weight_mapped
                                      : options.prior_weight_unmapped;
      blocks_[static_cast<size_t>(s)][kPriorTerm].push_back(problem_.AddResidualBlock(
          new ceres::AutoDiffCostFunction<RotationPriorCost, 3, 4>(new RotationPriorCost{data, u, prior_weight}),
          nullptr, rotation(s, u)));
    }
  }

  const SolverInput& input_;
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

Eigen::Vector3d targetOf(const Eigen::MatrixXd& targets, int frame, CanonicalJoint joint) {
  return targets.block<1, 3>(frame, 3 * index(joint)).transpose();
}

}  // namespace

SolverOutput solveCleanup(const SolverInput& input, const CleanupOptions& options) {
  const auto start_time = Clock::now();
  const int frames = static_cast<int>(input.targets.rows());
  const int unknowns = input.model.unknownCount();
  const int window = std::min(options.window_frames, frames);
  const int step = std::max(1, window - std::min(options.window_overlap, window - 1));

  SolverOutput out;
  out.root_positions.resize(static_cast<size_t>(frames));
  out.rotations.resize(static_cast<size_t>(frames) * static_cast<size_t>(unknowns));
  auto rotationsOf = [&](int frame) { return &out.rotations[static_cast<size_t>(frame) * static_cast<size_t>(unknowns)]; };
  std::vector<bool> initialised(static_cast<size_t>(frames), false);

  // Frame 0 starts from the content pose moved so that its hips meet the target hips; later frames
  // from the previous frame's solution, moved by the targets' hips step.
  const int root_joint_hips = input.model.chains[static_cast<size_t>(index(CanonicalJoint::Hips))].tip_joint;
  auto warmStart = [&](int frame) {
    if (frame == 0) {
      const Eigen::Vector3d content_hips = input.content_world.block<1, 3>(0, 3 * root_joint_hips).transpose();
      out.root_positions[0] = input.content_poses.translation(0, 0) +
                              (targetOf(input.targets, 0, CanonicalJoint::Hips) - content_hips);
      for (int u = 0; u < unknowns; ++u)
        rotationsOf(0)[u] = input.content_poses.rotation(0, input.model.unknown_joints[static_cast<size_t>(u)]);
    } else {
      out.root_positions[static_cast<size_t>(frame)] =
          out.root_positions[static_cast<size_t>(frame - 1)] + targetOf(input.targets, frame, CanonicalJoint::Hips) -
          targetOf(input.targets, frame - 1, CanonicalJoint::Hips);
      std::copy(rotationsOf(frame - 1), rotationsOf(frame - 1) + unknowns, rotationsOf(frame));
    }
    if (!input.model.root_translation_free)
      out.root_positions[static_cast<size_t>(frame)] = input.content_poses.translation(frame, 0);
    initialised[static_cast<size_t>(frame)] = true;
  };

  WindowProblem problem(input, options, window);
  // Puts frames first .. first + window - 1 into slots 2.., their two predecessors into slots 0, 1.
  auto loadWindow = [&](int first) {
    for (int i = 0; i < window; ++i) {
      const int frame = first + i;
      if (!initialised[static_cast<size_t>(frame)]) warmStart(frame);
      problem.setSlot(2 + i, out.root_positions[static_cast<size_t>(frame)], rotationsOf(frame));
      problem.loadFrameData(2 + i, frame);
    }
    for (int slot = 0; slot < 2; ++slot) {
      // Before the clip's start: a copy of the first frame, unused (its smoothness weight is 0).
      const int frame = first - 2 + slot >= 0 ? first - 2 + slot : first;
      problem.setSlot(slot, out.root_positions[static_cast<size_t>(frame)], rotationsOf(frame));
    }
  };

  int start = 0;
  while (start < frames) {
    const int first = std::min(start, frames - window);
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_time).count();
    const double remaining = input.time_budget_seconds - elapsed;
    if (remaining <= 0.0) {
      for (int frame = start; frame < frames; ++frame)
        if (!initialised[static_cast<size_t>(frame)]) warmStart(frame);
      out.frames_unsolved = frames - start;
      break;
    }
    loadWindow(first);
    const ceres::Solver::Summary summary = problem.solve(remaining);
    ++out.solves;
    out.total_iterations += summary.num_successful_steps + summary.num_unsuccessful_steps;
    if (summary.termination_type == ceres::NO_CONVERGENCE) ++out.solves_at_iteration_cap;
    for (int i = 0; i < window; ++i) problem.getSlot(2 + i, out.root_positions[static_cast<size_t>(first + i)],
                                                     rotationsOf(first + i));
    start = first + window >= frames ? frames : first + step;
  }

  // Final per-term costs of the committed solution, evaluated window by window.
  for (int batch = 0; batch < frames; batch += window) {
    const int first = std::min(batch, frames - window);
    loadWindow(first);
    for (int frame = batch; frame < std::min(batch + window, frames); ++frame) problem.addCosts(2 + frame - first, out.costs);
  }
  return out;
}

}  // namespace motionstyle::ik_detail
