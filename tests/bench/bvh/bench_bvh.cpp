// bench_bvh [folder]: how fast parseBvh reads every .bvh under `folder` on one thread.
//
// In-memory figure: the files are loaded first, then parsed 3 times; the best pass is reported, so
// the disk and the page cache are not measured. End-to-end figure: readBvh (file reading included),
// best of 3 as well. Also times formatBvh for reference. Plain stdout; the README quotes the figures.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "common/errors.h"

namespace {

using Clock = std::chrono::steady_clock;

struct Clip {
  std::filesystem::path path;
  std::string text;
};

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

struct Timing {
  double wall = 1e300;  // seconds
  double cpu = 1e300;   // process CPU seconds: shows how much of the wall time other processes took
};

template <typename Pass>
Timing bestOfThree(const Pass& pass) {
  Timing best;
  for (int run = 0; run < 3; ++run) {
    const Clock::time_point start = Clock::now();
    const std::clock_t cpu_start = std::clock();
    pass();
    best.cpu = std::min(best.cpu, static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC);
    best.wall = std::min(best.wall, secondsSince(start));
  }
  return best;
}

void report(const char* what, double megabytes, long long frames, Timing timing) {
  std::printf("%-28s %7.1f MB %8lld frames %7.3f s %7.1f MB/s %9.0f frames/s  (CPU %.3f s: %.1f MB/s)\n", what, megabytes,
              frames, timing.wall, megabytes / timing.wall, static_cast<double>(frames) / timing.wall, timing.cpu,
              megabytes / timing.cpu);
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path folder =
      argc > 1 ? std::filesystem::path(argv[1]) : std::filesystem::path(MOTIONSTYLE_SHARED_DATA_DIR) / "bandai";
  if (!std::filesystem::is_directory(folder)) {
    std::printf("bench_bvh: %s is absent; pass a folder of .bvh files. Skipping.\n", folder.string().c_str());
    return 0;
  }

  std::vector<Clip> clips;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".bvh") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    std::ostringstream content;
    content << in.rdbuf();
    clips.push_back({entry.path(), content.str()});
  }
  std::sort(clips.begin(), clips.end(), [](const Clip& a, const Clip& b) { return a.path < b.path; });
  if (clips.empty()) {
    std::printf("bench_bvh: no .bvh file under %s. Skipping.\n", folder.string().c_str());
    return 0;
  }

  double bytes = 0.0;
  for (const Clip& clip : clips) bytes += static_cast<double>(clip.text.size());
  const double megabytes = bytes / 1e6;
  long long frames = 0;
  int rejected = 0;
  for (const Clip& clip : clips) {
    try {
      frames += motionstyle::parseBvh(clip.text, clip.path.string()).frameCount();
    } catch (const motionstyle::InputError& error) {
      ++rejected;
      std::printf("rejected: %s\n", error.what());
    }
  }
  std::printf("bench_bvh: %zu files under %s (%d rejected), one thread, best of 3 passes (MB = 10^6 bytes)\n",
              clips.size(), folder.string().c_str(), rejected);

  long long sink = 0;  // keeps the parses observable
  const Timing in_memory = bestOfThree([&] {
    for (const Clip& clip : clips) {
      try {
        sink += motionstyle::parseBvh(clip.text, clip.path.string()).values.size();
      } catch (const motionstyle::InputError&) {
      }
    }
  });
  report("parseBvh (in memory)", megabytes, frames, in_memory);

  const Timing end_to_end = bestOfThree([&] {
    for (const Clip& clip : clips) {
      try {
        sink += motionstyle::readBvh(clip.path).values.size();
      } catch (const motionstyle::InputError&) {
      }
    }
  });
  report("readBvh (with file reading)", megabytes, frames, end_to_end);

  std::vector<motionstyle::Motion> motions;
  for (const Clip& clip : clips) {
    try {
      motions.push_back(motionstyle::parseBvh(clip.text, clip.path.string()));
    } catch (const motionstyle::InputError&) {
    }
  }
  double written = 0.0;
  const Timing formatting = bestOfThree([&] {
    written = 0.0;
    for (const motionstyle::Motion& motion : motions) written += static_cast<double>(motionstyle::formatBvh(motion).size());
  });
  report("formatBvh (output size)", written / 1e6, frames, formatting);
  return sink == 42 ? 1 : 0;
}
