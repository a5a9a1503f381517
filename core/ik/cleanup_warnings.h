#pragma once
// Private to core/ik: the clean-up report's residual figures and warnings (unreachable targets,
// joints left far from their targets), computed from the result's world positions a block of frames
// at a time, so that a long clip is never held whole.

#include <Eigen/Core>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "features/feature_layout.h"
#include "ik/cleanup.h"
#include "motion/kinematics.h"

namespace motionstyle::ik_detail {

// Runs of consecutive frames where a value exceeds a threshold, reported as
// "<prefix> <verb> X cm at frames a-b<suffix>" with each run's largest value; after kMaxRunsPerWarning runs the
// rest are counted ("<prefix>: N more such frame ranges"). Fed one frame at a time, in order.
// frame_scale r names a run of frames a..b by floor(a r) .. ceil((b + 1) r) - 1 (CleanupOptions::
// warning_fps: r = the named rate / the fed frames' rate; 1 names the fed frames).
class RunReporter {
 public:
  // `contact`: the CleanupWarning::contact each run's warning carries (-1: none).
  RunReporter(double threshold, std::string prefix, std::string verb, double frame_scale = 1.0, std::string suffix = {},
              int contact = -1)
      : threshold_(threshold), prefix_(std::move(prefix)), verb_(std::move(verb)), suffix_(std::move(suffix)),
        frame_scale_(frame_scale), contact_(contact) {}
  void add(int frame, double value);
  void finish(std::vector<CleanupWarning>& warnings);  // closes an open run, appends the messages

 private:
  void closeRun();
  double threshold_;
  std::string prefix_, verb_, suffix_;
  double frame_scale_;
  int contact_;
  int run_first_ = -1, run_last_ = -1;
  double run_peak_ = 0.0;
  int runs_ = 0;
  std::vector<CleanupWarning> messages_;
};

// The report's residual figures and warnings, fed the cleaned clip block by block in frame order. The
// warnings, in this order (what the user can act on first; a panel shows the first few): limbs whose
// targets lie beyond reach; heels and toes that their locked contact holds more than
// CleanupOptions::held_down_warning_cm under their targets,
//   held(f) = up . (target(f) - cleaned(f)) in cm, on the frames whose contact is locked (full weight),
// where the style lifts a foot the contact track holds down (ending the contact there follows the
// style); then joints far from their targets.
class CleanupWarnings {
 public:
  CleanupWarnings(const CleanupInput& input, const CleanupOptions& options);
  // Frames first .. first + result_world.rows() - 1: their content local poses (bone lengths) and the
  // cleaned world positions of every joint (file units).
  void add(int first, const LocalPoses& content_block, const Eigen::MatrixXd& result_world);
  // Fills report.mean/max_position_residual_cm and appends warnings such as
  // "targets unreachable: left arm stretched by 12.0 cm at frames 40-60".
  void finish(CleanupReport& report);

 private:
  const CleanupInput& input_;
  std::vector<RunReporter> limb_stretch_;                  // one per limb
  std::vector<RunReporter> joint_residual_;                // one per canonical joint
  std::vector<RunReporter> held_down_;                     // one per contact label; empty: nothing locked
  double residual_sum_ = 0.0, residual_peak_ = 0.0;
  long long residual_samples_ = 0;
};

// "12.3" (fixed, `decimals` digits).
std::string formatFixed(double value, int decimals);

}  // namespace motionstyle::ik_detail
