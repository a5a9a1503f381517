// bench_live [clip.bvh] [--frames N]
// What one live edit costs: the Result panel's job (StylizeCleanupJob) for a strength dragged from 1.0
// to 0.4 in steps of 0.02, with the clean-up's memory of the previous step, as the app runs it; phase by
// phase (features, network, clean-up with its contacts and metrics), the median over the steps. Default
// clip: tests/data/zombie.bvh (30 fps) played forward and back to 500 frames; network: the shipped
// elderly. Plain stdout.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "bvh/bvh_reader.h"
#include "common/resource_paths.h"
#include "features/representation.h"
#include "mapping/joint_mapping.h"
#include "motion/kinematics.h"
#include "nn/network_file.h"
#include "style/stylize_cleanup_job.h"
#include "style/stylized_cleanup.h"
#include "style/stylizer.h"

using namespace motionstyle;

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) { return std::chrono::duration<double, std::milli>(Clock::now() - start).count(); }

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

Motion pingPong(const Motion& clip, int frames) {
  Motion out = clip;
  const int n = clip.frameCount();
  out.values.resize(frames, clip.values.cols());
  for (int f = 0; f < frames; ++f) {
    const int cycle = f % (2 * n - 2);
    out.values.row(f) = clip.values.row(cycle < n ? cycle : 2 * n - 2 - cycle);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string path = std::string(MOTIONSTYLE_TEST_DATA_DIR) + "/zombie.bvh";
    int frames = 500;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
      else path = arg;
    }
    const auto resources = resourceDirectory();
    const auto network = resources ? shippedNetworkFile(*resources, "elderly") : std::nullopt;
    if (!network) throw std::runtime_error("the shipped elderly network was not found");
    const Motion content = pingPong(readBvh(path), frames);
    const JointMapping mapping = mapJoints(content.skeleton, content.source);
    auto stylizer = std::make_shared<const style::Stylizer>(nn::loadStyleModel(*network), network->string());
    std::printf("clip %s: %d frames at %.0f fps; elderly; strength 1.0 -> 0.4 in steps of 0.02\n", path.c_str(),
                content.frameCount(), content.fps());

    style::StylizeCleanupJob job;
    job.content = content;
    job.mapping = mapping;
    job.stylizer = stylizer;
    job.memory = std::make_shared<style::StylizeCleanupMemory>();
    job.run();  // the first result, as the app shows it before the drag
    // Pass 1, phase by phase, as the job runs them (the network's output and the clean-up's solution
    // kept from the previous step).
    std::vector<double> features_ms, network_ms, finish_ms, cleanup_ms, solve_ms, iterations;
    for (int step = 1; step <= 30; ++step) {
      const double strength = 1.0 - 0.02 * step;
      const auto start = Clock::now();
      const MotionFeatures features = extractFeatures(content, mapping);
      features_ms.push_back(msSince(start));
      const auto network_start = Clock::now();
      const Eigen::MatrixXd network_output = stylizer->networkOutput(features.values, features.contacts, job.path);  // a new clip's cost
      network_ms.push_back(msSince(network_start));
      const auto finish_start = Clock::now();
      const style::StylizedClip stylized = stylizer->stylize(features, network_output, strength, job.path);
      finish_ms.push_back(msSince(finish_start));
      const auto cleanup_start = Clock::now();
      const style::StylizedCleanup cleaned = style::cleanUpStylizedClip(content, mapping, stylized, job.options, 0.0, {},
                                                                        {nullptr, &job.memory->cleanup});
      cleanup_ms.push_back(msSince(cleanup_start));
      solve_ms.push_back(cleaned.report.seconds * 1000.0);
      iterations.push_back(static_cast<double>(cleaned.report.total_iterations) / std::max(1, cleaned.report.solves));
    }
    // Pass 2, the whole job (back up from 0.4), without and with the memory.
    std::vector<double> whole_ms, cold_ms;
    for (int step = 1; step <= 30; ++step) {
      job.strength = 0.4 + 0.02 * step;
      auto start = Clock::now();
      job.run();
      whole_ms.push_back(msSince(start));
      style::StylizeCleanupJob cold = job;
      cold.memory = nullptr;
      cold.strength -= 0.01;
      start = Clock::now();
      cold.run();
      cold_ms.push_back(msSince(start));
    }
    std::printf("per strength step (median of 30): features %.1f ms, network %.1f ms (only for a new clip or network), "
                "strength blend and bone lengths %.1f ms, clean-up %.1f ms (the solve %.1f ms, %.1f iterations per frame)\n",
                median(features_ms), median(network_ms), median(finish_ms), median(cleanup_ms), median(solve_ms),
                median(iterations));
    std::printf("whole job: %.1f ms with the memory of the previous step (network output, clean-up), %.1f ms without\n",
                median(whole_ms), median(cold_ms));

    const MotionFeatures features = extractFeatures(content, mapping);
    // A switch to a style never computed on the clip, as the Result panel runs it: the new style's
    // memory seeded from elderly's (StylizeCleanupMemory::seedFrom), against a memory of its own.
    {
      std::vector<double> seeded_ms, seeded_cleanup_ms, seeded_iterations, own_ms, own_iterations;
      for (const char* name : {"sad", "proud", "angry", "happy", "feminine", "masculine", "youthful", "exhausted"}) {
        const auto file = shippedNetworkFile(*resources, name);
        if (!file) continue;
        style::StylizeCleanupJob other = job;
        other.strength = 1.0;
        other.stylizer = std::make_shared<const style::Stylizer>(nn::loadStyleModel(*file), file->string());
        other.stylizer->networkOutput(features.values, features.contacts, job.path);  // its first run's page faults: untimed
        other.memory = std::make_shared<style::StylizeCleanupMemory>();
        other.seed = job.memory;
        auto start = Clock::now();
        const style::StylizeCleanupResult seeded = other.run();
        seeded_ms.push_back(msSince(start));
        seeded_cleanup_ms.push_back(seeded.report.seconds * 1000.0);
        seeded_iterations.push_back(static_cast<double>(seeded.report.total_iterations) / std::max(1, seeded.report.solves));
        other.memory = std::make_shared<style::StylizeCleanupMemory>();
        other.seed = nullptr;
        start = Clock::now();
        const style::StylizeCleanupResult own = other.run();
        own_ms.push_back(msSince(start));
        own_iterations.push_back(static_cast<double>(own.report.total_iterations) / std::max(1, own.report.solves));
      }
      std::printf("style switch from elderly (median over %zu styles): job %.1f ms (the clean-up's solve %.1f ms, %.1f "
                  "iterations per frame) seeded from elderly's memory; %.1f ms (%.1f iterations) with a memory of its own\n",
                  seeded_ms.size(), median(seeded_ms), median(seeded_cleanup_ms), median(seeded_iterations), median(own_ms),
                  median(own_iterations));
    }

    // Steps solved with at most K iterations per frame from the last solution, against a full solve.
    for (int cap : {1, 3, 25}) {
      CleanupMemory memory;
      CleanupOptions capped;
      capped.max_iterations = cap;
      style::cleanUpStylizedClip(content, mapping, stylizer->stylize(features, 1.0, job.path), {}, 0.0, {},
                                 {nullptr, &memory});
      std::vector<double> capped_ms;
      double worst_cm = 0.0;
      for (int step = 1; step <= 20; ++step) {
        const style::StylizedClip stylized = stylizer->stylize(features, 1.0 - 0.02 * step, job.path);
        const auto start = Clock::now();
        const style::StylizedCleanup quick =
            style::cleanUpStylizedClip(content, mapping, stylized, capped, 0.0, {}, {nullptr, &memory});
        capped_ms.push_back(msSince(start));
        const style::StylizedCleanup full = style::cleanUpStylizedClip(content, mapping, stylized);
        const double cm = stylized.anchor.convention.cm_per_unit;
        worst_cm = std::max(worst_cm, cm * (worldPositions(quick.motion) - worldPositions(full.motion)).cwiseAbs().maxCoeff());
      }
      std::printf("at most %d iteration(s) per frame from the last solution: clean-up %.1f ms, every joint within %.2f cm "
                  "of a full solve\n", cap, median(capped_ms), worst_cm);
    }
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_live: %s\n", error.what());
    return 1;
  }
}
