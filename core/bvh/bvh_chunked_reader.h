#pragma once
// The chunked BVH reader behind readBvh (internal to core/bvh; the tests drive it with tiny chunks).

#include <cstddef>
#include <string>

#include "bvh/bvh_line_cursor.h"
#include "motion/motion.h"

namespace motionstyle::bvh_detail {

// What is read before the text is checked to start like a BVH: a device or a binary file costs one
// small read.
inline constexpr std::size_t kBvhSniffBytes = std::size_t{1} << 16;
// readBvh's chunk: large enough that a read costs nothing per frame, small beside a long clip's values.
inline constexpr std::size_t kBvhReadChunkBytes = std::size_t{1} << 20;

// Parses the text `source` yields, options.chunk_bytes at a time, into the Motion parseBvh returns for
// the same text, with the same InputErrors on the same lines, whatever the chunk size. On top, the
// guards against devices and binary files: the first kBvhSniffBytes are read and their first
// non-blank line must be HIERARCHY before anything is parsed, and (options.refuse_nul) a NUL byte is
// refused on its line; an error on an earlier line is reported first. More than kBvhMaxBytes is
// refused (line 0). Memory: the Motion plus about two chunks (or the longest line), never the whole text.
Motion readBvhChunked(ByteSource& source, const std::string& source_name, int minimum_frames,
                      const ChunkedTextOptions& options);

}  // namespace motionstyle::bvh_detail
