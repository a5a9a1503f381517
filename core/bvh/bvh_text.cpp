#include "bvh/bvh_text.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <system_error>

#include "bvh/bvh_reader.h"

namespace motionstyle::bvh_detail {

std::string_view trim(std::string_view text) {
  while (!text.empty() && isBlank(text.front())) text.remove_prefix(1);
  while (!text.empty() && isBlank(text.back())) text.remove_suffix(1);
  return text;
}

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    char x = a[i];
    char y = b[i];
    if (x >= 'A' && x <= 'Z') x = static_cast<char>(x - 'A' + 'a');
    if (y >= 'A' && y <= 'Z') y = static_cast<char>(y - 'A' + 'a');
    if (x != y) return false;
  }
  return true;
}

void splitWords(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isBlank(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !isBlank(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
}

namespace {

// std::from_chars rejects a leading '+', which some exporters write; accept it before a digit or '.'.
const char* skipPlus(const char* p, const char* end) {
  if (p < end && *p == '+' && p + 1 < end && ((p[1] >= '0' && p[1] <= '9') || p[1] == '.')) return p + 1;
  return p;
}

constexpr bool isDigit(char c) { return c >= '0' && c <= '9'; }

// Clinger's fast path, the common case of mocap text ("-3.742960", "5.1072e-06"): with at most 15
// significant digits the digits form an integer m < 2^53 and with |e| <= 22 the power 10^e is exact
// too, so one IEEE multiplication or division gives the correctly rounded double, the very value
// std::from_chars returns (x86-64 evaluates doubles in SSE2 at round-to-nearest). Returns nullptr for
// anything else (more digits, big exponents, "nan", malformed text) so that from_chars decides.
const char* parseSimpleDecimal(const char* p, const char* end, double& value) {
  static constexpr double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                            1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const bool negative = p < end && *p == '-';
  if (p < end && (*p == '-' || *p == '+')) ++p;
  std::uint64_t mantissa = 0;
  int significant = 0;  // digits in `mantissa` once the leading zeros are skipped
  int exponent = 0;
  bool any_digit = false;
  for (; p < end && isDigit(*p); ++p) {
    any_digit = true;
    if (mantissa == 0 && *p == '0') continue;
    mantissa = mantissa * 10 + static_cast<std::uint64_t>(*p - '0');
    if (++significant > 15) return nullptr;
  }
  if (p < end && *p == '.') {
    for (++p; p < end && isDigit(*p); ++p) {
      any_digit = true;
      --exponent;
      if (mantissa == 0 && *p == '0') continue;
      mantissa = mantissa * 10 + static_cast<std::uint64_t>(*p - '0');
      if (++significant > 15) return nullptr;
    }
  }
  if (!any_digit) return nullptr;
  if (p < end && (*p == 'e' || *p == 'E')) {
    ++p;
    const bool negative_exponent = p < end && *p == '-';
    if (p < end && (*p == '-' || *p == '+')) ++p;
    if (p == end || !isDigit(*p)) return nullptr;
    int written = 0;
    for (; p < end && isDigit(*p); ++p) {
      written = written * 10 + (*p - '0');
      if (written > 1000) return nullptr;
    }
    exponent += negative_exponent ? -written : written;
  }
  if (p < end && !isBlank(*p) && *p != '\n') return nullptr;
  if (exponent < -22 || exponent > 22) {
    if (mantissa != 0) return nullptr;
    exponent = 0;  // zero is zero whatever its exponent ("0.000000000000000000000000")
  }
  double result = static_cast<double>(mantissa);
  result = exponent < 0 ? result / kPowersOfTen[-exponent] : result * kPowersOfTen[exponent];
  value = negative ? -result : result;
  return p;
}

}  // namespace

const char* parseNumberAt(const char* p, const char* end, double& value, NumberStatus& status) {
  if (const char* stop = parseSimpleDecimal(p, end, value)) {
    status = NumberStatus::Ok;
    return stop;
  }
  const auto [stop, error] = std::from_chars(skipPlus(p, end), end, value);
  if (error == std::errc::result_out_of_range) {
    status = NumberStatus::OutOfRange;
    return nullptr;
  }
  if (error != std::errc() || (stop < end && !isBlank(*stop) && *stop != '\n')) {
    status = NumberStatus::NotANumber;
    return nullptr;
  }
  // from_chars accepts "nan" and "inf": a motion channel must be a finite angle or length.
  if (!std::isfinite(value)) {
    status = NumberStatus::NotFinite;
    return nullptr;
  }
  status = NumberStatus::Ok;
  return stop;
}

NumberStatus parseNumber(std::string_view word, double& value) {
  NumberStatus status = NumberStatus::NotANumber;
  if (word.empty()) return status;
  const char* end = word.data() + word.size();
  const char* stop = parseNumberAt(word.data(), end, value, status);
  if (stop != nullptr && stop != end) status = NumberStatus::NotANumber;
  return status;
}

bool parseCount(std::string_view word, long long max_value, long long& value) {
  const char* end = word.data() + word.size();
  const auto [stop, error] = std::from_chars(skipPlus(word.data(), end), end, value);
  return !word.empty() && error == std::errc() && stop == end && value >= 0 && value <= max_value;
}

std::string_view wordAt(const char* p, const char* end) {
  const char* stop = p;
  while (stop < end && !isBlank(*stop) && *stop != '\n') ++stop;
  return std::string_view(p, static_cast<std::size_t>(stop - p));
}

std::string formatBound(double bound) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", bound);
  std::string text = buffer;
  if (text.find('e') != std::string::npos) {  // %g switches to exponents at 1e6 and below 1e-4
    std::snprintf(buffer, sizeof buffer, "%.0f", bound);
    if (bound >= 1.0) text = buffer;
  }
  return text;
}

std::string tooLargeDetail(std::string_view got) {
  return "expected at most " + std::to_string(kBvhMaxBytes) + " bytes of BVH, got " + std::string(got);
}

std::string excerpt(std::string_view text) {
  constexpr std::size_t kMaxShown = 40;
  std::string result = "'";
  for (std::size_t i = 0; i < text.size() && i < kMaxShown; ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte >= 0x20 && byte < 0x7F) {
      result += static_cast<char>(byte);
    } else {
      static constexpr char kHex[] = "0123456789ABCDEF";
      result += "\\x";
      result += kHex[byte >> 4];
      result += kHex[byte & 0xF];
    }
  }
  if (text.size() > kMaxShown) result += "...";
  result += "'";
  return result;
}

}  // namespace motionstyle::bvh_detail
