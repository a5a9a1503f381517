// The compute pool: parts really run on distinct threads, errors propagate, nesting stays safe.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
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
}  // namespace motionstyle::nn
