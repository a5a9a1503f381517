#include "nn/half_float.h"

#include <cstring>

namespace motionstyle::nn {
namespace {

constexpr std::uint32_t kHalfInfinity = 0x7C00u;
constexpr std::uint32_t kHalfQuietBit = 0x0200u;

// q rounded after dropping its `shift` low bits, ties to even. shift in [1, 31].
std::uint32_t shiftRightRoundingToEven(std::uint32_t q, int shift) {
  const std::uint32_t kept = q >> shift;
  const std::uint32_t remainder = q & ((1u << shift) - 1u);
  const std::uint32_t halfway = 1u << (shift - 1);
  return remainder > halfway || (remainder == halfway && (kept & 1u) != 0) ? kept + 1u : kept;
}

}  // namespace

std::uint16_t floatToHalf(float value) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  const std::uint32_t sign = (bits >> 16) & 0x8000u;
  const std::uint32_t exponent = (bits >> 23) & 0xFFu;
  const std::uint32_t mantissa = bits & 0x7FFFFFu;
  if (exponent == 0xFFu) {  // infinity or NaN
    if (mantissa == 0) return static_cast<std::uint16_t>(sign | kHalfInfinity);
    return static_cast<std::uint16_t>(sign | kHalfInfinity | kHalfQuietBit | (mantissa >> 13));
  }
  const int half_exponent = static_cast<int>(exponent) - 127 + 15;
  if (half_exponent >= 31) return static_cast<std::uint16_t>(sign | kHalfInfinity);
  if (half_exponent >= 1) {
    // Normal: drop 13 mantissa bits. A carry out of the mantissa correctly bumps the exponent, and out
    // of exponent 30 it gives exactly the infinity encoding.
    const std::uint32_t truncated = (static_cast<std::uint32_t>(half_exponent) << 10) | (mantissa >> 13);
    const std::uint32_t rest = mantissa & 0x1FFFu;
    const bool round_up = rest > 0x1000u || (rest == 0x1000u && (truncated & 1u) != 0);
    return static_cast<std::uint16_t>(sign | (truncated + (round_up ? 1u : 0u)));
  }
  if (exponent == 0) return static_cast<std::uint16_t>(sign);  // float32 subnormals are < 2^-126
  // Subnormal half: value = significand * 2^(exponent - 150), in units of 2^-24 that is
  // significand >> (126 - exponent). A shift past 24 leaves less than half a unit: zero.
  const int shift = 126 - static_cast<int>(exponent);
  if (shift > 24) return static_cast<std::uint16_t>(sign);
  // A result of 0x400 is the smallest normal, which is also its correct encoding.
  return static_cast<std::uint16_t>(sign | shiftRightRoundingToEven(mantissa | 0x800000u, shift));
}

float halfToFloat(std::uint16_t half) {
  const std::uint32_t sign = (static_cast<std::uint32_t>(half) & 0x8000u) << 16;
  const std::uint32_t exponent = (half >> 10) & 0x1Fu;
  std::uint32_t mantissa = half & 0x3FFu;
  std::uint32_t bits = 0;
  if (exponent == 0x1Fu) {
    bits = sign | 0x7F800000u | (mantissa << 13) | (mantissa != 0 ? 0x400000u : 0u);
  } else if (exponent != 0) {
    bits = sign | ((exponent - 15u + 127u) << 23) | (mantissa << 13);
  } else if (mantissa == 0) {
    bits = sign;
  } else {
    // Subnormal half: normalise (every one is a normal float32).
    int shift = 0;
    while ((mantissa & 0x400u) == 0) {
      mantissa <<= 1;
      ++shift;
    }
    bits = sign | (static_cast<std::uint32_t>(127 - 15 + 1 - shift) << 23) | ((mantissa & 0x3FFu) << 13);
  }
  float value = 0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}  // namespace motionstyle::nn
