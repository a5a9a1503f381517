#pragma once
// Low-level text helpers shared by the BVH reader's hierarchy and motion parsers (internal to core/bvh).
// Lines are walked by LineCursor (bvh_line_cursor.h).
//
// Line model: a line ends at '\n'. '\r' counts as whitespace, so CRLF, LF and files that mix both
// (CMU's converted files do) read the same, and line numbers match what an editor shows.
// Whitespace inside a line: space, tab, '\r', '\v', '\f'.

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace motionstyle::bvh_detail {

constexpr bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string_view trim(std::string_view text);
bool equalsIgnoreCase(std::string_view a, std::string_view b);

// Splits a line into whitespace-separated words.
void splitWords(std::string_view line, std::vector<std::string_view>& words);

enum class NumberStatus { Ok, NotANumber, OutOfRange, NotFinite };

// Parses one decimal number (fixed or scientific, optional sign, ".5" allowed) that must fill `word`.
NumberStatus parseNumber(std::string_view word, double& value);
// Parses a non-negative decimal integer that must fill `word` and be <= max_value.
bool parseCount(std::string_view word, long long max_value, long long& value);

// Hot-path variant for the MOTION section: parses a number starting at `p` that must be followed by
// whitespace, '\n' or the end. On success returns the pointer just past it; otherwise nullptr and
// `status` tells why.
const char* parseNumberAt(const char* p, const char* end, double& value, NumberStatus& status);

// The word starting at `p` (up to whitespace or the end), for messages.
std::string_view wordAt(const char* p, const char* end);

// A bound for an error message: shortest form ("0.0001", "1", "1000000"), never "1e+06".
std::string formatBound(double bound);

// "expected at most <kBvhMaxBytes> bytes of BVH, got <got>": the detail for a text over the cap.
std::string tooLargeDetail(std::string_view got);

// `text` quoted for an error message: at most 40 characters, control and non-ASCII bytes escaped so
// binary garbage cannot mangle a terminal or a dialog.
std::string excerpt(std::string_view text);

}  // namespace motionstyle::bvh_detail
