// IEEE binary16 conversion (nn/half_float.h): invalid and edge values first (overflow, NaN, infinity,
// subnormals, underflow), then exactness on every representable value and ties-to-even rounding
// between every pair of neighbouring values.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "nn/half_float.h"

namespace motionstyle::nn {
namespace {

// The value of a binary16 bit pattern from its definition, in double (independent of halfToFloat).
double referenceHalfValue(std::uint16_t h) {
  const int sign = (h >> 15) != 0 ? -1 : 1;
  const int exponent = (h >> 10) & 0x1F;
  const int mantissa = h & 0x3FF;
  if (exponent == 0) return sign * std::ldexp(static_cast<double>(mantissa), -24);
  return sign * std::ldexp(1.0 + mantissa / 1024.0, exponent - 15);
}

bool isHalfNan(std::uint16_t h) { return (h & 0x7C00u) == 0x7C00u && (h & 0x3FFu) != 0; }

TEST(HalfFloatInvalid, OverflowBecomesInfinity) {
  EXPECT_EQ(floatToHalf(65504.0f), 0x7BFFu);    // the largest finite value
  EXPECT_EQ(floatToHalf(65519.996f), 0x7BFFu);  // just below the midpoint to the next (nonexistent) value
  EXPECT_EQ(floatToHalf(65520.0f), 0x7C00u);    // the midpoint rounds to even: infinity
  EXPECT_EQ(floatToHalf(1e10f), 0x7C00u);
  EXPECT_EQ(floatToHalf(-1e10f), 0xFC00u);
  EXPECT_EQ(floatToHalf(std::numeric_limits<float>::max()), 0x7C00u);
  EXPECT_EQ(floatToHalf(std::numeric_limits<float>::infinity()), 0x7C00u);
  EXPECT_EQ(floatToHalf(-std::numeric_limits<float>::infinity()), 0xFC00u);
  EXPECT_TRUE(std::isinf(halfToFloat(0x7C00u)));
  EXPECT_LT(halfToFloat(0xFC00u), 0.0f);
}

TEST(HalfFloatInvalid, NanStaysNanWithItsSign) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(isHalfNan(floatToHalf(nan)));
  EXPECT_TRUE(isHalfNan(floatToHalf(-nan)));
  EXPECT_EQ(floatToHalf(-nan) & 0x8000u, 0x8000u);
  // A signalling NaN whose payload lives only in the low bits must not become infinity.
  EXPECT_TRUE(isHalfNan(floatToHalf(std::numeric_limits<float>::signaling_NaN())));
  EXPECT_TRUE(std::isnan(halfToFloat(0x7E00u)));
  EXPECT_TRUE(std::isnan(halfToFloat(0x7C01u)));
  EXPECT_TRUE(std::signbit(halfToFloat(0xFE00u)));
}

TEST(HalfFloatInvalid, SubnormalsAndUnderflow) {
  const float tiny = std::ldexp(1.0f, -24);  // the smallest subnormal
  EXPECT_EQ(floatToHalf(tiny), 0x0001u);
  EXPECT_EQ(halfToFloat(0x0001u), tiny);
  EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -25)), 0x0000u);             // halfway to 0: ties to even (0)
  EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -25) * 1.0001f), 0x0001u);   // just above halfway
  EXPECT_EQ(floatToHalf(std::ldexp(3.0f, -25)), 0x0002u);             // 1.5 units: ties to even (2)
  EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -26)), 0x0000u);
  EXPECT_EQ(floatToHalf(-std::ldexp(1.0f, -26)), 0x8000u);            // signed zero
  EXPECT_EQ(floatToHalf(std::numeric_limits<float>::denorm_min()), 0x0000u);
  EXPECT_EQ(floatToHalf(std::ldexp(1.0f, -14)), 0x0400u);             // the smallest normal
  EXPECT_EQ(floatToHalf(std::ldexp(1023.0f, -24)), 0x03FFu);          // the largest subnormal
  EXPECT_EQ(floatToHalf(std::ldexp(1023.5f, -24)), 0x0400u);          // rounds up into the normals
  EXPECT_EQ(floatToHalf(0.0f), 0x0000u);
  EXPECT_EQ(floatToHalf(-0.0f), 0x8000u);
  EXPECT_TRUE(std::signbit(halfToFloat(0x8000u)));
}

TEST(HalfFloat, EveryRepresentableValueIsExact) {
  for (std::uint32_t h = 0; h <= 0xFFFFu; ++h) {
    const auto half = static_cast<std::uint16_t>(h);
    if (isHalfNan(half)) continue;
    const float value = halfToFloat(half);
    if ((half & 0x7FFFu) == 0x7C00u) {
      EXPECT_TRUE(std::isinf(value)) << h;
    } else {
      EXPECT_EQ(static_cast<double>(value), referenceHalfValue(half)) << h;
    }
    EXPECT_EQ(floatToHalf(value), half) << h;
  }
  EXPECT_EQ(floatToHalf(1.0f), 0x3C00u);
  EXPECT_EQ(floatToHalf(-2.0f), 0xC000u);
  EXPECT_EQ(floatToHalf(0.333251953125f), 0x3555u);
}

TEST(HalfFloat, RoundsToNearestTiesToEvenBetweenEveryPairOfNeighbours) {
  // Positive finite values a < b adjacent in binary16; their midpoint is exact in float32.
  for (std::uint16_t h = 0; h < 0x7BFFu; ++h) {
    const auto next = static_cast<std::uint16_t>(h + 1);
    const float a = halfToFloat(h);
    const float b = halfToFloat(next);
    const float mid = 0.5f * (a + b);
    const std::uint16_t even = (h & 1u) == 0 ? h : next;
    EXPECT_EQ(floatToHalf(mid), even) << h;
    EXPECT_EQ(floatToHalf(std::nextafter(mid, b)), next) << h;
    EXPECT_EQ(floatToHalf(std::nextafter(mid, a)), h) << h;
    EXPECT_EQ(floatToHalf(-mid), even | 0x8000u) << h;
  }
}

TEST(HalfFloat, RelativeErrorOfNormalValuesIsAtMostHalfAnUlp) {
  for (float x = 6.2e-5f; x < 60000.0f; x *= 1.0007f) {
    const float back = halfToFloat(floatToHalf(x));
    EXPECT_LE(std::abs(static_cast<double>(back) - static_cast<double>(x)), std::ldexp(static_cast<double>(x), -11)) << x;
  }
}

}  // namespace
}  // namespace motionstyle::nn
