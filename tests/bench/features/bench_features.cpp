// Feature extraction throughput: BVH motion (already parsed) -> the paper's 66 values per frame at
// 60 fps, over every clip of a folder (default ../shared/data/bandai). One thread, best of 3 passes.
// Frames are counted at the representation's rate (60 fps), i.e. frames of features produced; the
// figure for the whole pipeline (mapping, resampling, kinematics, representation, contacts) and for
// the representation alone (from world positions) are both printed.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "bvh/bvh_reader.h"
#include "features/representation.h"
#include "mapping/joint_mapping.h"

using namespace motionstyle;
using Clock = std::chrono::steady_clock;

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
  double best = 1e300;
  double frames = 0, source_frames = 0;
  for (int pass = 0; pass < 3; ++pass) {
    frames = 0;
    source_frames = 0;
    const auto start = Clock::now();
    for (size_t i = 0; i < motions.size(); ++i) {
      const MotionFeatures features = extractFeatures(motions[i], mappings[i]);
      frames += features.frameCount();
      source_frames += motions[i].frameCount();
    }
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::printf("clips %zu, source frames %.0f, feature frames (60 fps) %.0f\n", motions.size(), source_frames, frames);
  std::printf("extractFeatures: %.3f s, %.0f feature frames/s (%.0f source frames/s)\n", best, frames / best,
              source_frames / best);
  return 0;
}
