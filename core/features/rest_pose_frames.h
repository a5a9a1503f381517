#pragma once
// A clip that opens with its rig's rest pose before the motion, as every BVH file of CMU's
// "cmuconvert" release does (frame 0 a T-pose at frame 1's root position). That frame is not motion:
// read as motion it is a jump of every limb and up to a half turn in one frame, which broke the
// features, the path and the clean-up of such files (docs/decisions.md, "Files that open with their
// rig's rest pose").
//
// The contract: the features (and so the networks, familiarity, training and the clean-up's targets)
// see the clip with its leading rest-pose frames REPLACED by the motion continued backward; the
// clean-up solves that clip and writes the content's own rest-pose frames back into its output (a
// pipeline keeps them for retargeting). Every frame keeps its time, so per-frame tracks and the user's
// contact edits stay on the clip's frames.
//
// Detection, scale-free: with p_t the 21 canonical joints relative to the hips at frame t and h the
// skeletal height (space_convention.h), the step s_t = mean_j |p_{t+1,j} - p_{t,j}| / h. Frame 0 is a
// rest-pose frame when s_0 > kRestPoseJump and s_0 > kRestPoseJumpRatio x the median of s_1..s_m over
// the next half second: a pose change no captured motion makes in one frame (thresholds measured on
// CMU and Bandai clips, with their margins, in docs/decisions.md).

#include "mapping/joint_mapping.h"
#include "motion/motion.h"

namespace motionstyle {

constexpr double kRestPoseJump = 0.05;      // of the skeletal height (about 6 cm for an adult)
constexpr double kRestPoseJumpRatio = 6.0;  // times the median step over the next half second

// The number of leading frames that are a rest pose and not motion: 0 or 1. A clip of fewer than 3
// frames has none. The mapping must index the motion's skeleton.
int leadingRestPoseFrames(const Motion& motion, const JointMapping& mapping);

// Replaces `motion`'s frames [0, rest_pose_frames) in place by the motion continued backward from
// frame rest_pose_frames at its first step: x_f = 2 x_{f+1} - x_{f+2} per channel, angles by their
// step wrapped into [-180, 180]. Why not a copy of the first frame: a held frame reads as feet at rest
// to contact detection. rest_pose_frames 0 changes nothing; otherwise the clip needs two frames after
// them (std::invalid_argument).
void replaceRestPoseFrames(Motion& motion, int rest_pose_frames);

// Puts the content's rest-pose frames back into `output`, a clip on the content's skeleton (the same
// channel layout) at any rate: every output frame whose nearest content frame (by time) is a rest-pose
// frame takes that frame's values. std::invalid_argument when the channel counts differ.
void restoreRestPoseFrames(Motion& output, const Motion& content, int rest_pose_frames);

}  // namespace motionstyle
