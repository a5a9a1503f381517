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
#include <ostream>
#include <string>
#include <vector>

#include "motion/motion.h"

namespace motionstyle {

// Writes BVH text to a stream block by block, so a long clip never sits in memory as text: the
// constructor writes the hierarchy and "MOTION", "Frames: <frames>", "Frame Time: <frame_time>"; each
// writeFrames call writes one line per row of its block; finish() checks that <frames> rows came.
// The bytes are formatBvh's, byte for byte (same numbers, depth-first joint order, each row permuted
// to match). They reach `out` before each call returns, in pieces of about 64 KiB; the writer
// neither flushes nor checks `out`, its owner does (writeFileAtomically checks it at the end).
class BvhStreamWriter {
 public:
  // Throws std::invalid_argument (a programming error, not bad user data), writing nothing, if the
  // skeleton fails Skeleton::validate() or cannot be expressed as BVH (see formatBvh), frame_time is
  // not positive and finite, or frames < 0.
  BvhStreamWriter(std::ostream& out, const Skeleton& skeleton, int frames, double frame_time);

  // Writes the rows of `values_block` (frames x skeleton.channelCount(), columns in the skeleton's
  // channel order as in Motion::values; a Motion::values or a middleRows() of it, no copy). Throws
  // std::invalid_argument, writing nothing, if the column count differs, a value is not finite, or the
  // block would take the frames written beyond the count announced in the header.
  void writeFrames(const Eigen::Ref<const MatrixRowMajor>& values_block);

  // Throws std::invalid_argument if the frames written differ from the count announced in the header
  // (the text would not read back).
  void finish() const;

  int framesWritten() const { return written_; }

 private:
  void flush();

  std::ostream& out_;
  std::vector<Eigen::Index> columns_;  // source column of each written column
  int frames_;
  int written_ = 0;
  std::string text_;  // the text not yet handed to `out_`
};

// The BVH text of `motion`, written by a BvhStreamWriter into a string. Throws std::invalid_argument
// (a programming error, not bad user data) if motion.validate() fails or the motion cannot be
// expressed as BVH the reader accepts: a joint other than an End Site without 3 or 6 channels (three
// rotations and/or three positions), or a joint name that is blank at either end or contains braces
// or control characters.
std::string formatBvh(const Motion& motion);

// formatBvh's text written atomically (writeFileAtomically): on any failure `file` is left as it was.
// Streamed through a BvhStreamWriter, so the text is never whole in memory. Throws
// std::invalid_argument as formatBvh (before touching the disk) and WriteError on I/O failure.
void writeBvh(const Motion& motion, const std::filesystem::path& file);

}  // namespace motionstyle
