#include "ik/cleanup_warnings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
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

}  // namespace

std::string formatFixed(double value, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, value);
  return buffer;
}

void RunReporter::add(int frame, double value) {
  if (!(value > threshold_)) {
    closeRun();
    return;
  }
  if (run_first_ < 0) {
    run_first_ = frame;
    run_peak_ = value;
  }
  run_last_ = frame;
  run_peak_ = std::max(run_peak_, value);
}

void RunReporter::closeRun() {
  if (run_first_ < 0) return;
  if (static_cast<size_t>(runs_) < kMaxRunsPerWarning) {
    // The named frames overlapping the run in time (1e-9: 2 x 67 stays 134 whatever the rounding).
    const int first = frameAtRate(run_first_, frame_scale_);
    const int last = std::max(first, static_cast<int>(std::ceil((run_last_ + 1) * frame_scale_ - 1e-9)) - 1);
    const std::string span = last > first ? "frames " + std::to_string(first) + "-" + std::to_string(last)
                                          : "frame " + std::to_string(first);
    messages_.push_back(
        {prefix_ + " " + verb_ + " " + formatFixed(run_peak_, 1) + " cm at " + span + suffix_, first, last, contact_});
  }
  ++runs_;
  run_first_ = run_last_ = -1;
}

void RunReporter::finish(std::vector<CleanupWarning>& warnings) {
  closeRun();
  warnings.insert(warnings.end(), messages_.begin(), messages_.end());
  if (static_cast<size_t>(runs_) > kMaxRunsPerWarning)
    warnings.push_back({prefix_ + ": " + std::to_string(runs_ - static_cast<int>(kMaxRunsPerWarning)) +
                        " more such frame ranges"});
}

CleanupWarnings::CleanupWarnings(const CleanupInput& input, const CleanupOptions& options) : input_(input) {
  const double frame_scale = options.warning_fps > 0.0 ? options.warning_fps * input.content.frame_time : 1.0;
  for (const Limb& limb : kLimbs)
    limb_stretch_.emplace_back(options.unreachable_warning_cm, std::string("targets unreachable: ") + limb.name,
                               "stretched by", frame_scale);
  for (int c = 0; c < kCanonicalJointCount; ++c)
    joint_residual_.emplace_back(options.residual_warning_cm,
                                 "large residual: " + std::string(canonicalJointName(static_cast<CanonicalJoint>(c))),
                                 "off target by", frame_scale);
  if (options.lock_contacts)
    for (int label = 0; label < kContactCount; ++label)
      held_down_.emplace_back(options.held_down_warning_cm,
                              "held down by its contact: " + std::string(contactLabelName(label)),
                              "under the style's lift by", frame_scale, " (end the contact there to follow the style)",
                              label);
}

void CleanupWarnings::add(int first, const LocalPoses& content_block, const Eigen::MatrixXd& result_world) {
  const double cm = input_.cm_per_unit;
  for (int row = 0; row < static_cast<int>(result_world.rows()); ++row) {
    const int frame = first + row;
    // Residual of every mapped joint, cm.
    for (int c = 0; c < kCanonicalJointCount; ++c) {
      const Eigen::Vector3d target = input_.targets.block<1, 3>(frame, 3 * c).transpose();
      const double error = (at(result_world, row, input_.mapping.joints[static_cast<size_t>(c)]) - target).norm() * cm;
      residual_sum_ += error;
      residual_peak_ = std::max(residual_peak_, error);
      joint_residual_[static_cast<size_t>(c)].add(frame, error);
    }
    ++residual_samples_;
    // A locked heel or toe held under its target (the style lifts it; its contact holds it down).
    for (size_t label = 0; label < held_down_.size(); ++label) {
      const int c = index(kContactJoint[label]);
      const bool locked = input_.contacts(frame, static_cast<Eigen::Index>(label)) != 0;
      const Eigen::Vector3d target = input_.targets.block<1, 3>(frame, 3 * c).transpose();
      const double held = input_.up.dot(target - at(result_world, row, input_.mapping.joints[static_cast<size_t>(c)])) * cm;
      held_down_[label].add(frame, locked ? held : 0.0);
    }
    // Limbs whose targets lie further apart than the limb can reach.
    for (size_t l = 0; l < kLimbs.size(); ++l) {
      const Limb& limb = kLimbs[l];
      const double distance = (input_.targets.block<1, 3>(frame, 3 * index(limb.end)) -
                               input_.targets.block<1, 3>(frame, 3 * index(limb.base))).norm();
      const double limb_reach = reach(input_.content.skeleton, content_block, row, input_.mapping[limb.base],
                                      input_.mapping[limb.end]);
      limb_stretch_[l].add(frame, (distance - limb_reach) * cm);
    }
  }
}

void CleanupWarnings::finish(CleanupReport& report) {
  report.mean_position_residual_cm =
      residual_samples_ > 0 ? residual_sum_ / (static_cast<double>(residual_samples_) * kCanonicalJointCount) : 0.0;
  report.max_position_residual_cm = residual_peak_;
  // The order of the report's warnings: what the user can act on first (a front end shows the first
  // few): limbs beyond reach, contacts holding a foot under the style's lift (end them there), then
  // the joints off target, which a held foot pulls off too.
  for (RunReporter& limb : limb_stretch_) limb.finish(report.warnings);
  for (RunReporter& held : held_down_) held.finish(report.warnings);
  for (RunReporter& joint : joint_residual_) joint.finish(report.warnings);
}

}  // namespace motionstyle::ik_detail
