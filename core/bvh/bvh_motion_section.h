#pragma once
// MOTION section of a BVH file (internal to core/bvh): "MOTION", "Frames: N", "Frame Time: t" and the
// frame lines.

#include <string>

#include "bvh/bvh_line_cursor.h"
#include "motion/motion.h"

namespace motionstyle::bvh_detail {

// Reads from `cursor` (just after the hierarchy) to the end of the text and fills motion.frame_time
// (seconds) and motion.values (frames x motion.skeleton.channelCount(), file units and degrees).
// The skeleton must already be set. Throws InputError naming `source` and the line, also when
// "Frames:" states fewer than `minimum_frames` (the caller needs motion, the file holds less).
void parseMotionSection(LineCursor& cursor, const std::string& source, int minimum_frames, Motion& motion);

}  // namespace motionstyle::bvh_detail
