// Feature extraction throughput: BVH motion (already parsed) -> the paper's 66 values per frame at
// 60 fps, over every clip of a folder (default ../shared/data/bandai). Best of 3 passes. Frames are
// counted at the representation's rate (60 fps), i.e. frames of features produced. The whole pipeline
// (resampling, kinematics, representation, contacts) is timed on one thread, by wall-clock time and by
// the thread's CPU time (the machine is often shared: CPU time is the figure that load from other
// processes does not move), then by wall-clock time with the clips split over 2 threads.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <thread>
#include <vector>

#include "bvh/bvh_reader.h"
#include "features/representation.h"
#include "mapping/joint_mapping.h"

using namespace motionstyle;
using Clock = std::chrono::steady_clock;

namespace {

double threadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Feature frames produced for clips [begin, end).
double extractRange(const std::vector<Motion>& motions, const std::vector<JointMapping>& mappings, size_t begin,
                    size_t end) {
  double frames = 0;
  for (size_t i = begin; i < end; ++i) frames += extractFeatures(motions[i], mappings[i]).frameCount();
  return frames;
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path folder = argc > 1 ? argv[1] : std::filesystem::path(MOTIONSTYLE_SHARED_DATA_DIR) / "bandai";
  if (!std::filesystem::is_directory(folder)) {
    std::printf("bench_features: %s is absent; pass a folder of BVH files\n", folder.c_str());
    return 0;
  }
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder))
    if (entry.path().extension() == ".bvh") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<Motion> motions;
  std::vector<JointMapping> mappings;
  for (const auto& file : files) {
    motions.push_back(readBvh(file));
    mappings.push_back(mapJoints(motions.back().skeleton, file.string()));
  }
  double source_frames = 0;
  for (const Motion& motion : motions) source_frames += motion.frameCount();

  double best = 1e300, best_cpu = 1e300, frames = 0;
  for (int pass = 0; pass < 3; ++pass) {
    const auto start = Clock::now();
    const double cpu_start = threadCpuSeconds();
    frames = extractRange(motions, mappings, 0, motions.size());
    best_cpu = std::min(best_cpu, threadCpuSeconds() - cpu_start);
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::printf("clips %zu, source frames %.0f, feature frames (60 fps) %.0f\n", motions.size(), source_frames, frames);
  std::printf("extractFeatures: %.3f s, %.0f feature frames/s (%.0f source frames/s)\n", best, frames / best,
              source_frames / best);
  std::printf("extractFeatures, thread CPU time: %.3f s, %.0f feature frames/s\n", best_cpu, frames / best_cpu);

  double best_parallel = 1e300;
  for (int pass = 0; pass < 3; ++pass) {
    const auto start = Clock::now();
    double second_half = 0;
    std::thread worker([&] { second_half = extractRange(motions, mappings, motions.size() / 2, motions.size()); });
    const double first_half = extractRange(motions, mappings, 0, motions.size() / 2);
    worker.join();
    frames = first_half + second_half;
    best_parallel = std::min(best_parallel, std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::printf("extractFeatures, 2 threads: %.3f s, %.0f feature frames/s\n", best_parallel, frames / best_parallel);
  return 0;
}
