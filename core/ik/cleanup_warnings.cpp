#include "ik/cleanup_warnings.h"

#include <algorithm>
#include <cstdio>
#include <vector>

#include "mapping/canonical_joints.h"

namespace motionstyle::ik_detail {
namespace {

constexpr size_t kMaxRunsPerWarning = 5;  // more runs are summarised as "and N more"

struct Limb {
  const char* name;
  CanonicalJoint base;
  CanonicalJoint end;
};
constexpr std::array<Limb, 4> kLimbs = {{
    {"left arm", CanonicalJoint::LeftUpperArm, CanonicalJoint::LeftWrist},
    {"right arm", CanonicalJoint::RightUpperArm, CanonicalJoint::RightWrist},
    {"left leg", CanonicalJoint::LeftHip, CanonicalJoint::LeftAnkle},
    {"right leg", CanonicalJoint::RightHip, CanonicalJoint::RightAnkle},
}};

Eigen::Vector3d at(const Eigen::MatrixXd& positions, int frame, int joint) {
  return positions.block<1, 3>(frame, 3 * joint).transpose();
}

// Longest possible distance from `base` to its descendant `end` at `frame`: the sum of the bone
// lengths on the path (exact when every joint on it rotates freely; an upper bound otherwise, so the
// warning never fires for a reachable pose). File units.
double reach(const Skeleton& skeleton, const LocalPoses& poses, int frame, int base, int end) {
  double length = 0.0;
  for (int j = end; j >= 0 && j != base; j = skeleton.joints[static_cast<size_t>(j)].parent)
    length += poses.translation(frame, j).norm();
  return length;
}

// Runs of consecutive frames where value(frame) > threshold, reported as "... by X cm at frames a-b"
// with the run's largest value.
void reportRuns(const std::vector<double>& value, double threshold, const std::string& prefix,
                const std::string& verb, std::vector<std::string>& warnings) {
  size_t runs = 0;
  const auto frames = static_cast<int>(value.size());
  for (int f = 0; f < frames;) {
    if (!(value[static_cast<size_t>(f)] > threshold)) {
      ++f;
      continue;
    }
    int last = f;
    double peak = value[static_cast<size_t>(f)];
    while (last + 1 < frames && value[static_cast<size_t>(last + 1)] > threshold) peak = std::max(peak, value[static_cast<size_t>(++last)]);
    if (runs < kMaxRunsPerWarning) {
      const std::string span = last > f ? "frames " + std::to_string(f) + "-" + std::to_string(last)
                                        : "frame " + std::to_string(f);
      warnings.push_back(prefix + " " + verb + " " + formatFixed(peak, 1) + " cm at " + span);
    }
    ++runs;
    f = last + 1;
  }
  if (runs > kMaxRunsPerWarning)
    warnings.push_back(prefix + ": " + std::to_string(runs - kMaxRunsPerWarning) + " more such frame ranges");
}

}  // namespace

std::string formatFixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

void addCleanupWarnings(const CleanupInput& input, const CleanupOptions& options, const LocalPoses& content_poses,
                        const Eigen::MatrixXd& result_world, CleanupReport& report) {
  const int frames = static_cast<int>(input.targets.rows());
  const double cm = input.cm_per_unit;

  // Residual of every mapped joint, cm.
  std::vector<std::vector<double>> residual(kCanonicalJointCount, std::vector<double>(static_cast<size_t>(frames)));
  double sum = 0.0, peak = 0.0;
  for (int c = 0; c < kCanonicalJointCount; ++c) {
    for (int f = 0; f < frames; ++f) {
      const Eigen::Vector3d target = input.targets.block<1, 3>(f, 3 * c).transpose();
      const double error = (at(result_world, f, input.mapping.joints[static_cast<size_t>(c)]) - target).norm() * cm;
      residual[static_cast<size_t>(c)][static_cast<size_t>(f)] = error;
      sum += error;
      peak = std::max(peak, error);
    }
  }
  report.mean_position_residual_cm = sum / (static_cast<double>(frames) * kCanonicalJointCount);
  report.max_position_residual_cm = peak;

  // Limbs whose targets lie further apart than the limb can reach.
  for (const Limb& limb : kLimbs) {
    const int base = input.mapping[limb.base];
    const int end = input.mapping[limb.end];
    std::vector<double> stretch(static_cast<size_t>(frames));
    for (int f = 0; f < frames; ++f) {
      const double distance = (input.targets.block<1, 3>(f, 3 * index(limb.end)) -
                               input.targets.block<1, 3>(f, 3 * index(limb.base))).norm();
      stretch[static_cast<size_t>(f)] = (distance - reach(input.content.skeleton, content_poses, f, base, end)) * cm;
    }
    reportRuns(stretch, options.unreachable_warning_cm, std::string("targets unreachable: ") + limb.name,
               "stretched by", report.warnings);
  }

  // Joints left far from their targets (whatever the reason: stretch, a contact lock, the floor).
  for (int c = 0; c < kCanonicalJointCount; ++c)
    reportRuns(residual[static_cast<size_t>(c)], options.residual_warning_cm,
               "large residual: " + std::string(canonicalJointName(static_cast<CanonicalJoint>(c))), "off target by",
               report.warnings);
}

}  // namespace motionstyle::ik_detail
