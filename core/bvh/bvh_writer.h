#pragma once
// BVH writer: Motion -> standard BVH text that Blender, Maya and MotionBuilder import.
//
// Layout: tab indentation, "HIERARCHY", ROOT/JOINT/"End Site" blocks with "OFFSET x y z" and
// "CHANNELS n ...", then "MOTION", "Frames: N", "Frame Time: t" and one line of values per frame, LF
// line endings. Values are written exactly as stored (file units, rotations in degrees).
//
// Numbers: the shortest decimal that reads back to the very same double (std::to_chars, fixed
// notation). So read -> write -> read is exact, not merely within 1e-4; values read from a file are
// written as they were typed (".0083333" stays 0.0083333, 1/120 becomes 0.008333333333333333); and
// there is no exponent notation, which some importers mishandle. A fixed "%.6f" would lose 1e-7
// values and print noise digits for every other value; "%.6g" loses large values.
//
// Joint order: the hierarchy is written depth-first (children in index order), with each frame's
// values permuted to match, so any Skeleton that validates can be written; a skeleton read from a file
// is already in that order and round-trips unchanged. End Site names are not part of BVH: they are
// written as "End Site" and the reader regenerates "<parent>_End".

#include <filesystem>
#include <string>

#include "motion/motion.h"

namespace motionstyle {

// The BVH text of `motion`. Throws std::invalid_argument (a programming error, not bad user data) if
// motion.validate() fails or the motion cannot be expressed as BVH the reader accepts: a joint other
// than an End Site without 3 or 6 channels (three rotations and/or three positions), or a joint name
// that is blank at either end or contains braces or control characters.
std::string formatBvh(const Motion& motion);

// formatBvh written atomically (writeFileAtomically): on any failure `file` is left as it was.
// Throws std::invalid_argument as formatBvh (before touching the disk) and WriteError on I/O failure.
void writeBvh(const Motion& motion, const std::filesystem::path& file);

}  // namespace motionstyle
