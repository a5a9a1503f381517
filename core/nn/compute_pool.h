#pragma once
// A tiny fixed thread pool for splitting one matrix product (or any loop over columns) across cores.
//
// Why our own: Eigen parallelises its matrix products only through OpenMP, which the project does not
// link. The networks need exactly one pattern: "split these columns into N parts and wait", so a pool
// of N-1 persistent workers plus the calling thread is all there is. Persistent threads matter: a
// 240-frame stylize takes a few milliseconds, so spawning threads per layer would be visible.
//
// Waiting: a worker between regions, and the caller waiting for the workers, first spin for up to
// kSpinMicroseconds (a stylize runs ~30 regions a few microseconds apart; waking a sleeping thread
// through the kernel cost 15 % of a 960-frame stylize), then sleep on a condition variable.
//
// Reentrancy: one parallel region at a time. If another thread is already inside run() (e.g. the GUI
// stylizes while a training thread runs), the second caller runs every part itself, serially: correct,
// never deadlocks, just slower. Calling run() from inside a task also runs serially.

#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace motionstyle::nn {

class ComputePool {
 public:
  // threads >= 1 is the total parallelism including the calling thread (threads - 1 workers).
  explicit ComputePool(int threads);
  ~ComputePool();
  ComputePool(const ComputePool&) = delete;
  ComputePool& operator=(const ComputePool&) = delete;

  int threadCount() const { return thread_count_; }

  // How long a waiting thread spins before it sleeps.
  static constexpr int kSpinMicroseconds = 50;

  // Calls task(part) once for every part in [0, parts) and returns when all are done. Parts are spread
  // over the workers and the calling thread. The first exception thrown by a task is rethrown here
  // (after every part has finished).
  void run(int parts, const std::function<void(int)>& task);

  // Splits [0, count) into at most threadCount() contiguous ranges whose starts are multiples of
  // `align` (>= 1), each at least `min_chunk` long, and calls range(begin, end) for each in parallel.
  void parallelRanges(int count, int align, int min_chunk, const std::function<void(int, int)>& range);

 private:
  void workerLoop(int worker);
  void runParts(int first, int stride);

  int thread_count_;
  std::vector<std::thread> workers_;
  std::mutex busy_;  // held by the caller for the whole parallel region
  std::mutex state_;
  std::condition_variable wake_;
  std::condition_variable done_;
  // task_ and parts_ are written under state_ before generation_ is incremented, and read by a worker
  // after it sees the new generation_.
  const std::function<void(int)>* task_ = nullptr;
  int parts_ = 0;
  std::atomic<long> generation_ = 0;
  std::atomic<int> pending_ = 0;  // workers still running the current region
  std::atomic<bool> stop_ = false;
  std::exception_ptr error_;
};

// While one is alive on a thread, every run() called from that thread runs all its parts on that thread
// (results are the same: parts never depend on who runs them). For callers that keep every core busy
// with their own workers (a batch: one clip per core): a layer split with the pool there only made the
// workers wait for a pool thread that had no core to run on.
class SerialComputeScope {
 public:
  SerialComputeScope();
  ~SerialComputeScope();
  SerialComputeScope(const SerialComputeScope&) = delete;
  SerialComputeScope& operator=(const SerialComputeScope&) = delete;
};

// The process-wide pool used by the networks: min(hardware threads, 8) threads, created on first use.
// MOTIONSTYLE_NN_THREADS=<n> in the environment overrides the count (n >= 1), read once.
ComputePool& computePool();

// An element-wise job over `items` items of `item_size` values each (the columns of a matrix, the
// windows of a batch): range(begin, end) on computePool(), split only where each part moves at least
// kMinValuesPerPart values (a smaller copy costs less than waking a worker). Parts never overlap, so
// the result does not depend on the thread count. Why: between a training step's products, these
// copies, masks and maxima ran on one core and took a third of the step's wall time.
constexpr long kMinValuesPerPart = 1L << 15;
void parallelItems(long items, long item_size, const std::function<void(int, int)>& range);

// The sum of part(begin, end) over the consecutive blocks of `block` items (>= 1) that cover [0, items),
// blocks spread over computePool() and their sums added in block order: the same value on any thread
// count. part(begin, end) returns the sum over its own items (and may write to them).
double parallelSum(long items, long block, const std::function<double(int, int)>& part);

}  // namespace motionstyle::nn
