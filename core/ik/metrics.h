#pragma once
// Quality metrics of a clip, one module for the CLI (--metrics FILE.json), the GUI's quality track and
// the tests. All figures are in centimetres and seconds (cm, cm/s, cm/s^3) via cm_per_unit and fps, so
// they compare across rigs and frame rates.
//
// Inputs are world positions in the clip's own space (file units and axes) of either
//   - every joint of a skeleton (worldPositions(motion)), with `canonical_joints` = the mapping, or
//   - just the 21 canonical joints (frames x 63, e.g. raw network output converted to file space),
//     with `canonical_joints` = identityCanonicalJoints().
//
// Definitions:
//   foot skate        mean horizontal speed (cm/s) of each foot over the steps t -> t+1 where one of its
//                     contact joints (heel, toe) is labelled in contact at both t and t+1, the foot's
//                     speed there being the slower of those joints' (0 when there is no such step).
//                     Why per foot: a foot turning about a joint that holds still (a heel rolling up on
//                     its planted toe) does not slide; a foot whose every contact moves does;
//   floor penetration depth below the floor (cm) of the four contact joints, max over all frames and
//                     mean over the samples that are below it;
//   bone error        | |p_joint - p_parent| - reference length | (cm), mean and max over bones and frames;
//   position residual |p_canonical - target| (cm) over the 21 canonical joints, mean and max (and where);
//   jerk              mean |p(t+3) - 3 p(t+2) + 3 p(t+1) - p(t)| * fps^3 (cm/s^3) over canonical joints.

#include <Eigen/Core>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "features/feature_layout.h"
#include "mapping/joint_mapping.h"
#include "motion/motion.h"

namespace motionstyle {

// One bone: joint indices into the positions' joints, reference length in file units.
struct BoneReference {
  int joint = 0;
  int parent = 0;
  double length = 0.0;
};

// Every bone of a full skeleton (non-root joints, End Sites included) whose length is fixed by its
// OFFSET, i.e. joints without position channels; indices are skeleton joint indices.
std::vector<BoneReference> skeletonBones(const Skeleton& skeleton);

// The 20 canonical bones (joint c, its canonical parent) of a content clip, for positions that hold
// only the canonical joints (frames x 63): each length is the median over the content's frames of the
// distance between the two mapped joints (chains through extra joints, e.g. the spine, may bend
// slightly). content_world: frames x 3J world positions of the content clip, file units.
std::vector<BoneReference> canonicalBones(const Eigen::MatrixXd& content_world, const JointMapping& mapping);

std::array<int, kCanonicalJointCount> identityCanonicalJoints();

struct MetricsInput {
  MetricsInput(const Eigen::MatrixXd& positions_, const std::array<int, kCanonicalJointCount>& canonical_joints_,
               std::vector<BoneReference> bones_ = {})
      : positions(positions_), canonical_joints(canonical_joints_), bones(std::move(bones_)) {}

  const Eigen::MatrixXd& positions;  // frames x 3J world positions, file units
  std::array<int, kCanonicalJointCount> canonical_joints{};  // joint index in `positions` per canonical joint
  std::vector<BoneReference> bones;  // may be empty: no bone figures
  Eigen::MatrixXi contacts;          // frames x 4 (ContactLabel order), 0/1; empty: no skate figure
  Eigen::MatrixXd targets;           // frames x 63 canonical targets, file units; empty: no residual
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  double floor_height = 0.0;         // file units along up
  double cm_per_unit = 1.0;
  double fps = 60.0;

  // Throws std::invalid_argument on a column count that is not 3 x joints, an index out of range,
  // contacts or targets whose frame count differs or whose values are bad, a non-unit up, or a
  // non-positive cm_per_unit or fps.
  void validate() const;
};

struct ClipMetrics {
  int frames = 0;
  double foot_skate_cm_s = 0.0;
  int contact_steps = 0;                 // (foot, t -> t+1) pairs the skate figure averages
  double penetration_max_cm = 0.0;
  double penetration_mean_cm = 0.0;      // over penetrating samples; 0 when none
  int penetrating_samples = 0;
  double bone_error_mean_cm = 0.0;
  double bone_error_max_cm = 0.0;
  bool has_residual = false;
  double residual_mean_cm = 0.0;
  double residual_max_cm = 0.0;
  // Where residual_max_cm is (the first such frame): so that a front end can show it. -1: no residual.
  int residual_max_frame = -1;
  int residual_max_joint = -1;  // canonical joint index (CanonicalJoint order)
  double jerk_mean_cm_s3 = 0.0;
  // Per-frame tracks for the GUI (length `frames`): the mean skate of the feet in contact over the
  // step from this frame to the next (cm/s, 0 when none), and the largest bone error (cm).
  std::vector<double> skate_track_cm_s;
  std::vector<double> bone_error_track_cm;
};

ClipMetrics computeMetrics(const MetricsInput& input);

// computeMetrics a block of frames at a time, for clips too long to hold whole: add() consecutive
// blocks in frame order (each a MetricsInput holding only its frames, with the same joints, bones,
// up, floor, unit, rate, and contacts/targets present in every block or in none), then finish().
// The figures are exactly computeMetrics' over the concatenated blocks (same sums in the same order):
// steps and jerk windows that straddle two blocks use the last frames kept from the previous block.
// Memory: the last 3 frames plus, when keep_tracks, 16 bytes per frame for the two tracks.
class MetricsAccumulator {
 public:
  explicit MetricsAccumulator(bool keep_tracks = true) : keep_tracks_(keep_tracks) {}
  // std::invalid_argument as MetricsInput::validate, or when a block's settings differ from the first's.
  void add(const MetricsInput& block);
  ClipMetrics finish() const;

 private:
  bool keep_tracks_;
  bool started_ = false;
  std::array<int, kCanonicalJointCount> canonical_joints_{};
  std::vector<BoneReference> bones_;
  Eigen::Vector3d up_ = Eigen::Vector3d::UnitY();
  double floor_height_ = 0.0, cm_per_unit_ = 1.0, fps_ = 60.0;
  Eigen::Index columns_ = 0;
  bool has_contacts_ = false, has_targets_ = false;
  Eigen::MatrixXd history_;           // the last (up to 3) frames' positions
  Eigen::RowVectorXi last_contacts_;  // the last frame's contact labels
  ClipMetrics partial_;               // counts, maxima and tracks so far
  double skate_sum_ = 0.0, depth_sum_ = 0.0, bone_sum_ = 0.0, residual_sum_ = 0.0, jerk_sum_ = 0.0;
};

// {"frames": ..., "foot_skate_cm_s": ..., ...}; `include_tracks` adds the per-frame tracks.
std::string metricsToJson(const ClipMetrics& metrics, bool include_tracks = false);

}  // namespace motionstyle
