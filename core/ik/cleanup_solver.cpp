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

// The content's local poses of one block of frames, recomputed when a window needs frames outside it:
// a long clip's poses (56 bytes per joint and frame) are never all held.
class ContentPoseBlock {
 public:
  ContentPoseBlock(const Motion& content, int block_frames) : content_(content), block_frames_(block_frames) {}

  // Makes frames first .. first + count - 1 available.
  void cover(int first, int count) {
    if (first >= first_ && first + count <= first_ + poses_.frames) return;
    first_ = first;
    poses_ = localPoses(content_, first, std::min(std::max(block_frames_, count), content_.frameCount() - first));
  }
  const LocalPoses& poses() const { return poses_; }
  int row(int frame) const { return frame - first_; }  // the frame's row in poses()
  const Eigen::Quaterniond& rotation(int frame, int joint) const { return poses_.rotation(row(frame), joint); }
  const Eigen::Vector3d& translation(int frame, int joint) const { return poses_.translation(row(frame), joint); }

 private:
  const Motion& content_;
  int block_frames_;
  int first_ = 0;
  LocalPoses poses_;
};

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

  // Loads the content data and targets of `frame` into the slot's FrameData (`content` covers the frame).
  void loadFrameData(int slot, int frame, const ContentPoseBlock& content) {
    FrameData& data = frames_[static_cast<size_t>(slot)];
    for (size_t c = 0; c < kCanonicalJointCount; ++c) {
      chainSegmentsAt(input_.model, input_.model.chains[c], content.poses(), content.row(frame), data.segments[c]);
      data.targets[c] = input_.targets.block<1, 3>(frame, static_cast<Eigen::Index>(3 * c)).transpose();
    }
    for (size_t i = 0; i < kContactCount; ++i) {
      data.lock_positions[i] = input_.lock_positions[static_cast<size_t>(frame)][i];
      data.lock_weights[i] = input_.lock_weights(frame, static_cast<Eigen::Index>(i));
    }
    for (int u = 0; u < unknowns_; ++u)
      data.prior_rotations[static_cast<size_t>(u)] =
          content.rotation(frame, input_.model.unknown_joints[static_cast<size_t>(u)]);
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

// The solutions of the frames a window may still read or change: frames first() .. end() - 1.
class SolutionBuffer {
 public:
  explicit SolutionBuffer(int unknowns) : unknowns_(static_cast<size_t>(unknowns)) {}
  int first() const { return first_; }
  int end() const { return first_ + static_cast<int>(roots_.size()); }
  Eigen::Vector3d& root(int frame) { return roots_[offset(frame)]; }
  Eigen::Quaterniond* rotations(int frame) { return &rotations_[offset(frame) * unknowns_]; }
  void append() {  // frame end() becomes available (its values are set by the caller)
    roots_.emplace_back(Eigen::Vector3d::Zero());
    rotations_.resize(rotations_.size() + unknowns_, Eigen::Quaterniond::Identity());
  }
  void dropBefore(int frame) {  // frames before `frame` are no longer needed
    const auto count = static_cast<size_t>(std::clamp(frame - first_, 0, end() - first_));
    roots_.erase(roots_.begin(), roots_.begin() + static_cast<std::ptrdiff_t>(count));
    rotations_.erase(rotations_.begin(), rotations_.begin() + static_cast<std::ptrdiff_t>(count * unknowns_));
    first_ += static_cast<int>(count);
  }

 private:
  size_t offset(int frame) const { return static_cast<size_t>(frame - first_); }
  size_t unknowns_;
  int first_ = 0;
  std::vector<Eigen::Vector3d> roots_;
  std::vector<Eigen::Quaterniond> rotations_;
};

}  // namespace

SolverOutput solveCleanup(const SolverInput& input, const CleanupOptions& options, const FinalFrameSink& sink) {
  const auto start_time = Clock::now();
  const int frames = static_cast<int>(input.targets.rows());
  const int unknowns = input.model.unknownCount();
  const int window = std::min(options.window_frames, frames);
  const int step = std::max(1, window - std::min(options.window_overlap, window - 1));

  SolverOutput out;
  SolutionBuffer solved(unknowns);
  ContentPoseBlock content(input.content, options.block_frames);

  // Frame 0 starts from the content pose moved so that its hips meet the target hips; later frames
  // from the previous frame's solution, moved by the targets' hips step. Frames are warm-started in
  // order, each once: frame solved.end() is the next.
  auto warmStartNext = [&]() {
    const int frame = solved.end();
    solved.append();
    if (frame == 0) {
      solved.root(0) = content.translation(0, 0) + (targetOf(input.targets, 0, CanonicalJoint::Hips) - input.content_hips_at_frame0);
      for (int u = 0; u < unknowns; ++u)
        solved.rotations(0)[u] = content.rotation(0, input.model.unknown_joints[static_cast<size_t>(u)]);
    } else {
      solved.root(frame) = solved.root(frame - 1) + targetOf(input.targets, frame, CanonicalJoint::Hips) -
                           targetOf(input.targets, frame - 1, CanonicalJoint::Hips);
      std::copy(solved.rotations(frame - 1), solved.rotations(frame - 1) + unknowns, solved.rotations(frame));
    }
    if (!input.model.root_translation_free) solved.root(frame) = content.translation(frame, 0);
  };

  WindowProblem problem(input, options, window);
  // Puts frames first .. first + window - 1 into slots 2.., their two predecessors into slots 0, 1.
  auto loadWindow = [&](int first) {
    content.cover(first, window);
    for (int i = 0; i < window; ++i) {
      const int frame = first + i;
      while (solved.end() <= frame) warmStartNext();
      problem.setSlot(2 + i, solved.root(frame), solved.rotations(frame));
      problem.loadFrameData(2 + i, frame, content);
    }
    for (int slot = 0; slot < 2; ++slot) {
      // Before the clip's start: a copy of the first frame, unused (its smoothness weight is 0).
      const int frame = first - 2 + slot >= 0 ? first - 2 + slot : first;
      problem.setSlot(slot, solved.root(frame), solved.rotations(frame));
    }
  };

  // A frame is final once the next window starts after it: its cost is taken from the problem as it
  // stands (its predecessors are final too) and it goes to the sink.
  int start = 0;
  int next_final = 0;  // the first frame not yet handed to the sink
  bool out_of_time = false;
  while (start < frames) {
    const int first = std::min(start, frames - window);
    const double remaining = input.time_budget_seconds - std::chrono::duration<double>(Clock::now() - start_time).count();
    if (!out_of_time && remaining <= 0.0) {
      out_of_time = true;  // the rest keeps its warm start
      out.frames_unsolved = frames - start;
    }
    loadWindow(first);
    if (!out_of_time) {
      const ceres::Solver::Summary summary = problem.solve(remaining);
      ++out.solves;
      out.total_iterations += summary.num_successful_steps + summary.num_unsuccessful_steps;
      if (summary.termination_type == ceres::NO_CONVERGENCE) ++out.solves_at_iteration_cap;
      for (int i = 0; i < window; ++i) problem.getSlot(2 + i, solved.root(first + i), solved.rotations(first + i));
    }
    const int next_start = first + window >= frames ? frames : first + step;
    const int next_first = next_start >= frames ? frames : std::min(next_start, frames - window);
    for (; next_final < next_first; ++next_final) {
      problem.addCosts(2 + next_final - first, out.costs);
      sink(next_final, solved.root(next_final), solved.rotations(next_final));
    }
    solved.dropBefore(next_first - 2);
    start = next_start;
  }
  return out;
}

}  // namespace motionstyle::ik_detail
