#pragma once
// BVH reader: text -> validated Motion (editable data, file units, rotations in degrees).
//
// Accepted (what real exporters write, Blender/Maya/MotionBuilder/CMU/Bandai alike):
// - One ROOT with any tree of JOINTs and End Sites. An End Site becomes a Joint with end_site = true,
//   no channels, named "<parent>_End" (suffixed "_End2", "_End3"... if that name is taken).
// - Every ROOT/JOINT has "CHANNELS 3" or "CHANNELS 6": three rotations, three positions, or both, in any
//   order (the order of the rotation channels is the Euler order). "CHANNELS 0" and partial sets such as
//   "CHANNELS 2 Xrotation Yrotation" are rejected: the issue lists a channel-less joint as bad input, and
//   kinematics, IK and the feature code all assume a joint rotates about all three axes or not at all.
// - Keywords and channel names in any letter case; tabs or spaces; LF, CRLF or both mixed; a UTF-8
//   BOM; numbers as "-0.5", ".0083333", "+1", "1.87e-05". Joint names are the rest of the line
//   (trimmed), so names with inner spaces survive.
// - "Frames: N" must match the frame lines exactly; each frame line has exactly channelCount() values;
//   blank lines are ignored; "Frames: 0" is a valid skeleton-only file (0 rows), unless the caller
//   asks for `minimum_frames` (commands that transform motion ask for 1: "the clip has no frames").
// Rejected with InputError(file, line, "expected ..., got ..."): everything else, including NaN/inf
// values, numbers beyond double range, duplicate joint names, the physical ranges and the caps below.
//
// Physical ranges (a value outside is no capture: refused on read, so no solver or resampler sees it):
// - Frame Time from kBvhMinFrameTime (1e-4 s, 10 kHz: beyond the fastest optical capture) to
//   kBvhMaxFrameTime (1 s, 1 fps): the representation resamples every clip to 60 fps and resampling is
//   capped at 100x, so a slower clip could not be used; denormals such as 5e-324 fall out too.
// - Every OFFSET and channel value within +-kBvhMaxMagnitude (1e6 file units or degrees): 10 km in cm,
//   1 km in mm, 2778 turns. Beyond, the clean-up's squared costs (1e12+) swamp centimetre precision and
//   the solver only reports failures.
//
// Resource caps (the parser never allocates more than the text justifies):
// - kBvhMaxBytes: texts over 1 GiB are refused (line numbers are int; a 1 GiB clip is ~2 h of mocap).
// - kBvhMaxJoints / kBvhMaxDepth: the hierarchy is parsed iteratively, but downstream code (FK, IK,
//   the viewport) walks chains, so absurd headers are refused early with the offending line.
// - The frame matrix is sized from min(claimed frames, what the remaining bytes could hold at 2 bytes
//   per value), so "Frames: 1000000000" on a small file allocates nothing big and fails on the data.
//   readBvh takes the remaining bytes from the file's size; for a pipe or a device (size unknown) the
//   matrix doubles as frames arrive, never beyond what the bytes read so far could hold.
// - readBvh reads the first 64 KiB, checks that its first non-blank line is HIERARCHY, then parses on,
//   refusing a NUL byte (with its line; an error on an earlier line is reported first): /dev/zero,
//   /dev/urandom or a binary file stop after one small read. A FIFO without a writer still blocks in
//   open(), as every reader of a named pipe does.
//
// Memory: readBvh never holds the whole text. It reads 1 MiB chunks and keeps only the current one
// plus the incomplete line carried to the next (a ~2 MiB buffer), so a clip costs its values (8 bytes
// per channel per frame) and a constant, not its text too (~0.7-1 KB more per frame for CMU's 96
// channels).
//
// Speed: the MOTION section is parsed in place with std::from_chars, no per-line allocation; see
// tests/bench/bvh for the measured throughput.

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "motion/motion.h"

namespace motionstyle {

inline constexpr std::size_t kBvhMaxBytes = std::size_t{1} << 30;
inline constexpr int kBvhMaxJoints = 10'000;  // End Sites included
inline constexpr int kBvhMaxDepth = 1'000;    // ROOT is depth 1
inline constexpr double kBvhMinFrameTime = 1e-4;  // seconds
inline constexpr double kBvhMaxFrameTime = 1.0;   // seconds
inline constexpr double kBvhMaxMagnitude = 1e6;   // file units (OFFSET, positions) or degrees

// Reads the file in chunks and parses it: the same Motion and errors as parseBvh of its text, plus
// the 64 KiB HIERARCHY check and the NUL refusal above. Throws InputError (line 0) if the file cannot
// be read, and InputError (file, line, detail) if its content is not a valid BVH or holds fewer than
// `minimum_frames` frames (named on the "Frames:" line).
Motion readBvh(const std::filesystem::path& file, int minimum_frames = 0);

// Parses BVH text already in memory. `source_name` is used in error messages and stored in
// Motion::source.
Motion parseBvh(std::string_view text, const std::string& source_name, int minimum_frames = 0);

// Another tool's motion format ("an FBX file") for a file that is not BVH, by its first bytes (may be
// empty: the extension alone) or its name's extension; nullptr when it is none of those known. readBvh
// names it in its error with what to do, and the app names it for a file dropped on the window.
const char* otherMotionFormat(std::string_view first_bytes, const std::string& name);

}  // namespace motionstyle
