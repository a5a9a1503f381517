#pragma once
// StylizeCleanupJob: a content clip through a style network (or an already stylized clip, the
// optimisation method's output) and the IK clean-up onto the content's own skeleton, with the quality
// metrics before and after: what the app's Result panel, motionstyle-filmstrip and motionstyle-cli's
// stylize and transfer write (cleanUpStylizedClip's chain, stylized_cleanup.h).
//
// The job shape of every long operation (ozz-animation's jobs): plain inputs copied in, validate(),
// run() with a cancel flag, a typed Result apart from the inputs.

#include <Eigen/Core>

#include <atomic>
#include <memory>
#include <optional>
#include <string>

#include "ik/cleanup.h"
#include "features/representation.h"
#include "ik/metrics.h"
#include "mapping/joint_mapping.h"
#include "motion/motion.h"
#include "style/path_mode.h"
#include "style/stylizer.h"

namespace motionstyle::style {

struct StylizeCleanupResult {
  StylizedClip stylized;         // raw network output: 21 canonical joints, file space, 60 fps
  Motion cleaned;                // on the content's skeleton, at the content's rate and frame count
                                 // (or at output_fps)
  // frames x 3*joints: worldPositions(cleaned), every joint, file units and axes, when the job was asked
  // for them (StylizeCleanupJob::world_positions), else empty. Computed on the job's thread, so that a
  // viewer draws the cleaned clip without forward kinematics on its own (the app's GUI thread spent
  // 65-220 ms of each result of a 36,000-frame clip on it).
  Eigen::MatrixXd cleaned_world_positions;
  CleanupReport report;
  ClipMetrics raw_metrics;       // the raw output, judged by the content's contacts (60 fps)
  ClipMetrics cleaned_metrics;   // the cleaned clip; its skate over the contact tracks shown (stylized_cleanup.h)
  Eigen::MatrixXi contacts;      // frames x 4 at cleanup_fps: the labels the clean-up locked
  double cleanup_fps = 0.0;      // the clean-up's rate (stylized_cleanup.h): of contacts and cleaned_metrics
  double seconds = 0.0;          // wall clock of the whole job
  bool network_output_kept = false;  // the memory's network output served: the network did not run
};

// What a job keeps for the next one on the same content, so that a live edit redoes only what it
// changed: the content's features (for a content and mapping equal bit for bit to the last job's), the
// network's output for them (the strength does not change it: stylizer.h, networkOutput) and the
// clean-up's memory (ik/cleanup.h). A job reuses the network output only for the same network, path
// mode (the contacts are planted under its root path), kind aimed at and features equal bit for bit;
// anything else is computed and kept instead. Results never depend on it. One job at a time per memory.
struct StylizeCleanupMemory {
  CleanupMemory cleanup;
  Motion content;  // the clip and mapping content_features were extracted from
  JointMapping mapping;
  std::optional<MotionFeatures> content_features;
  std::shared_ptr<const Stylizer> stylizer;  // whose output network_output is
  Eigen::MatrixXd features;                  // the content's features it was computed from
  PathMode path = PathMode::Content;         // and the path its contacts were planted under
  std::string kind;                          // and the job's kind to aim at
  Eigen::MatrixXd network_output;

  // Starts from `other`'s clip, features and clean-up solutions (another network's memory on the same
  // clip), without its network output: a job on another network is as warm as one on `other` and
  // leaves `other` as it was.
  void seedFrom(const StylizeCleanupMemory& other);
  // seedFrom(other) and other's network output too (the same network on the same clip): a job then
  // runs only the clean-up, from other's solutions, and `other` stays as it was. Only while no job
  // writes `other` (it is read here, on the caller's thread).
  void copyFrom(const StylizeCleanupMemory& other);
};

struct StylizeCleanupJob {
  Motion content;        // the user's clip at its own rate, file space
  JointMapping mapping;  // its canonical joints
  // Either a network (stylizer + strength in [0, 1]) or an already stylized clip for the same content.
  std::shared_ptr<const Stylizer> stylizer;
  double strength = 1.0;
  PathMode path = PathMode::Content;  // whose root path the output follows
  // The locomotion kind whose style clip the refinement aims at (locomotion_kind.h): "" read from the
  // clip, else one of kLocomotionKinds: the user's choice for a clip the reading gets wrong (a shuffling
  // run read as a walk).
  std::string kind;
  std::optional<StylizedClip> stylized;
  // User contact overrides at the CONTENT's rate (frames x 4, -1 auto / 0 off / 1 on); empty: none.
  Eigen::MatrixXi contact_overrides;
  CleanupOptions options;
  double output_fps = 0.0;  // the cleaned clip's rate (resampled): 0 = the content's own
  bool world_positions = false;  // also give the cleaned clip's world positions (for a viewer)
  // The previous job on this clip: after a small edit only what changed is computed again (the
  // network not at all for a strength change, the clean-up only where its inputs moved, from
  // the last solution). Null: compute everything.
  std::shared_ptr<StylizeCleanupMemory> memory;
  // When `memory` has nothing yet (new), it is first seeded from this one (StylizeCleanupMemory::
  // seedFrom): the app keeps each style's memory apart and starts a new style's from the last one's.
  // Read on the job's thread; no other job may use it meanwhile.
  std::shared_ptr<const StylizeCleanupMemory> seed;

  // std::invalid_argument: neither a network nor a stylized clip, a strength outside [0, 1], overrides
  // whose shape is not content frames x 4, a kind neither "" nor one of kLocomotionKinds.
  void validate() const;

  // Validates, stylizes (unless `stylized` is given) and cleans up. Throws InputError (an unmappable or
  // too short clip), std::invalid_argument (a stylized clip that does not belong to the content) and
  // OperationCancelled when `cancel` is seen (between steps, and before every frame of the clean-up).
  StylizeCleanupResult run(const std::atomic<bool>* cancel = nullptr) const;
};

}  // namespace motionstyle::style
