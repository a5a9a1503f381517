// The compute pool: parts really run on distinct threads, errors propagate, nesting stays safe; its
// element-wise and sum helpers cover every item once and sum in an order no thread count changes.

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "nn/compute_pool.h"

namespace motionstyle::nn {
namespace {

TEST(ComputePoolInvalid, TaskExceptionsReachTheCallerAfterEveryPartRan) {
  ComputePool pool(2);
  std::atomic<int> ran{0};
  EXPECT_THROW(pool.run(4,
                        [&](int part) {
                          ++ran;
                          if (part == 1) throw std::runtime_error("part 1 failed");
                        }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 4);
  pool.run(2, [&](int) { ++ran; });  // still usable afterwards
  EXPECT_EQ(ran.load(), 6);
}

TEST(ComputePool, PartsRunOnDistinctThreadsAndRangesCoverEverything) {
  ComputePool pool(2);
  std::mutex lock;
  std::set<std::thread::id> threads;
  pool.run(2, [&](int) {
    std::lock_guard<std::mutex> guard(lock);
    threads.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(threads.size(), 2u);

  std::vector<int> hits(1001, 0);
  pool.parallelRanges(1001, 2, 10, [&](int begin, int end) {
    EXPECT_EQ(begin % 2, 0);
    for (int i = begin; i < end; ++i) ++hits[static_cast<std::size_t>(i)];
  });
  for (int h : hits) EXPECT_EQ(h, 1);
}

TEST(ComputePool, NestedAndConcurrentCallersRunSeriallyWithoutDeadlock) {
  ComputePool pool(2);
  std::atomic<int> inner{0};
  pool.run(2, [&](int) { pool.run(3, [&](int) { ++inner; }); });
  EXPECT_EQ(inner.load(), 6);
  std::atomic<int> total{0};
  std::thread other([&] {
    for (int i = 0; i < 200; ++i) pool.run(2, [&](int) { ++total; });
  });
  for (int i = 0; i < 200; ++i) pool.run(2, [&](int) { ++total; });
  other.join();
  EXPECT_EQ(total.load(), 800);
}

// Regions back to back (the workers find the next one while they spin) and regions after a pause
// longer than the spin (the workers sleep and are woken): every part runs once per region, and what a
// part wrote (plain memory, no atomics) is what the caller reads after run() returns.
TEST(ComputePool, RegionsAfterSpinningAndAfterSleepingSeeEachOthersWrites) {
  for (int threads : {2, 4}) {
    ComputePool pool(threads);
    std::vector<long> written(16, 0);
    long expected = 0;
    for (int region = 0; region < 300; ++region) {
      if (region % 50 == 0) std::this_thread::sleep_for(std::chrono::microseconds(4 * ComputePool::kSpinMicroseconds));
      pool.run(16, [&](int part) { written[static_cast<std::size_t>(part)] += region; });
      expected += region;
      for (long value : written) ASSERT_EQ(value, expected) << threads << " threads, region " << region;
    }
  }
}

}  // namespace
TEST(ComputePoolHelpers, ParallelItemsCoversEveryItemOnceAndNothingForNoItems) {
  int calls = 0;
  parallelItems(0, 100, [&](int, int) { ++calls; });
  EXPECT_EQ(calls, 0);
  for (long item_size : {1L, 64L, kMinValuesPerPart, 10 * kMinValuesPerPart}) {
    std::vector<std::atomic<int>> hits(777);
    parallelItems(777, item_size, [&](int begin, int end) {
      for (int i = begin; i < end; ++i) ++hits[static_cast<std::size_t>(i)];
    });
    for (const auto& h : hits) EXPECT_EQ(h.load(), 1) << "item size " << item_size;
  }
}

TEST(ComputePoolHelpers, ParallelSumAddsBlocksInOrderWhateverRunsThem) {
  EXPECT_EQ(parallelSum(0, 8, [](int, int) { return 1.0; }), 0.0);
  // Terms whose floating-point sum depends on the order: 1e16 then many 1s then -1e16.
  std::vector<double> values(10001, 1.0);
  values.front() = 1e16;
  values.back() = -1e16;
  const auto part = [&](int begin, int end) {
    double s = 0;
    for (int i = begin; i < end; ++i) s += values[static_cast<std::size_t>(i)];
    return s;
  };
  for (long block : {0L, 1L, 7L, 1000L, 20000L}) {
    double expected = 0;  // the blocks' sums, added in block order
    const long b = std::max(1L, block);
    for (long first = 0; first < 10001; first += b) expected += part(static_cast<int>(first), static_cast<int>(std::min(10001L, first + b)));
    const double pooled = parallelSum(10001, block, part);
    double serial = 0;
    {
      SerialComputeScope one_thread;
      serial = parallelSum(10001, block, part);
    }
    EXPECT_EQ(pooled, expected) << "block " << block;
    EXPECT_EQ(serial, expected) << "block " << block;
  }
}

}  // namespace motionstyle::nn
