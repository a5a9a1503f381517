#pragma once
// The last step of stylize / transfer: the stylized canonical joint positions become a clean clip on
// the content's OWN skeleton through the IK clean-up (ik/cleanup.h), with the quality metrics
// before (raw network output) and after (the cleaned clip).
//
// Rates: the stylized clip is at the representation's 60 fps. The solve runs at the content's own rate
// when that is lower (a 30 fps clip: its own frames, the targets taken at its times; half the work of
// a 60 fps solve whose every other frame the export drops), else at 60 fps with the content resampled
// to it (its rotations warm-start and prior each frame). The cleaned clip is then resampled to
// `output_fps` (default: the content's own rate) for export. The raw output's metrics are at 60 fps,
// the cleaned clip's at the solve's rate; all in cm. The clean-up's warnings name the frames of the
// clip that comes out (output_fps, else the content's; CleanupOptions::warning_fps unless set).

#include "ik/cleanup.h"
#include "ik/metrics.h"
#include "mapping/joint_mapping.h"
#include "motion/motion.h"
#include "style/stylizer.h"

namespace motionstyle::style {

struct StylizedCleanup {
  Motion motion;          // content's skeleton, hierarchy, names, offsets and channel layout; output rate
  CleanupReport report;
  ClipMetrics raw;        // the network's output (21 canonical joints) judged by the CONTENT's contacts
  // The cleaned clip's canonical joints, bones of the whole skeleton; its skate over the contact tracks
  // the user sees (the content's, under the overrides), not over the locks: a stance left unlocked (the
  // style moved the step) and sliding counts; a joint the clean-up lifts off the floor with the style
  // (CleanupReport::lifted_contacts) does not, there.
  ClipMetrics cleaned;
  Eigen::MatrixXi contacts;  // frames x 4 at `fps`: the labels the clean-up locked (see the .cpp)
  double fps = 0.0;          // the solve's rate: of `contacts` and of the `cleaned` metrics' tracks
};

// content: the user's clip at its own rate (the one whose features were stylized); mapping: its
// canonical joints. Its leading rest-pose frames (stylized.anchor.rest_pose_frames: a CMU T-pose frame
// 0) are solved as the motion continued backward and come out as they went in (rest_pose_frames.h). output_fps <= 0 keeps the content's rate, and then the frame count too (frames
// past the last solved one hold its pose). contact_overrides: the user's per-frame overrides at the
// content's rate (frames x 4, -1 automatic / 0 off / 1 on; ik/contacts.h), or empty; they win over
// the labels the locks would use. control: the clean-up's cancel flag and memory (ik/cleanup.h). Throws std::invalid_argument when the stylized clip does not belong
// to the content (frame counts disagree after resampling) or the overrides have the wrong shape.
StylizedCleanup cleanUpStylizedClip(const Motion& content, const JointMapping& mapping, const StylizedClip& stylized,
                                    const CleanupOptions& options = {}, double output_fps = 0.0,
                                    const Eigen::MatrixXi& contact_overrides = {}, const CleanupControl& control = {});

// The floor height along the file's up axis, in file units, of a clip whose features have this anchor.
double fileFloorHeight(const FeatureAnchor& anchor);

}  // namespace motionstyle::style
