#pragma once
// A clip that opens with its rig's rest pose before the motion: every BVH file of CMU's "cmuconvert"
// release (the most used free motion capture) has frame 0 a T-pose at the first frame's root position,
// facing wherever the rig's rest faces, then the capture from frame 1. That frame is not motion: the
// features would read a jump of arms and legs and, where the capture faces elsewhere, a turn of up to
// 180 degrees in one frame (CMU 127_07 as published: path 14 % long, its end 25 % of the distance off,
// joints 105 cm off their targets after the clean-up). Pipelines keep it for retargeting, so it stays
// in every file MotionStyle writes.
//
// The contract: the features (and so the networks, familiarity, training and the clean-up's targets)
// see the clip with its leading rest-pose frames REPLACED by the motion continued backward; the
// clean-up solves that clip and puts the content's own rest-pose frames back into its output. Every
// frame keeps its time, so the app's tracks and the user's contact edits stay on the clip's frames.
//
// Detection, scale-free: with p_t the 21 canonical joints relative to the hips at frame t and h the
// skeletal height (space_convention.h), the step s_t = mean_j |p_{t+1,j} - p_{t,j}| / h. Frame 0 is a
// rest-pose frame when s_0 > kRestPoseJump and s_0 > kRestPoseJumpRatio x the median of s_1..s_m over
// the next half second: a pose change no captured motion makes in one frame. Measured: the T-pose
// frames of the five CMU walks and runs 0.20-0.35 and 26-40x their clip's median step at 120 fps (07_01
// at 30 / 24 fps: 10.1x / 8.6x; at 15 fps 4.9x, not found), the zero-rotation pose put before the
// committed 131_01 (another conversion, standing closer to it) 0.088 and 65x; the 1,357 Bandai clips at
// most 0.064 (a dash, 1.3x; none over 0.035 with more than 1.7x) and 5.4x (a hand raised from rest,
// 0.028); the samples (CMU 131_01 trimmed, the zombie) at most 0.004 and 2x.

#include "mapping/joint_mapping.h"
#include "motion/motion.h"

namespace motionstyle {

constexpr double kRestPoseJump = 0.05;      // of the skeletal height (about 6 cm for an adult)
constexpr double kRestPoseJumpRatio = 6.0;  // times the median step over the next half second

// The number of leading frames that are a rest pose and not motion: 0 or 1. A clip of fewer than 3
// frames has none. The mapping must index the motion's skeleton.
int leadingRestPoseFrames(const Motion& motion, const JointMapping& mapping);

// Replaces `motion`'s frames [0, rest_pose_frames) in place by the motion continued the motion backward from frame
// rest_pose_frames at its first step (x_f = 2 x_{f+1} - x_{f+2} per channel, angles by their step
// wrapped into [-180, 180)). Why not a copy of the first frame: a held frame reads as a foot at rest,
// and the clean-up then locked feet over the motion's first frames (a knee 6-8 cm off its target on
// CMU 09_01 and 127_07). rest_pose_frames 0 changes nothing; otherwise the clip needs two frames
// after them (std::invalid_argument).
void replaceRestPoseFrames(Motion& motion, int rest_pose_frames);

// Puts the content's rest-pose frames back into `output`, a clip on the content's skeleton (the same
// channel layout) at any rate: every output frame whose nearest content frame (by time) is a rest-pose
// frame takes that frame's values. std::invalid_argument when the channel counts differ.
void restoreRestPoseFrames(Motion& output, const Motion& content, int rest_pose_frames);

}  // namespace motionstyle
