#pragma once
// A positions-only clip of the 21 canonical joints: the raw stylize/transfer output as a BVH file
// (--no-cleanup, --raw), before the IK clean-up (core/ik/cleanup.h) puts it on the content's skeleton.
//
// Skeleton: the canonical tree (kCanonicalParent), joints named as canonicalJointName(), EVERY joint
// with three position channels (Xposition Yposition Zposition) and no rotation channels. A BVH position
// channel replaces the joint's offset, so a joint's world position is its parent's plus its channel
// values: the file reproduces the target world positions exactly (up to the writer's decimal output),
// in the content's file units and axes. Offsets are the first frame's, so the rest pose is that frame.
// Blender, Maya and MotionBuilder import translation channels on any joint; bones are drawn between
// joints but carry no rotation.

#include <Eigen/Core>
#include <string>

#include "motion/motion.h"

namespace motionstyle::style {

// world_positions: frames x 63 (canonical feature order, file space), frames >= 1, finite; fps > 0.
// Throws std::invalid_argument otherwise.
Motion canonicalPositionsMotion(const Eigen::MatrixXd& world_positions, double fps, const std::string& source);

}  // namespace motionstyle::style
