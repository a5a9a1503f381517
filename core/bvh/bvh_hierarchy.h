#pragma once
// HIERARCHY section of a BVH file (internal to core/bvh): "HIERARCHY" up to the ROOT's closing brace.

#include <string>

#include "bvh/bvh_line_cursor.h"
#include "motion/skeleton.h"

namespace motionstyle::bvh_detail {

// Reads lines from `cursor` (left just after the ROOT's closing '}') and returns the skeleton in file
// order (parents before children). Iterative, so depth costs no stack. Throws InputError naming
// `source` and the line on any malformed or over-cap input (see bvh_reader.h for the rules), and
// "expected HIERARCHY, got an empty file" on line 1 for a text of whitespace only.
Skeleton parseHierarchy(LineCursor& cursor, const std::string& source);

}  // namespace motionstyle::bvh_detail
