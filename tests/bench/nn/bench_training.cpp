// bench_nn --full-training: the issue's "100-epoch style training over 72,000 frames (20 minutes at
// 60 fps)", through the real training API (trainStyleNetwork: windows, shuffling, micro-batches, Adam,
// per-epoch checkpoints), on the licensed Bandai data when it is beside the project, else on the
// committed fixture clips repeated to the same length (clearly labelled). The loss network is the
// default architecture with initial weights: the cost of a step does not depend on the weights' values.
// --epochs N runs fewer epochs and extrapolates to 100, labelled as an extrapolation.

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <optional>
#include <vector>

#include "bench_training.h"
#include "features/feature_statistics.h"
#include "nn/compute_pool.h"
#include "style/training.h"

namespace motionstyle::bench {
namespace {

constexpr int kTargetFrames = 72000;  // 20 minutes at 60 fps

struct BenchData {
  std::string description;
  std::vector<style::MotionClip> content;
  std::filesystem::path style_clip;
  long frames = 0;
};

long frameCount(const std::vector<style::MotionClip>& clips) {
  long frames = 0;
  for (const style::MotionClip& clip : clips) frames += clip.features.values.cols();
  return frames;
}

// Bandai dataset-2 clips until 72,000 frames: the normal-style ones first (what style training uses;
// they hold about 35,000 frames), then the other styles' clips, each group in name order. The elderly
// walk is the style clip.
bool loadBandai(BenchData& data) {
  const std::filesystem::path dir = std::filesystem::path(MOTIONSTYLE_SHARED_DATA_DIR) / "bandai" / "dataset-2" / "data";
  if (!std::filesystem::is_directory(dir)) return false;
  std::vector<std::filesystem::path> normal;
  std::vector<std::filesystem::path> other;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".bvh") continue;
    (entry.path().filename().string().find("_normal_") != std::string::npos ? normal : other).push_back(entry.path());
  }
  std::sort(normal.begin(), normal.end());
  std::sort(other.begin(), other.end());
  std::vector<std::filesystem::path> files = normal;
  files.insert(files.end(), other.begin(), other.end());
  data.style_clip = dir / "dataset-2_walk_elderly_001.bvh";
  if (files.empty() || !std::filesystem::exists(data.style_clip)) return false;
  for (const std::filesystem::path& file : files) {
    if (data.frames >= kTargetFrames) break;
    data.content.push_back(style::loadMotionClip(file));
    data.frames = frameCount(data.content);
  }
  const std::size_t normal_used = std::min(normal.size(), data.content.size());
  data.description = "Bandai dataset-2, " + std::to_string(data.content.size()) + " clips (" +
                     std::to_string(normal_used) + " normal-style, then other styles, name order), style clip "
                     "dataset-2_walk_elderly_001.bvh";
  return true;
}

// The committed fixtures (CMU 131_01, zombie) repeated to 72,000 frames; style: zombie.bvh.
void loadFixtures(BenchData& data) {
  const std::filesystem::path dir = MOTIONSTYLE_TEST_DATA_DIR;
  const style::MotionClip a = style::loadMotionClip(dir / "cmu_131_01.bvh");
  const style::MotionClip b = style::loadMotionClip(dir / "zombie.bvh");
  while (data.frames < kTargetFrames) {
    data.content.push_back(data.content.size() % 2 == 0 ? a : b);
    data.frames = frameCount(data.content);
  }
  data.style_clip = dir / "zombie.bvh";
  data.description = "SYNTHETIC: the committed fixtures cmu_131_01.bvh and zombie.bvh repeated (" +
                     std::to_string(data.content.size()) + " copies), style clip zombie.bvh";
}

// CPU seconds of this process, all threads: less inflated by other processes than wall time.
double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

double loadAverage() {
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

}  // namespace

int fullTrainingBench(int epochs, bool synthetic_only) {
  if (epochs < 1) epochs = 1;
  std::printf("full style training: %d epoch(s), threads %d, load average %.2f\n", epochs,
              nn::computePool().threadCount(), loadAverage());
  BenchData data;
  const auto load_start = std::chrono::steady_clock::now();
  if (synthetic_only || !loadBandai(data)) {
    if (!synthetic_only)
      std::printf("SKIP Bandai run: %s/bandai/dataset-2 is absent (set MOTIONSTYLE_SHARED_DATA_DIR); "
                  "running on fixture repeats instead\n", MOTIONSTYLE_SHARED_DATA_DIR);
    data = BenchData{};
    loadFixtures(data);
  }
  const double load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();
  std::printf("data: %s: %ld frames at 60 fps (%.1f min), loaded in %.1f s (not counted below)\n",
              data.description.c_str(), data.frames, static_cast<double>(data.frames) / 3600.0, load_seconds);

  std::vector<Eigen::MatrixXd> values;
  for (const style::MotionClip& clip : data.content) values.push_back(clip.features.values);
  nn::LossNetworkModel loss{nn::LossNetwork<float>(), computeFeatureStatistics(values), {}};
  loss.network.initialise(1);
  loss.metadata.representation = style::currentRepresentation();

  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("motionstyle-bench-training-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  style::StyleTrainingConfig config;
  config.settings.epochs = epochs;
  config.settings.seed = 1;
  config.settings.output = dir / "bench.net";
  config.loss_network_model = loss;
  config.content_clips = data.content;
  config.styles = {style::StyleSource{std::nullopt, data.style_clip}};
  style::TrainingCallbacks callbacks;
  callbacks.progress = [](const style::TrainingProgress& p) {
    if (p.phase == style::TrainingProgress::Phase::EpochEnd)
      std::printf("  epoch %3d/%d: %d steps, total loss %.4f, %.1f s elapsed, load %.2f\n", p.epoch, p.epochs,
                  p.steps_per_epoch, p.total, p.elapsed_seconds, loadAverage());
  };
  const double cpu_start = processCpuSeconds();
  const style::StyleTrainingResult result = style::trainStyleNetwork(config, callbacks);
  const double cpu_seconds = processCpuSeconds() - cpu_start;
  std::filesystem::remove_all(dir);

  double epoch_seconds = 0;
  for (const style::EpochRecord& record : result.history) epoch_seconds += record.seconds;
  const double per_epoch = epoch_seconds / static_cast<double>(std::max<std::size_t>(1, result.history.size()));
  // Outside the epochs' own time: style Grams, content encoding, windows, the per-epoch checkpoints
  // (written after each epoch's clock stops) and the final save.
  const double setup = result.seconds - epoch_seconds;
  std::printf("measured: %d epoch(s) in %.1f s (%.2f s per epoch; %.1f s besides: checkpoints, Gram matrices, "
              "content encoding, final save)\n",
              result.epochs_completed, result.seconds, per_epoch, setup);
  if (epochs == 100)
    std::printf("100 epochs over %ld frames: %.1f min (measured)\n", data.frames, result.seconds / 60.0);
  else
    std::printf("100 epochs over %ld frames: %.1f min EXTRAPOLATED from %d epoch(s) (setup + 100 x mean epoch)\n",
                data.frames, (setup + 100.0 * per_epoch) / 60.0, epochs);
  std::printf("process CPU time: %.1f s for %d epoch(s) (all threads; on an idle 2-core machine the wall time of\n"
              "  2 threads approaches CPU time / 2): 100 epochs ~ %.1f CPU-min\n",
              cpu_seconds, result.epochs_completed,
              cpu_seconds / std::max(1, result.epochs_completed) * 100.0 / 60.0);
  std::printf("load average at the end %.2f\n", loadAverage());
  return 0;
}

}  // namespace motionstyle::bench
