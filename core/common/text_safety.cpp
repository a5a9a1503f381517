#include "common/text_safety.h"

#include <cstdint>
#include <cstdio>

namespace motionstyle {
namespace {

constexpr std::string_view kReplacementCharacter = "\xEF\xBF\xBD";  // U+FFFD in UTF-8

// Length of the valid UTF-8 sequence at `at` (1 to 4), or 0 if the bytes there are not one.
// RFC 3629, table 3-7 of the Unicode standard: the second byte's range depends on the first byte.
std::size_t validSequenceLength(std::string_view text, std::size_t at) {
  const auto byte = [&](std::size_t i) { return static_cast<std::uint8_t>(text[at + i]); };
  const std::uint8_t lead = byte(0);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  std::uint8_t second_low = 0x80, second_high = 0xBF;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) second_low = 0xA0;   // overlong
    if (lead == 0xED) second_high = 0x9F;  // surrogates
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) second_low = 0x90;   // overlong
    if (lead == 0xF4) second_high = 0x8F;  // above U+10FFFF
  } else {
    return 0;  // continuation byte, overlong lead C0/C1, or F5-FF
  }
  if (at + length > text.size()) return 0;
  if (byte(1) < second_low || byte(1) > second_high) return 0;
  for (std::size_t i = 2; i < length; ++i)
    if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
  return length;
}

// C0, DEL, or C1 (U+0080-U+009F, encoded C2 80 - C2 9F).
bool isControl(std::string_view text, std::size_t at, std::size_t length) {
  const auto lead = static_cast<std::uint8_t>(text[at]);
  if (length == 1) return lead < 0x20 || lead == 0x7F;
  return length == 2 && lead == 0xC2 && static_cast<std::uint8_t>(text[at + 1]) <= 0x9F;
}

}  // namespace

std::string textSafetyProblem(std::string_view text) {
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t length = validSequenceLength(text, at);
    if (length == 0) return "invalid UTF-8 at byte " + std::to_string(at);
    if (isControl(text, at, length)) {
      char code[8];
      std::snprintf(code, sizeof code, "0x%02x", length == 1 ? static_cast<unsigned>(static_cast<std::uint8_t>(text[at]))
                                                               : static_cast<unsigned>(static_cast<std::uint8_t>(text[at + 1])));
      return std::string("control character ") + code + " at byte " + std::to_string(at);
    }
    at += length;
  }
  return {};
}

std::string safeText(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t length = validSequenceLength(text, at);
    if (length == 0 || isControl(text, at, length)) {
      out += kReplacementCharacter;
      at += length == 0 ? 1 : length;
      continue;
    }
    out.append(text.substr(at, length));
    at += length;
  }
  return out;
}

std::string safeLines(std::string_view text) {
  std::string out;
  for (std::size_t start = 0;;) {
    const std::size_t end = text.find('\n', start);
    out += safeText(text.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) return out;
    out += '\n';
    start = end + 1;
  }
}

}  // namespace motionstyle
