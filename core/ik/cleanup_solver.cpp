// The sweep: chunks of the clip solved independently (in parallel), each frame by frame or window by
// window with a WindowSolver (cleanup_window_solver.h).
//
// A chunk covers frames [begin, end). Its sweep starts chunk_lead_in frames earlier (at the clip's
// start for the first chunk) from the content's pose moved so that its hips meet the target hips,
// exactly as the clip's frame 0 does; the lead-in frames are solved to settle the smoothness terms'
// history and then dropped. Frames are warm-started in order from the previous frame's solution,
// moved by the targets' hips step.

#include "ik/cleanup_solver.h"

#include <algorithm>
#include <cmath>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <thread>
#include <utility>

#include "common/errors.h"
#include "ik/cleanup_window_solver.h"

namespace motionstyle::ik_detail {
namespace {

using Clock = std::chrono::steady_clock;

// The content's local poses of one block of frames, recomputed when a window needs frames outside it:
// a long clip's poses (56 bytes per joint and frame) are never all held.
class ContentPoseBlock {
 public:
  ContentPoseBlock(const Motion& content, int block_frames) : content_(content), block_frames_(block_frames) {}

  // Makes frames first .. first + count - 1 available, and up to a block's worth after them but not
  // at or past `end` (the chunk's end: its neighbour's frames are its neighbour's work).
  void cover(int first, int count, int end) {
    if (poses_.frames > 0 && first >= first_ && first + count <= first_ + poses_.frames) return;
    first_ = first;
    poses_ = localPoses(content_, first, std::min(std::max(block_frames_, count), end - first));
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

Eigen::Vector3d targetOf(const Eigen::MatrixXd& targets, int frame, CanonicalJoint joint) {
  return targets.block<1, 3>(frame, 3 * index(joint)).transpose();
}

// One chunk's result: the solutions of frames [begin, end) and its share of the report.
struct ChunkResult {
  int index = 0;
  int begin = 0, end = 0;
  std::vector<Eigen::Vector3d> roots;
  std::vector<Eigen::Quaterniond> rotations;  // (end - begin) x unknowns
  SolverOutput output;
  bool reused = false, warm = false;  // from CleanupControl::memory
  std::exception_ptr error;
};

// FNV-1a over the bytes of the values a chunk's solve reads.
class Digest {
 public:
  void add(const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) value_ = (value_ ^ p[i]) * 1099511628211ull;
  }
  void add(double v) { add(&v, sizeof v); }
  void add(int v) { add(&v, sizeof v); }
  std::uint64_t value() const { return value_; }

 private:
  std::uint64_t value_ = 14695981039346656037ull;
};

}  // namespace

// One chunk as the last clean-up left it (cleanup.h: CleanupMemory).
struct ChunkMemory {
  int begin = -1, end = -1, start = -1;  // frames [begin, end), its sweep from `start`
  std::uint64_t clip = 0;                // the content's frames, the skeleton and the options
  std::uint64_t inputs = 0;              // the targets, locks and problem constants
  std::vector<Eigen::Vector3d> roots;    // frames start .. end - 1
  std::vector<Eigen::Quaterniond> rotations;
  SolverOutput output;
};

}  // namespace motionstyle::ik_detail

namespace motionstyle {
struct CleanupMemory::Chunks {
  std::vector<ik_detail::ChunkMemory> chunks;
};
CleanupMemory::CleanupMemory() : chunks_(std::make_unique<Chunks>()) {}
CleanupMemory::~CleanupMemory() = default;
void CleanupMemory::copySolutionsFrom(const CleanupMemory& other) {
  if (&other != this) chunks_->chunks = other.chunks_->chunks;
}
}  // namespace motionstyle

namespace motionstyle::ik_detail {
namespace {

std::uint64_t clipDigest(const SolverInput& input, const CleanupOptions& options, int start, int end) {
  Digest digest;
  const Motion& content = input.content;
  for (int f = start; f < end; ++f)  // row-major: one row is contiguous
    digest.add(content.values.row(f).data(), sizeof(double) * static_cast<size_t>(content.values.cols()));
  digest.add(content.frame_time);
  digest.add(content.skeleton.jointCount());
  for (const Joint& joint : content.skeleton.joints) digest.add(joint.offset.data(), sizeof(double) * 3);
  for (double weight : {options.position_weight, options.hips_weight, options.contact_weight, options.floor_weight,
                        options.root_smoothness_weight, options.rotation_smoothness_weight,
                        options.prior_weight_mapped, options.prior_weight_unmapped})
    digest.add(weight);
  for (int value : {options.max_iterations, options.window_frames, options.window_overlap, options.chunk_frames,
                    options.chunk_lead_in, static_cast<int>(options.solver), options.lock_contacts ? 1 : 0,
                    options.keep_above_floor ? 1 : 0})
    digest.add(value);
  return digest.value();
}

std::uint64_t inputsDigest(const SolverInput& input, int start, int end) {
  Digest digest;
  for (int f = start; f < end; ++f) {
    for (Eigen::Index column = 0; column < input.targets.cols(); ++column) digest.add(input.targets(f, column));
    for (Eigen::Index i = 0; i < input.lock_weights.cols(); ++i) {
      digest.add(input.lock_weights(f, i));
      if (input.lock_weights(f, i) != 0.0)  // an unused lock's position is never read (nor set)
        digest.add(input.lock_positions[static_cast<size_t>(f)][static_cast<size_t>(i)].data(), sizeof(double) * 3);
    }
  }
  digest.add(input.constants.cm_per_unit);
  digest.add(input.constants.up.data(), sizeof(double) * 3);
  digest.add(input.constants.floor_height);
  return digest.value();
}

class ChunkSweep {
 public:
  ChunkSweep(const SolverInput& input, const CleanupOptions& options, Clock::time_point deadline)
      : input_(input), options_(options), deadline_(deadline), unknowns_(input.model.unknownCount()),
        content_(input.content, options.block_frames),
        solver_(makeWindowSolver(input.model, options, input.constants,
                                 std::min(options.window_frames, input.content.frameCount()))) {}

  // Solves `chunk`, or takes it from `memory` (the chunk's slot of a CleanupMemory, or null), which
  // then holds this solve.
  void run(ChunkResult& chunk, ChunkMemory* memory) {
    const int start = std::max(0, chunk.begin - options_.chunk_lead_in);
    const int frames = chunk.end - start;
    warm_ = nullptr;
    std::uint64_t clip = 0, inputs = 0;
    if (memory) {
      clip = clipDigest(input_, options_, start, chunk.end);
      inputs = inputsDigest(input_, start, chunk.end);
      if (memory->begin == chunk.begin && memory->end == chunk.end && memory->start == start && memory->clip == clip) {
        if (memory->inputs == inputs) {
          chunk.roots.assign(memory->roots.begin() + (chunk.begin - start), memory->roots.end());
          chunk.rotations.assign(memory->rotations.begin() + static_cast<std::ptrdiff_t>((chunk.begin - start) * unknowns_),
                                 memory->rotations.end());
          chunk.output = memory->output;  // its costs; nothing was solved this time
          chunk.output.solves = chunk.output.total_iterations = chunk.output.solves_at_iteration_cap = 0;
          chunk.reused = true;
          return;
        }
        warm_ = memory;
        chunk.warm = true;
      }
    }
    const int window = std::min(solver_->window(), frames);
    const int step = std::max(1, window - std::min(options_.window_overlap, window - 1));
    roots_.assign(static_cast<size_t>(frames), Eigen::Vector3d::Zero());
    rotations_.assign(static_cast<size_t>(frames * unknowns_), Eigen::Quaterniond::Identity());
    start_ = start;
    warmed_ = 0;

    int next_final = start;  // the first frame not yet final
    for (int first = start; first < chunk.end;) {
      first = std::min(first, chunk.end - window);
      if (input_.control.cancel && input_.control.cancel->load()) throw OperationCancelled();
      loadWindow(first, window, chunk.end);
      const double remaining = std::chrono::duration<double>(deadline_ - Clock::now()).count();
      if (remaining > 0.0) {
        const WindowSolveStats stats = solver_->solve(remaining);
        ++chunk.output.solves;
        chunk.output.total_iterations += stats.iterations;
        if (stats.at_iteration_cap) ++chunk.output.solves_at_iteration_cap;
        for (int i = 0; i < window; ++i) solver_->solution(i, root(first + i), rotations(first + i));
      } else {
        chunk.output.frames_unsolved += std::max(0, first + window - std::max(next_final, chunk.begin));
      }
      const int next_first = first + window >= chunk.end ? chunk.end : std::min(first + step, chunk.end - window);
      for (; next_final < next_first; ++next_final)  // final: no later window changes these frames
        if (next_final >= chunk.begin && remaining > 0.0) solver_->addCosts(next_final - first, chunk.output.costs);
      first = first + window >= chunk.end ? chunk.end : first + step;
    }
    chunk.roots.assign(roots_.begin() + (chunk.begin - start), roots_.end());
    chunk.rotations.assign(rotations_.begin() + static_cast<std::ptrdiff_t>((chunk.begin - start) * unknowns_),
                           rotations_.end());
    if (memory) {
      *memory = ChunkMemory{};
      if (chunk.output.frames_unsolved > 0) return;  // not a solution to start from or to reuse
      *memory = ChunkMemory{chunk.begin, chunk.end, start, clip, inputs, roots_, rotations_, chunk.output};
    }
  }

 private:
  Eigen::Vector3d& root(int frame) { return roots_[static_cast<size_t>(frame - start_)]; }
  Eigen::Quaterniond* rotations(int frame) {
    return &rotations_[static_cast<size_t>(frame - start_) * static_cast<size_t>(unknowns_)];
  }

  // The next frame's warm start (frames are warmed once each, in order). With a memory: the sweep's
  // first frame from its last solution, every later one from the previous frame's new solution moved
  // by the last solution's own step between the two (root: + its step; rotation: q_new(f-1) q_last(f-1)^-1
  // q_last(f)), which carries both the motion and the correction the edit needed on the frame before.
  // Without: as the header says.
  void warmStartNext() {
    const int frame = start_ + warmed_++;
    const int hips = input_.hips_joint;
    if (warm_) {
      const auto row = static_cast<size_t>(frame - start_);
      const Eigen::Quaterniond* last = &warm_->rotations[row * static_cast<size_t>(unknowns_)];
      if (frame == start_) {
        root(frame) = warm_->roots[row];
        std::copy_n(last, unknowns_, rotations(frame));
      } else {
        root(frame) = root(frame - 1) + (warm_->roots[row] - warm_->roots[row - 1]);
        const Eigen::Quaterniond* before = last - unknowns_;
        for (int u = 0; u < unknowns_; ++u)
          rotations(frame)[u] = (rotations(frame - 1)[u] * (before[u].conjugate() * last[u])).normalized();
      }
    } else if (frame == start_) {
      const Eigen::Vector3d content_hips =
          worldPositions(input_.content.skeleton, localPoses(input_.content, frame, 1), std::span<const int>(&hips, 1))
              .row(0).transpose();
      root(frame) = content_.translation(frame, 0) + (targetOf(input_.targets, frame, CanonicalJoint::Hips) - content_hips);
      for (int u = 0; u < unknowns_; ++u)
        rotations(frame)[u] = content_.rotation(frame, input_.model.unknown_joints[static_cast<size_t>(u)]);
    } else {
      root(frame) = root(frame - 1) + targetOf(input_.targets, frame, CanonicalJoint::Hips) -
                    targetOf(input_.targets, frame - 1, CanonicalJoint::Hips);
      std::copy(rotations(frame - 1), rotations(frame - 1) + unknowns_, rotations(frame));
    }
    if (!input_.model.root_translation_free) root(frame) = content_.translation(frame, 0);
  }

  void loadFrameData(FrameData& data, int frame) {
    treeSegmentsAt(input_.model, input_.content.skeleton, content_.poses(), content_.row(frame), data.tree);
    for (size_t c = 0; c < kCanonicalJointCount; ++c)
      data.targets[c] = input_.targets.block<1, 3>(frame, static_cast<Eigen::Index>(3 * c)).transpose();
    for (size_t i = 0; i < kContactCount; ++i) {
      data.lock_positions[i] = input_.lock_positions[static_cast<size_t>(frame)][i];
      data.lock_weights[i] = input_.lock_weights(frame, static_cast<Eigen::Index>(i));
    }
    for (int u = 0; u < unknowns_; ++u)
      data.prior_rotations[static_cast<size_t>(u)] =
          content_.rotation(frame, input_.model.unknown_joints[static_cast<size_t>(u)]);
    data.smoothness_scale = frame - start_ >= 2 ? 1.0 : 0.0;
  }

  // Frames first .. first + window - 1 into the solver, with their two predecessors (before the
  // sweep's start: a copy of its first frame, unused as its smoothness weight is 0).
  void loadWindow(int first, int window, int end) {
    content_.cover(first, window, end);
    for (int i = 0; i < window; ++i) {
      const int frame = first + i;
      while (start_ + warmed_ <= frame) warmStartNext();
      solver_->setStart(i, root(frame), rotations(frame));
      loadFrameData(solver_->frame(i), frame);
    }
    const int before_previous = std::max(first - 2, start_), previous = std::max(first - 1, start_);
    solver_->setPrevious({&root(before_previous), rotations(before_previous)}, {&root(previous), rotations(previous)});
  }

  const SolverInput& input_;
  const CleanupOptions& options_;
  Clock::time_point deadline_;
  int unknowns_;
  ContentPoseBlock content_;
  std::unique_ptr<WindowSolver> solver_;
  int start_ = 0, warmed_ = 0;
  const ChunkMemory* warm_ = nullptr;  // the last solution of this chunk, or null
  std::vector<Eigen::Vector3d> roots_;
  std::vector<Eigen::Quaterniond> rotations_;
};

void addOutput(SolverOutput& total, const SolverOutput& part) {
  total.costs.position += part.costs.position;
  total.costs.contact += part.costs.contact;
  total.costs.floor += part.costs.floor;
  total.costs.smoothness += part.costs.smoothness;
  total.costs.prior += part.costs.prior;
  total.solves += part.solves;
  total.total_iterations += part.total_iterations;
  total.solves_at_iteration_cap += part.solves_at_iteration_cap;
  total.frames_unsolved += part.frames_unsolved;
}

// The fewest chunks of a clip at least twelve lead-ins long (see chunkRanges).
constexpr int kBalancedChunks = 4;

// The chunks' frame ranges: about chunk_frames long, at least two when the clip is six lead-ins long
// (so that short clips use two cores too), and of equal work: the first, which has no lead-in, is
// longer by one lead-in. Depends on the clip's length and the options only, never on the thread count.
std::vector<std::pair<int, int>> chunkRanges(int frames, const CleanupOptions& options) {
  const int lead_in = options.chunk_lead_in;
  if (frames < 6 * lead_in) return {{0, frames}};
  // At least kBalancedChunks where each can still be three lead-ins long. With two chunks on two cores
  // a live edit's job waited for whichever chunk the window's paint had preempted (a 500-frame drag:
  // 3-6 of 30 results over 50 ms); with four, the other core takes the next one (docs/decisions.md).
  const int balanced = lead_in > 0 ? std::min(kBalancedChunks, frames / (3 * lead_in)) : kBalancedChunks;
  const int count = std::max({2, balanced, static_cast<int>(std::lround(frames / static_cast<double>(options.chunk_frames)))});
  const int length = (frames - lead_in) / count;  // the others; the first: length + lead_in
  if (length < 1) return {{0, frames}};
  std::vector<std::pair<int, int>> ranges;
  int begin = 0;
  for (int k = 0; k < count; ++k) {
    const int end = k + 1 == count ? frames : begin + length + (k == 0 ? lead_in : 0);
    ranges.emplace_back(begin, end);
    begin = end;
  }
  return ranges;
}

}  // namespace

// Workers take chunks in order (at most 2 x threads ahead of the sink, which bounds the memory); the
// calling thread hands each finished chunk's frames to the sink in order while the workers go on.
SolverOutput solveCleanup(const SolverInput& input, const CleanupOptions& options, const FinalFrameSink& sink) {
  const auto budget = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(std::min(input.time_budget_seconds, 1e9)));
  const Clock::time_point deadline = Clock::now() + budget;
  const auto unknowns = static_cast<size_t>(input.model.unknownCount());
  const std::vector<std::pair<int, int>> ranges = chunkRanges(static_cast<int>(input.targets.rows()), options);
  const int chunks = static_cast<int>(ranges.size());
  std::vector<ChunkMemory>* memory = input.control.memory ? &input.control.memory->chunks().chunks : nullptr;
  if (memory) memory->resize(static_cast<size_t>(chunks));  // each worker writes its own chunks' slots
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::clamp(options.threads > 0 ? options.threads : hardware, 1, chunks);
  const int ahead = 2 * threads;

  std::mutex mutex;
  std::condition_variable changed;
  int next = 0, emitted = 0;
  bool stop = false;
  std::map<int, ChunkResult> finished;
  auto worker = [&]() {
    ChunkSweep sweep(input, options, deadline);
    while (true) {
      ChunkResult chunk;
      {
        std::unique_lock<std::mutex> lock(mutex);
        changed.wait(lock, [&] { return stop || next >= chunks || next < emitted + ahead; });
        if (stop || next >= chunks) return;
        chunk.begin = ranges[static_cast<size_t>(next)].first;
        chunk.end = ranges[static_cast<size_t>(next)].second;
        chunk.index = next++;
      }
      try {
        sweep.run(chunk, memory ? &(*memory)[static_cast<size_t>(chunk.index)] : nullptr);
      } catch (...) {
        chunk.error = std::current_exception();
      }
      {
        const std::lock_guard<std::mutex> lock(mutex);
        finished.emplace(chunk.index, std::move(chunk));
      }
      changed.notify_all();
    }
  };

  SolverOutput out;
  const auto emit = [&](const ChunkResult& chunk) {
    if (chunk.error) std::rethrow_exception(chunk.error);
    addOutput(out, chunk.output);
    ++out.chunks;
    if (chunk.reused) ++out.chunks_reused;
    if (chunk.warm) ++out.chunks_warm;
    for (int f = chunk.begin; f < chunk.end; ++f) {
      const auto row = static_cast<size_t>(f - chunk.begin);
      sink(f, chunk.roots[row], &chunk.rotations[row * unknowns]);
    }
  };
  std::vector<std::jthread> workers;
  auto stopWorkers = [&]() {
    {
      const std::lock_guard<std::mutex> lock(mutex);
      stop = true;
    }
    changed.notify_all();
    workers.clear();  // joins
  };
  try {
    if (threads == 1) {  // one core (a batch's worker, a one-chunk clip): no thread to start and hand over to
      ChunkSweep sweep(input, options, deadline);
      for (int k = 0; k < chunks; ++k) {
        ChunkResult chunk;
        chunk.begin = ranges[static_cast<size_t>(k)].first;
        chunk.end = ranges[static_cast<size_t>(k)].second;
        chunk.index = k;
        sweep.run(chunk, memory ? &(*memory)[static_cast<size_t>(k)] : nullptr);
        emit(chunk);
      }
    } else {
      for (int t = 0; t < threads; ++t) workers.emplace_back(worker);
      for (int k = 0; k < chunks; ++k) {
        ChunkResult chunk;
        {
          std::unique_lock<std::mutex> lock(mutex);
          changed.wait(lock, [&] { return finished.count(k) > 0; });
          chunk = std::move(finished.at(k));
          finished.erase(k);
        }
        emit(chunk);
        {
          const std::lock_guard<std::mutex> lock(mutex);
          ++emitted;
        }
        changed.notify_all();
      }
    }
  } catch (const OperationCancelled&) {
    stopWorkers();
    throw;  // every slot is whole (written after its chunk): the memory stays (cleanup.h)
  } catch (...) {
    stopWorkers();
    if (memory) memory->clear();  // a failed clean-up leaves nothing to trust
    throw;
  }
  stopWorkers();
  return out;
}

}  // namespace motionstyle::ik_detail
