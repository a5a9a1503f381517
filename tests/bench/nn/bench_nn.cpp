// bench_nn: figures for the neural core (README: "bench_nn" and "bench_nn --residual-experiment").
//   stylize 240 / 960 / 14,400 frames with the float32 fast path (ms and frames/s, median of runs)
//   one transformation-network training step (forward + backward, full eq. 10 loss), batch 16 x 240
//   one loss network training step (eq. 3, dropout on), batch 16 x 240
// By default on 1 and then 2 threads (each in a forked child: the compute pool's size is fixed at its
// first use); --threads N runs N only. Lines start with "[threads=N]" (tests/peer/pytorch_peer.py
// parses them).
// bench_nn --full-training [--epochs N] [--synthetic]: a 100-epoch style training over 72,000 frames
// (bench_training.cpp); fewer epochs are extrapolated, and say so.
// bench_nn --residual-experiment [steps] [style weight]: trains T with and without the residual
// connection on synthetic data (same seeds, same budget) and prints validation losses.
// Threads: MOTIONSTYLE_NN_THREADS (default: all hardware threads, at most 8).

#include <algorithm>
#include <array>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "bench_training.h"
#include "nn/adam.h"
#include "nn/compute_pool.h"
#include "common/allocator_tuning.h"
#include "nn/fast_stylizer.h"
#include "nn/transformation_objective.h"

namespace {

using namespace motionstyle;
using namespace motionstyle::nn;

template <typename S>
Mat<S> randomMatrix(Eigen::Index rows, Eigen::Index cols, std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Mat<S> m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = static_cast<S>(u(rng));
  return m;
}

double processCpuMs() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

// The machine is shared: besides the wall time we report the process CPU time per call (all threads),
// which other processes inflate much less. Both are medians over `runs` calls after `warmup` calls.
struct Timing {
  double wall_ms;
  double cpu_ms;
};

Timing medianMs(int warmup, int runs, const std::function<void()>& f) {
  for (int i = 0; i < warmup; ++i) f();
  std::vector<double> wall;
  std::vector<double> cpu;
  for (int i = 0; i < runs; ++i) {
    const double cpu_start = processCpuMs();
    const auto start = std::chrono::steady_clock::now();
    f();
    wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    cpu.push_back(processCpuMs() - cpu_start);
  }
  std::sort(wall.begin(), wall.end());
  std::sort(cpu.begin(), cpu.end());
  return {wall[wall.size() / 2], cpu[cpu.size() / 2]};
}

double loadAverage() {
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}


// Synthetic motion with the structure of real features: a 21-joint chain with FIXED bone lengths whose
// bone directions oscillate smoothly (phases and frequencies random per clip), a root walking forward
// with a little sway and turning. Returned DE-normalised (cm, cm/frame, rad/frame).
Mat<double> syntheticMotion(Eigen::Index frames, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  static const std::array<double, kCanonicalJointCount> kLength = {0,  10, 42, 40, 15, 10, 42, 40, 15, 12, 15,
                                                                  15, 12, 16, 28, 25, 8,  16, 28, 25, 8};
  const double step_rate = 0.05 + 0.05 * u(rng);  // rad per frame of the gait cycle
  std::array<Eigen::Vector3d, kCanonicalJointCount> base{}, swing{};
  std::array<double, kCanonicalJointCount> phase{};
  for (int j = 1; j < kCanonicalJointCount; ++j) {
    const bool up = j >= 9 && j <= 12;
    const bool arm = j >= 13;
    base[static_cast<std::size_t>(j)] = up ? Eigen::Vector3d(0, 1, 0) : arm ? Eigen::Vector3d(j < 17 ? 0.3 : -0.3, -1, 0) : Eigen::Vector3d(0, -1, 0.05);
    if (j == 1 || j == 13) base[static_cast<std::size_t>(j)] = Eigen::Vector3d(1, 0, 0);
    if (j == 5 || j == 17) base[static_cast<std::size_t>(j)] = Eigen::Vector3d(-1, 0, 0);
    swing[static_cast<std::size_t>(j)] = Eigen::Vector3d(0.1 * u(rng), 0.1 * u(rng), 0.3 + 0.4 * u(rng));
    phase[static_cast<std::size_t>(j)] = (j >= 5 && j <= 8) || j >= 17 ? 3.14159 : 0.0;
  }
  Mat<double> x(kFeatureCount, frames);
  for (Eigen::Index t = 0; t < frames; ++t) {
    const double cycle = step_rate * static_cast<double>(t);
    // Scalar writes: GCC 12 misreports AVX-512 loads when a fixed-size vector meets a dynamic block.
    x(0, t) = 0;
    x(1, t) = 95 + 2 * std::sin(2 * cycle);
    x(2, t) = 0;
    for (int j = 1; j < kCanonicalJointCount; ++j) {
      const auto js = static_cast<std::size_t>(j);
      const Eigen::Vector3d direction = (base[js] + swing[js] * std::sin(cycle + phase[js])).normalized();
      const int parent = kCanonicalParent[js];
      for (int a = 0; a < 3; ++a) x(3 * j + a, t) = x(3 * parent + a, t) + kLength[js] * direction(a);
    }
    x(kSidewaysVelocity, t) = 0.3 * std::sin(cycle);
    x(kForwardVelocity, t) = 2.0 + 0.5 * std::sin(2 * cycle);
    x(kTurningVelocity, t) = 0.01 * std::sin(0.1 * cycle);
  }
  return x;
}

// Per-feature statistics of synthetic motion (std floored so constant features stay finite).
FeatureStatistics syntheticNormalisation() {
  std::mt19937 rng(123);
  const Mat<double> x = syntheticMotion(4000, rng);
  FeatureStatistics n;
  n.mean = x.rowwise().mean();
  n.std = ((x.colwise() - n.mean).array().square().rowwise().mean()).sqrt().matrix();
  n.std = n.std.cwiseMax(1e-2);
  return n;
}

template <typename S>
Mat<S> syntheticClip(Eigen::Index frames, std::mt19937& rng) {
  static const FeatureStatistics norm = syntheticNormalisation();
  const Mat<double> x = syntheticMotion(frames, rng);
  return ((x.colwise() - norm.mean).array().colwise() / norm.std.array()).matrix().template cast<S>();
}

// Constraint targets taken from the content itself, as the real pipeline does: each window's bone
// lengths are the content's mean lengths, and a foot is "in contact" where the content's own foot
// displacement (eq. 7) is in the lower third for that foot.
void contentTargets(StyleBatch<float>& batch, const FeatureStatistics& norm) {
  const int windows = batch.windows();
  const Mat<double> x = (batch.content.cast<double>().array().colwise() * norm.std.array()).colwise() + norm.mean.array();
  batch.bone_lengths.resize(kBoneCount, windows);
  for (int w = 0; w < windows; ++w)
    for (int b = 0; b < kBoneCount; ++b) {
      const int child = b + 1;
      const int parent = kCanonicalParent[static_cast<std::size_t>(child)];
      double sum = 0;
      for (int t = 0; t < batch.frames; ++t) {
        const Eigen::Index c = static_cast<Eigen::Index>(w) * batch.frames + t;
        sum += (x.block(3 * child, c, 3, 1) - x.block(3 * parent, c, 3, 1)).norm();
      }
      batch.bone_lengths(b, w) = static_cast<float>(sum / batch.frames);
    }
  batch.contacts = Mat<float>::Zero(kContactCount, batch.content.cols());
  for (int k = 0; k < kContactCount; ++k) {
    const int j = index(kContactJoint[static_cast<std::size_t>(k)]);
    std::vector<std::pair<double, Eigen::Index>> displacement;
    for (int w = 0; w < windows; ++w)
      for (int t = 0; t + 1 < batch.frames; ++t) {
        const Eigen::Index c = static_cast<Eigen::Index>(w) * batch.frames + t;
        const double a = x(kTurningVelocity, c);
        const Eigen::Vector3d q = x.block(3 * j, c + 1, 3, 1);
        const Eigen::Vector3d rotated(std::cos(a) * q.x() + std::sin(a) * q.z(), q.y(), -std::sin(a) * q.x() + std::cos(a) * q.z());
        const Eigen::Vector3d d = Eigen::Vector3d(x(kSidewaysVelocity, c), 0, x(kForwardVelocity, c)) + rotated - x.block(3 * j, c, 3, 1);
        displacement.emplace_back(d.norm(), c);
      }
    std::sort(displacement.begin(), displacement.end());
    for (std::size_t i = 0; i < displacement.size() / 3; ++i) batch.contacts(k, displacement[i].second) = 1.0f;
  }
}

StyleBatch<float> syntheticBatch(const LossNetwork<float>& loss_network, const FeatureStatistics& norm, int windows, int frames,
                                 std::mt19937& rng) {
  StyleBatch<float> batch;
  batch.frames = frames;
  batch.content = syntheticClip<float>(static_cast<Eigen::Index>(windows) * frames, rng);
  contentTargets(batch, norm);
  batch.content_hidden = contentHidden(loss_network, batch.content, frames);
  // The "style": the content with a faster, larger oscillation added.
  // The "style": another synthetic clip with a fast tremor on every joint.
  Mat<float> style = syntheticClip<float>(480, rng);
  for (Eigen::Index t = 0; t < style.cols(); ++t)
    style.col(t).head(3 * kCanonicalJointCount).array() += 0.5f * static_cast<float>(std::sin(0.6 * static_cast<double>(t)));
  batch.style_grams.push_back(styleGram(loss_network, style));
  return batch;
}

void speedBench() {
  const int threads = computePool().threadCount();
  std::printf("[threads=%d] load average %.2f (the figures assume an otherwise idle machine)\n", threads,
              loadAverage());
  std::mt19937 rng(1);
  TransformationNetwork<float> t;
  LossNetwork<float> loss_network;
  t.initialise(1);
  loss_network.initialise(2);
  FastStylizer fast(t, loss_network);
  for (int frames : {240, 960, 14400}) {
    const Mat<float> x = randomMatrix<float>(kFeatureCount, frames, rng);
    Mat<float> out;
    const int runs = frames > 5000 ? 11 : 51;
    const Timing ms = medianMs(3, runs, [&] { fast.stylize(x, out); });
    std::printf("[threads=%d] stylize %6d frames: wall %8.2f ms %9.0f frames/s | cpu %8.2f ms (all threads)\n",
                threads, frames, ms.wall_ms, frames / ms.wall_ms * 1000.0, ms.cpu_ms);
  }
  {
    const Mat<float> x = randomMatrix<float>(kFeatureCount, 14400, rng);
    Mat<float> out;
    const Timing ms = medianMs(2, 11, [&] { fast.project(x, out); });
    std::printf("[threads=%d] project %6d frames: wall %8.2f ms %9.0f frames/s | cpu %8.2f ms\n", threads, 14400,
                ms.wall_ms, 14400 / ms.wall_ms * 1000.0, ms.cpu_ms);
  }
  const FeatureStatistics norm = syntheticNormalisation();
  const StyleBatch<float> batch = syntheticBatch(loss_network, norm, 16, 240, rng);
  const Timing t_ms = medianMs(1, 7, [&] {
    t.zeroGrad();
    accumulateObjective(t, loss_network, batch, norm, LossWeights{});
  });
  std::printf("[threads=%d] T training step (fwd+bwd, eq. 10), batch 16 x 240: wall %8.1f ms | cpu %8.1f ms\n",
              threads, t_ms.wall_ms, t_ms.cpu_ms);
  std::mt19937 dropout_rng(3);
  const Timing loss_network_ms = medianMs(1, 7, [&] {
    loss_network.zeroGrad();
    loss_network.accumulateReconstruction(batch.content, 240, static_cast<float>(kDefaultSparsity),
                                static_cast<float>(kDefaultInputDropout), &dropout_rng);
  });
  std::printf("[threads=%d] AE training step (fwd+bwd, eq. 3, dropout), batch 16 x 240: wall %8.1f ms | cpu %8.1f ms\n",
              threads, loss_network_ms.wall_ms, loss_network_ms.cpu_ms);
}

// Trains T on synthetic data with and without the residual connection, same seeds and budget, and
// prints the loss curve. Behind TransformationShape::residual's default.
void residualExperiment(int steps, double style_weight) {
  std::mt19937 data_rng(7);
  LossNetwork<float> loss_network;
  loss_network.initialise(5);
  // A briefly trained loss network, so hidden units mean something for the synthetic signal.
  {
    Adam<float> adam(loss_network.parameters(), AdamOptions{1e-3});
    std::mt19937 rng(9);
    for (int step = 0; step < 150; ++step) {
      const Mat<float> x = syntheticClip<float>(8 * 240, data_rng);
      adam.zeroGrad();
      const auto terms = loss_network.accumulateReconstruction(x, 240, static_cast<float>(kDefaultSparsity), 0.25f, &rng);
      adam.step();
      if (step % 50 == 0 || step == 149) std::printf("  AE step %3d  mse %.4f\n", step, terms.mse);
    }
  }
  const FeatureStatistics norm = syntheticNormalisation();
  std::vector<StyleBatch<float>> batches;
  for (int i = 0; i < 4; ++i) batches.push_back(syntheticBatch(loss_network, norm, 8, 240, data_rng));
  const StyleBatch<float> validation = syntheticBatch(loss_network, norm, 8, 240, data_rng);
  LossWeights weights;
  weights.style = style_weight;
  std::printf("loss weights: content %g style %g foot %g bone %g trajectory %g\n", weights.content, weights.style,
              weights.foot, weights.bone, weights.trajectory);
  for (bool residual : {false, true}) {
    TransformationNetwork<float> t({kFeatureCount, 128, 25, residual});
    t.initialise(11);
    Adam<float> adam(t.parameters(), AdamOptions{1e-3});
    std::printf("%s:\n", residual ? "residual (output = input + T(input))" : "plain (paper)");
    for (int step = 0; step <= steps; ++step) {
      if (step % (steps / 5) == 0) {
        const ObjectiveTerms v = evaluateObjective(t, loss_network, validation, norm, weights);
        std::printf("  step %4d  total %9.4f  content %8.4f  style %9.4f  foot %9.3f  bone %9.3f  traj %8.4f\n",
                    step, v.total, v.content, v.style, v.foot, v.bone, v.trajectory);
      }
      if (step == steps) break;
      adam.zeroGrad();
      accumulateObjective(t, loss_network, batches[static_cast<std::size_t>(step) % batches.size()], norm, weights);
      adam.step();
    }
  }
}

// speedBench() in a child process whose compute pool has `threads` threads.
int speedBenchWithThreads(int threads) {
  std::fflush(stdout);
  const pid_t child = fork();
  if (child < 0) return 1;
  if (child == 0) {
    setenv("MOTIONSTYLE_NN_THREADS", std::to_string(threads).c_str(), 1);
    speedBench();
    std::fflush(stdout);
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

int usage() {
  std::fprintf(stderr,
               "usage: bench_nn [--threads N]\n"
               "       bench_nn --full-training [--epochs N] [--synthetic] [--threads N]\n"
               "       bench_nn --residual-experiment [steps] [style weight]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  motionstyle::keepLargeAllocationsInHeap();  // as motionstyle-cli and the app do
  if (argc >= 2 && std::strcmp(argv[1], "--residual-experiment") == 0) {
    residualExperiment(argc >= 3 ? std::atoi(argv[2]) : 200, argc >= 4 ? std::atof(argv[3]) : LossWeights{}.style);
    return 0;
  }
  bool full_training = false;
  bool synthetic = false;
  int epochs = 100;
  int threads = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--full-training") {
      full_training = true;
    } else if (arg == "--synthetic") {
      synthetic = true;
    } else if (arg == "--epochs" && i + 1 < argc) {
      epochs = std::atoi(argv[++i]);
    } else if (arg == "--threads" && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else {
      return usage();
    }
  }
  if (threads > 0) setenv("MOTIONSTYLE_NN_THREADS", std::to_string(threads).c_str(), 1);  // before first use
  if (full_training) return motionstyle::bench::fullTrainingBench(epochs, synthetic);
  if (threads > 0) {
    speedBench();
    return 0;
  }
  int failed = 0;
  for (int t : {1, 2}) failed |= speedBenchWithThreads(t);
  return failed;
}
