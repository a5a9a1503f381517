#pragma once
// IEEE 754 binary16 ("half", f16) conversion for compact network files (NETWORK_FORMAT.md, version 2).
// Written here rather than taken from a library: it is 60 lines and the file format must not depend on
// a compiler's _Float16 support. Weights are stored as f16 and always computed with in float32.
//
// binary16: 1 sign bit, 5 exponent bits (bias 15), 10 mantissa bits. Largest finite 65504, smallest
// normal 2^-14 (~6.1e-5), smallest subnormal 2^-24 (~6.0e-8), ~3.3 significant decimal digits
// (relative rounding error <= 2^-11 for normal values).

#include <cstdint>

namespace motionstyle::nn {

// Round to nearest, ties to even (IEEE's default), including into and out of the subnormal range:
// |value| >= 65520 (the midpoint above 65504) becomes +-infinity, |value| <= 2^-25 becomes +-0, float32
// subnormals become +-0. Infinities stay infinities; NaN stays NaN (quiet, sign and the top mantissa
// bits kept). Every binary16 value converts back to itself: floatToHalf(halfToFloat(h)) == h for
// every h that is not a NaN.
std::uint16_t floatToHalf(float value);

// Exact: every binary16 value (incl. subnormals, +-0, +-infinity) is representable in float32. NaN
// gives a quiet NaN with the same sign.
float halfToFloat(std::uint16_t half);

constexpr float kHalfMax = 65504.0f;

}  // namespace motionstyle::nn
