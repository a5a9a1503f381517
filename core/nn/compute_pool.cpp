#include "nn/compute_pool.h"

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace motionstyle::nn {
namespace {

thread_local bool t_inside_task = false;
thread_local int t_serial_scopes = 0;  // SerialComputeScope objects alive on this thread

struct InsideTask {
  InsideTask() { t_inside_task = true; }
  ~InsideTask() { t_inside_task = false; }
};

// Spins until done() or kSpinMicroseconds have passed; returns done().
template <typename Done>
bool spinUntil(const Done& done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::microseconds(ComputePool::kSpinMicroseconds);
  for (;;) {
    for (int i = 0; i < 64; ++i) {
      if (done()) return true;
#if defined(__x86_64__) || defined(__i386__)
      __builtin_ia32_pause();
#endif
    }
    if (std::chrono::steady_clock::now() >= deadline) return done();
  }
}

}  // namespace

SerialComputeScope::SerialComputeScope() { ++t_serial_scopes; }
SerialComputeScope::~SerialComputeScope() { --t_serial_scopes; }

ComputePool::ComputePool(int threads) : thread_count_(std::max(1, threads)) {
  workers_.reserve(static_cast<std::size_t>(thread_count_ - 1));
  for (int w = 1; w < thread_count_; ++w) workers_.emplace_back([this, w] { workerLoop(w); });
}

ComputePool::~ComputePool() {
  {
    std::lock_guard<std::mutex> lock(state_);
    stop_ = true;
  }
  wake_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void ComputePool::runParts(int first, int stride) {
  for (int part = first; part < parts_; part += stride) {
    try {
      (*task_)(part);
    } catch (...) {
      std::lock_guard<std::mutex> lock(state_);
      if (!error_) error_ = std::current_exception();
    }
  }
}

void ComputePool::workerLoop(int worker) {
  long seen = 0;
  for (;;) {
    const auto woken = [&] { return stop_.load() || generation_.load() != seen; };
    if (!spinUntil(woken)) {
      std::unique_lock<std::mutex> lock(state_);
      wake_.wait(lock, woken);
    }
    if (stop_) return;
    seen = generation_;
    {
      InsideTask inside;
      runParts(worker, thread_count_);
    }
    if (pending_.fetch_sub(1) == 1) {
      // Taking the lock orders this with a caller between its check and its wait: no lost wake-up.
      std::lock_guard<std::mutex> lock(state_);
    }
    done_.notify_one();
  }
}

void ComputePool::run(int parts, const std::function<void(int)>& task) {
  if (parts <= 0) return;
  std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
  if (parts == 1 || thread_count_ == 1 || t_inside_task || t_serial_scopes > 0 || !busy.owns_lock()) {
    for (int part = 0; part < parts; ++part) task(part);
    return;
  }
  {
    std::lock_guard<std::mutex> lock(state_);
    task_ = &task;
    parts_ = parts;
    pending_ = thread_count_ - 1;
    error_ = nullptr;
    ++generation_;
  }
  wake_.notify_all();
  {
    InsideTask inside;
    runParts(0, thread_count_);
  }
  const auto finished = [&] { return pending_.load() == 0; };
  std::exception_ptr error;
  {
    if (!spinUntil(finished)) {
      std::unique_lock<std::mutex> lock(state_);
      done_.wait(lock, finished);
    }
    std::lock_guard<std::mutex> lock(state_);
    error = error_;
    error_ = nullptr;
    task_ = nullptr;
  }
  if (error) std::rethrow_exception(error);
}

void ComputePool::parallelRanges(int count, int align, int min_chunk,
                                 const std::function<void(int, int)>& range) {
  if (count <= 0) return;
  align = std::max(1, align);
  const int max_parts = std::max(1, count / std::max(1, min_chunk));
  const int parts = std::min(thread_count_, max_parts);
  if (parts <= 1) {
    range(0, count);
    return;
  }
  // Boundaries at multiples of `align`, as even as that allows.
  std::vector<int> bounds(static_cast<std::size_t>(parts) + 1, count);
  bounds[0] = 0;
  for (int p = 1; p < parts; ++p) {
    const long ideal = static_cast<long>(count) * p / parts;
    bounds[static_cast<std::size_t>(p)] =
        std::min(count, static_cast<int>((ideal + align / 2) / align * align));
  }
  run(parts, [&](int p) {
    const int begin = bounds[static_cast<std::size_t>(p)];
    const int end = bounds[static_cast<std::size_t>(p) + 1];
    if (end > begin) range(begin, end);
  });
}

void parallelItems(long items, long item_size, const std::function<void(int, int)>& range) {
  if (items <= 0) return;
  const long min_items = std::max(1L, kMinValuesPerPart / std::max(1L, item_size));
  computePool().parallelRanges(static_cast<int>(items), 1, static_cast<int>(std::min(items, min_items)), range);
}

double parallelSum(long items, long block, const std::function<double(int, int)>& part) {
  if (items <= 0) return 0.0;
  block = std::max(1L, block);
  const int blocks = static_cast<int>((items + block - 1) / block);
  std::vector<double> sums(static_cast<std::size_t>(blocks), 0.0);
  computePool().parallelRanges(blocks, 1, 1, [&](int first, int last) {
    for (int b = first; b < last; ++b)
      sums[static_cast<std::size_t>(b)] =
          part(static_cast<int>(b * block), static_cast<int>(std::min(items, (b + 1) * block)));
  });
  double total = 0.0;
  for (double s : sums) total += s;
  return total;
}

ComputePool& computePool() {
  static ComputePool pool([] {
    int threads = static_cast<int>(std::thread::hardware_concurrency());
    if (const char* env = std::getenv("MOTIONSTYLE_NN_THREADS")) {
      try {
        threads = std::stoi(env);
      } catch (const std::exception&) {
        // A malformed override is ignored: the default is always safe.
      }
    }
    return std::clamp(threads, 1, 8);
  }());
  return pool;
}

}  // namespace motionstyle::nn
