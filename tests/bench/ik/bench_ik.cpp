// bench_ik [clip.bvh] [--threads T] [--solver tree|ceres] [--window N] [--overlap M] [--iterations K]
//          [--frames F] [--chunk F] [--lead-in F] [--rotation-smoothness W] [--root-smoothness W]
//          [--prior-mapped W] [--prior-unmapped W]
// Clean-up speed (frames per second of wall clock with T threads, default 2, and of CPU; the median
// of three runs) on 240-,
// 3,600- and 14,400-frame clips built from a real clip (default: tests/data/cmu_131_01.bvh; the long
// ones loop it), plus the quality figures of cleaning damaged targets (smooth noise, foot sliding
// during contact, bone-length changes). Plain stdout.

#include <algorithm>
#include <array>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "bvh/bvh_reader.h"
#include "features/foot_contacts.h"
#include "features/representation.h"
#include "features/space_convention.h"
#include "ik/cleanup.h"
#include "ik/metrics.h"
#include "ik_test_support.h"
#include "mapping/joint_mapping.h"
#include "motion/kinematics.h"

using namespace motionstyle;

namespace {

// `frames` frames of `clip`, looping it; each loop continues from where the previous one ended
// (horizontally), so the root does not jump back.
Motion loopClip(const Motion& clip, int frames, const Eigen::Vector3d& up) {
  Motion out = clip;
  out.values.resize(frames, clip.values.cols());
  const std::vector<int> offsets = clip.skeleton.channelOffsets();
  std::array<int, 3> root_columns{-1, -1, -1};
  for (size_t c = 0; c < clip.skeleton.joints[0].channels.size(); ++c) {
    const ChannelType type = clip.skeleton.joints[0].channels[c];
    if (!isRotation(type)) root_columns[static_cast<size_t>(axisOf(type))] = offsets[0] + static_cast<int>(c);
  }
  Eigen::Vector3d shift = Eigen::Vector3d::Zero(), travel = Eigen::Vector3d::Zero();
  const int n = clip.frameCount();
  for (int axis = 0; axis < 3; ++axis)
    if (root_columns[static_cast<size_t>(axis)] >= 0)
      travel[axis] = clip.values(n - 1, root_columns[static_cast<size_t>(axis)]) - clip.values(0, root_columns[static_cast<size_t>(axis)]);
  travel -= up.dot(travel) * up;
  for (int f = 0; f < frames; ++f) {
    if (f > 0 && f % n == 0) shift += travel;
    out.values.row(f) = clip.values.row(f % n);
    for (int axis = 0; axis < 3; ++axis)
      if (root_columns[static_cast<size_t>(axis)] >= 0) out.values(f, root_columns[static_cast<size_t>(axis)]) += shift[axis];
  }
  return out;
}

struct Scenario {
  Motion clip;
  JointMapping mapping;
  Eigen::Vector3d up;
  double cm_per_unit;
  double floor;
  Eigen::MatrixXd world;
  Eigen::MatrixXi contacts;
};

Scenario makeScenario(const Motion& clip) {
  Scenario s{clip, mapJoints(clip.skeleton, clip.source), {}, 1.0, 0.0, worldPositions(clip), {}};
  const FileSpaceGround ground = detectFileSpaceGround(clip, s.mapping, canonicalJointPositions(clip, s.mapping));
  s.up = ground.up;
  s.cm_per_unit = ground.convention.cm_per_unit;
  s.floor = ground.floor_height;
  s.contacts = ground.contacts;
  return s;
}

void runOnce(const Scenario& s, const Eigen::MatrixXd& targets, const CleanupOptions& options, const char* label) {
  CleanupInput input{s.clip, s.mapping, targets, s.contacts, s.up, s.floor, s.cm_per_unit};
  CleanupReport report;
  // The median of three runs (the first in a process also pays for first-touch memory and thread start).
  std::array<std::pair<double, double>, 3> runs{};  // wall, cpu
  Motion cleaned;
  for (auto& [wall_seconds, cpu_seconds] : runs) {
    const std::clock_t cpu_start = std::clock();
    const auto wall_start = std::chrono::steady_clock::now();
    cleaned = cleanupMotion(input, options, &report);
    wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  }
  std::sort(runs.begin(), runs.end());
  const auto [wall_seconds, cpu_seconds] = runs[1];
  const Eigen::MatrixXd world = worldPositions(cleaned);
  const ClipMetrics m = test::cleanedClipMetrics(world, cleaned, s.mapping, s.contacts, targets, s.up, s.floor, s.cm_per_unit);
  const Eigen::MatrixXd clean_canonical = test::canonicalPositions(s.world, s.mapping);
  const Eigen::MatrixXd result_canonical = test::canonicalPositions(world, s.mapping);
  double change = 0.0;
  for (Eigen::Index f = 0; f < world.rows(); ++f)
    for (int c = 0; c < kCanonicalJointCount; ++c)
      change += (result_canonical.block<1, 3>(f, 3 * c) - clean_canonical.block<1, 3>(f, 3 * c)).norm();
  change *= s.cm_per_unit / (static_cast<double>(world.rows()) * kCanonicalJointCount);
  std::printf("%-8s %5d frames %6.3f s wall %6.3f s cpu %6.0f frames/s wall %6.0f frames/s cpu | iters/solve %.1f cap %d | skate %.3f cm/s | pen max %.3f cm"
              " | residual mean %.2f max %.2f cm | vs clean %.2f cm | bone max %.1e cm | jerk %.0f cm/s3 | warnings %zu\n",
              label, report.frames, wall_seconds, cpu_seconds, report.frames / wall_seconds, report.frames / cpu_seconds,
              static_cast<double>(report.total_iterations) / std::max(1, report.solves), report.solves_at_iteration_cap,
              m.foot_skate_cm_s, m.penetration_max_cm, m.residual_mean_cm, m.residual_max_cm, change,
              m.bone_error_max_cm, m.jerk_mean_cm_s3, report.warnings.size());
  std::printf("           final costs: position %.1f contact %.1f floor %.1f smoothness %.1f prior %.1f\n",
              report.final_costs.position, report.final_costs.contact, report.final_costs.floor,
              report.final_costs.smoothness, report.final_costs.prior);
  for (size_t i = 0; i < std::min<size_t>(3, report.warnings.size()); ++i)
    std::printf("           warning: %s\n", report.warnings[i].text.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string path = std::string(MOTIONSTYLE_TEST_DATA_DIR) + "/cmu_131_01.bvh";
    CleanupOptions options;
    options.threads = 2;
    std::vector<int> sizes = {240, 3600, 14400};
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--threads" && i + 1 < argc) options.threads = std::atoi(argv[++i]);
      else if (arg == "--solver" && i + 1 < argc)
        options.solver = std::string(argv[++i]) == "ceres" ? CleanupSolver::Ceres : CleanupSolver::KinematicTree;
      else if (arg == "--chunk" && i + 1 < argc) options.chunk_frames = std::atoi(argv[++i]);
      else if (arg == "--lead-in" && i + 1 < argc) options.chunk_lead_in = std::atoi(argv[++i]);
      else if (arg == "--window" && i + 1 < argc) options.window_frames = std::atoi(argv[++i]);
      else if (arg == "--overlap" && i + 1 < argc) options.window_overlap = std::atoi(argv[++i]);
      else if (arg == "--iterations" && i + 1 < argc) options.max_iterations = std::atoi(argv[++i]);
      else if (arg == "--frames" && i + 1 < argc) sizes = {std::atoi(argv[++i])};
      else if (arg == "--rotation-smoothness" && i + 1 < argc) options.rotation_smoothness_weight = std::atof(argv[++i]);
      else if (arg == "--root-smoothness" && i + 1 < argc) options.root_smoothness_weight = std::atof(argv[++i]);
      else if (arg == "--prior-mapped" && i + 1 < argc) options.prior_weight_mapped = std::atof(argv[++i]);
      else if (arg == "--prior-unmapped" && i + 1 < argc) options.prior_weight_unmapped = std::atof(argv[++i]);
      else path = arg;
    }
    const Motion clip = readBvh(path);
    std::printf("clip %s: %d frames at %.0f fps, %d joints; %s solver, window %d overlap %d, %d iterations max, "
                "chunks of %d frames (lead-in %d), %d threads\n",
                path.c_str(), clip.frameCount(), clip.fps(), clip.skeleton.jointCount(),
                options.solver == CleanupSolver::Ceres ? "Ceres" : "kinematic tree", options.window_frames,
                options.window_overlap, options.max_iterations, options.chunk_frames, options.chunk_lead_in,
                options.threads);
    const Eigen::Vector3d up = makeScenario(clip).up;
    for (int frames : sizes) {
      const Scenario s = makeScenario(loopClip(clip, frames, up));
      const Eigen::MatrixXd clean = test::canonicalPositions(s.world, s.mapping);
      const Eigen::MatrixXd damaged = test::damageTargets(clean, s.contacts, s.clip.fps(), s.cm_per_unit, s.up, {});
      runOnce(s, clean, options, "clean");
      runOnce(s, damaged, options, "damaged");
    }
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_ik: %s\n", error.what());
    return 1;
  }
}
