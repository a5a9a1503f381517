#include "motion/rotation.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>

namespace motionstyle {
namespace {

constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;
constexpr double kRadiansPerDegree = std::numbers::pi / 180.0;
// |cos(middle angle)| below this counts as gimbal lock: only there do the first and third angles trade
// off freely without moving the rotation by more than ~1e-12 rad.
constexpr double kGimbalLockCosine = 1e-12;

// sin and cos of HALF an angle given in degrees, branch-free so that loops over it vectorise.
// The half angle h is split as h = 90 q + r with q whole and |r| <= 45 (+ rounding): q comes from the
// 1.5 * 2^52 rounding trick (its low bits are q mod 4), and r = h - 90 q is EXACT in floating point
// (90 q is an integer, a multiple of h's ulp, and |r| <= |h|). Then sin/cos of r (in radians, at most
// pi/4) by Taylor series: the first omitted terms, x^19/19! and x^18/18!, are below 1e-17, under half an
// ulp. Valid for angles below 2^50 degrees; larger ones go through halfAngleSinCosLarge.
struct SinCos {
  double sin, cos;
};

constexpr double kRoundingShifter = 0x1.8p52;
constexpr double kLargeHalfAngle = 0x1p50;  // degrees

// Taylor coefficients (-1)^n / (2n + first)!, n = 0 .. N - 1: sin uses first = 3 (x^3 .. x^17 after x),
// cos uses first = 2 (x^2 .. x^16 after 1).
template <size_t N>
constexpr std::array<double, N> taylorCoefficients(int first) {
  std::array<double, N> coefficients{};
  double factorial = 1.0;  // exact: 17! < 2^53
  for (int k = 2; k < first; ++k) factorial *= k;
  for (size_t n = 0; n < N; ++n) {
    const int power = first + 2 * static_cast<int>(n);
    factorial *= power;
    if (n > 0) factorial *= power - 1;
    coefficients[n] = (n % 2 == 0 ? -1.0 : 1.0) / factorial;
  }
  return coefficients;
}
constexpr std::array<double, 8> kSineTaylor = taylorCoefficients<8>(3);
constexpr std::array<double, 8> kCosineTaylor = taylorCoefficients<8>(2);

// sum_n coefficients[n] z^n, by Horner's rule.
template <size_t N>
inline double horner(const std::array<double, N>& coefficients, double z) {
  double sum = coefficients[N - 1];
  for (size_t n = N - 1; n-- > 0;) sum = sum * z + coefficients[n];
  return sum;
}

inline SinCos halfAngleSinCosSmall(double degrees) {
  const double half = 0.5 * degrees;
  const double shifted = half * (1.0 / 90.0) + kRoundingShifter;
  const double quadrant = shifted - kRoundingShifter;
  const auto quadrant_bits = std::bit_cast<std::uint64_t>(shifted);
  const double x = (half - 90.0 * quadrant) * kRadiansPerDegree;
  const double z = x * x;
  const double s = x + x * z * horner(kSineTaylor, z);
  const double c = 1.0 + z * horner(kCosineTaylor, z);
  // h = r + 90 q: quadrant 1 gives (cos r, -sin r), 2 gives (-sin r, -cos r), 3 gives (-cos r, sin r).
  const bool swap = (quadrant_bits & 1u) != 0;
  const std::uint64_t sin_sign = (quadrant_bits & 2u) << 62;
  const std::uint64_t cos_sign = ((quadrant_bits + 1u) & 2u) << 62;
  const double sine = swap ? c : s;
  const double cosine = swap ? s : c;
  return {std::bit_cast<double>(std::bit_cast<std::uint64_t>(sine) ^ sin_sign),
          std::bit_cast<double>(std::bit_cast<std::uint64_t>(cosine) ^ cos_sign)};
}

// N angles at once, results gathered in registers before they are stored (outputs may alias nothing).
template <size_t N>
void halfAngleSinCosBlock(const double* degrees, double* sines, double* cosines) {
  std::array<double, N> sin_block, cos_block;
  for (size_t i = 0; i < N; ++i) {
    const SinCos value = halfAngleSinCosSmall(degrees[i]);
    sin_block[i] = value.sin;
    cos_block[i] = value.cos;
  }
  std::copy_n(sin_block.begin(), N, sines);
  std::copy_n(cos_block.begin(), N, cosines);
}

// Any finite angle: whole turns (720 degrees of the full angle) removed exactly first.
SinCos halfAngleSinCosLarge(double degrees) { return halfAngleSinCosSmall(std::fmod(degrees, 720.0)); }

SinCos halfAngleSinCosOf(double degrees) {
  return std::abs(degrees) < kLargeHalfAngle ? halfAngleSinCosSmall(degrees) : halfAngleSinCosLarge(degrees);
}

// Maps degrees into (-180, 180]. An angle already there is returned as it is, as remainder() would
// return it, without the library call (a clip's conversion to channels makes millions of them).
double wrapPrincipal(double degrees) {
  if (degrees > -180.0 && degrees <= 180.0) return degrees;
  double wrapped = std::remainder(degrees, 360.0);  // [-180, 180]
  if (wrapped <= -180.0) wrapped += 360.0;
  return wrapped;
}

// `degrees` moved by a multiple of 360 to lie within 180 of `reference` (remainder() returns a
// difference of at most 180 unchanged: the fast path gives the same number).
double wrapNear(double degrees, double reference) {
  const double difference = degrees - reference;
  return reference + (std::abs(difference) <= 180.0 ? difference : std::remainder(difference, 360.0));
}

// Three distinct axes i, j, k in channel order and the parity sign s: +1 when (i, j, k) is a cyclic
// permutation of (X, Y, Z), -1 otherwise. With it the matrix entries of R = Ri(a) Rj(b) Rk(c) read
// uniformly: R(i,k) = s sin b, R(j,k) = -s sin a cos b, R(k,k) = cos a cos b, R(i,j) = -s cos b sin c.
struct TaitBryan {
  int i, j, k;
  double s;
};

TaitBryan taitBryan(int first, int second) {
  return {first, second, 3 - first - second, second == (first + 1) % 3 ? 1.0 : -1.0};
}

Eigen::Matrix3d axisMatrix(int axis, double radians) {
  return Eigen::AngleAxisd(radians, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
}

// Given the first angle a (radians), the middle and last angles of R = Ri(a) Rj(b) Rk(c): from
// M = Ri(a)^T R = Rj(b) Rk(c), whose column k is Rj(b) e_k and whose row j is e_j^T Rk(c). Exact when
// some decomposition with this a exists (always one of the two solutions' a, any a at gimbal lock).
Eigen::Vector3d completeFromFirst(const Eigen::Matrix3d& r, const TaitBryan& t, double a) {
  const Eigen::Matrix3d m = axisMatrix(t.i, a).transpose() * r;
  const double b = std::atan2(t.s * m(t.i, t.k), m(t.k, t.k));
  const double c = std::atan2(t.s * m(t.j, t.i), m(t.j, t.j));
  return {a, b, c};
}

// completeFromFirst's last angle c alone (the same arithmetic, one atan2 fewer).
double lastFromFirst(const Eigen::Matrix3d& r, const TaitBryan& t, double a) {
  const Eigen::Matrix3d m = axisMatrix(t.i, a).transpose() * r;
  return std::atan2(t.s * m(t.j, t.i), m(t.j, t.j));
}

// Principal solution in radians: b in [-pi/2, pi/2]; at gimbal lock c = 0 and a carries the free angle.
Eigen::Vector3d principalRadians(const Eigen::Matrix3d& r, const TaitBryan& t, bool& gimbal_lock) {
  // b from row i = (cos b cos c, -s cos b sin c, s sin b): well conditioned everywhere, in [-pi/2, pi/2].
  const double cos_b = std::hypot(r(t.i, t.i), r(t.i, t.j));
  const double b = std::atan2(t.s * r(t.i, t.k), cos_b);
  gimbal_lock = cos_b < kGimbalLockCosine;
  double a = 0.0;
  if (!gimbal_lock) {
    a = std::atan2(-t.s * r(t.j, t.k), r(t.k, t.k));
  } else {
    // At b = +-90: Ri(a) Rj(b) = Rj(b) Rk(s sin(b) a), so R = Rj(b) Rk(s sin(b) a + c). With c = 0, read
    // the angle phi of Rk(phi) = Rj(b)^T R (row j of Rk(phi) is e_j^T Rk) and set a = s sin(b) phi.
    const Eigen::Matrix3d p = axisMatrix(t.j, b).transpose() * r;
    const double phi = std::atan2(t.s * p(t.j, t.i), p(t.j, t.j));
    a = t.s * (b > 0.0 ? 1.0 : -1.0) * phi;
  }
  // c from a (not from row i, whose entries vanish near lock), so that the three stay consistent.
  return {a, b, lastFromFirst(r, t, a)};
}

Eigen::Vector3d toDegrees(const Eigen::Vector3d& radians) { return radians * kDegreesPerRadian; }

double squaredDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return (a - b).squaredNorm(); }

Eigen::Vector3d wrapAllNear(const Eigen::Vector3d& degrees, const Eigen::Vector3d& previous) {
  return {wrapNear(degrees[0], previous[0]), wrapNear(degrees[1], previous[1]), wrapNear(degrees[2], previous[2])};
}

// The other solution of a Tait-Bryan decomposition (degrees): (a + 180, 180 - b, c + 180).
Eigen::Vector3d alternateSolution(const Eigen::Vector3d& degrees) {
  return {degrees[0] + 180.0, 180.0 - degrees[1], degrees[2] + 180.0};
}

Eigen::Vector3d threeAxisPrincipal(const Eigen::Matrix3d& r, const TaitBryan& t) {
  bool gimbal_lock = false;
  const Eigen::Vector3d d = toDegrees(principalRadians(r, t, gimbal_lock));
  return {wrapPrincipal(d[0]), d[1], wrapPrincipal(d[2])};
}

Eigen::Vector3d threeAxisNearest(const Eigen::Matrix3d& r, const TaitBryan& t, const Eigen::Vector3d& previous) {
  bool gimbal_lock = false;
  const Eigen::Vector3d principal = toDegrees(principalRadians(r, t, gimbal_lock));
  Eigen::Vector3d best = wrapAllNear(principal, previous);
  const Eigen::Vector3d alternate = wrapAllNear(alternateSolution(principal), previous);
  if (squaredDistance(alternate, previous) < squaredDistance(best, previous)) best = alternate;
  if (!gimbal_lock) return best;
  // The free family is (a + u, b, c - sigma u) with sigma = s sign(sin b): take the u that moves a and c
  // least, then re-derive b and c from that a so that the rotation stays exact.
  const double sigma = t.s * (std::sin(best[1] * kRadiansPerDegree) > 0.0 ? 1.0 : -1.0);
  const double u = 0.5 * ((previous[0] - best[0]) + sigma * (best[2] - previous[2]));
  const Eigen::Vector3d split = toDegrees(completeFromFirst(r, t, (best[0] + u) * kRadiansPerDegree));
  const Eigen::Vector3d candidate = wrapAllNear(split, previous);
  return squaredDistance(candidate, previous) < squaredDistance(best, previous) ? candidate : best;
}

// Two axes (a, b): decompose with the missing third axis and keep the solution whose third angle is
// nearest 0 (mod 360); ties (only for rotations far from expressible) go to the one nearest `previous`.
Eigen::Vector3d twoAxis(const Eigen::Matrix3d& r, const RotationAxes& axes, const Eigen::Vector3d* previous) {
  const TaitBryan t = taitBryan(axes.axis[0], axes.axis[1]);
  bool gimbal_lock = false;
  const Eigen::Vector3d principal = toDegrees(principalRadians(r, t, gimbal_lock));
  const Eigen::Vector3d alternate = alternateSolution(principal);
  const double residual_principal = std::abs(wrapPrincipal(principal[2]));
  const double residual_alternate = std::abs(wrapPrincipal(alternate[2]));
  Eigen::Vector3d chosen;
  if (previous == nullptr) {
    chosen = residual_alternate < residual_principal ? alternate : principal;
    return {wrapPrincipal(chosen[0]), wrapPrincipal(chosen[1]), 0.0};
  }
  const Eigen::Vector3d reference((*previous)[0], (*previous)[1], 0.0);
  const Eigen::Vector3d near_principal = wrapAllNear(principal, reference);
  const Eigen::Vector3d near_alternate = wrapAllNear(alternate, reference);
  if (std::abs(residual_alternate - residual_principal) > 1e-9)
    chosen = residual_alternate < residual_principal ? near_alternate : near_principal;
  else
    chosen = squaredDistance(near_alternate, reference) < squaredDistance(near_principal, reference) ? near_alternate
                                                                                                      : near_principal;
  return {chosen[0], chosen[1], 0.0};
}

// One axis: the twist about it, 2 atan2(q_axis, q_w), in degrees.
double twistDegrees(const Eigen::Quaterniond& q, int axis) {
  return 2.0 * std::atan2(q.vec()[axis], q.w()) * kDegreesPerRadian;
}

Eigen::Vector3d decompose(const Eigen::Quaterniond& rotation, const RotationAxes& axes,
                          const Eigen::Vector3d* previous) {
  const double norm = rotation.norm();
  if (!(std::isfinite(norm) && norm > 0.0))
    throw std::invalid_argument("quaternionToEuler: the quaternion is zero or not finite");
  const Eigen::Quaterniond q(rotation.coeffs() / norm);
  switch (axes.count) {
    case 0: return Eigen::Vector3d::Zero();
    case 1: {
      const double twist = twistDegrees(q, axes.axis[0]);
      return {previous ? wrapNear(twist, (*previous)[0]) : wrapPrincipal(twist), 0.0, 0.0};
    }
    case 2: return twoAxis(q.toRotationMatrix(), axes, previous);
    case 3: {
      const TaitBryan t = taitBryan(axes.axis[0], axes.axis[1]);
      const Eigen::Matrix3d r = q.toRotationMatrix();
      return previous ? threeAxisNearest(r, t, *previous) : threeAxisPrincipal(r, t);
    }
    default: throw std::invalid_argument("rotation axes: count must be 0..3, got " + std::to_string(axes.count));
  }
}

void checkAxes(const RotationAxes& axes) {
  if (axes.count < 0 || axes.count > 3)
    throw std::invalid_argument("rotation axes: count must be 0..3, got " + std::to_string(axes.count));
  for (int n = 0; n < axes.count; ++n) {
    if (axes.axis[n] < 0 || axes.axis[n] > 2) throw std::invalid_argument("rotation axes: axis must be 0, 1 or 2");
    for (int m = 0; m < n; ++m)
      if (axes.axis[m] == axes.axis[n]) throw std::invalid_argument("rotation axes: an axis repeats");
  }
}

}  // namespace

std::string_view eulerOrderName(EulerOrder order) {
  switch (order) {
    case EulerOrder::XYZ: return "XYZ";
    case EulerOrder::XZY: return "XZY";
    case EulerOrder::YXZ: return "YXZ";
    case EulerOrder::YZX: return "YZX";
    case EulerOrder::ZXY: return "ZXY";
    case EulerOrder::ZYX: return "ZYX";
  }
  return "?";
}

RotationAxes RotationAxes::of(EulerOrder order) {
  switch (order) {
    case EulerOrder::XYZ: return {{0, 1, 2}, 3};
    case EulerOrder::XZY: return {{0, 2, 1}, 3};
    case EulerOrder::YXZ: return {{1, 0, 2}, 3};
    case EulerOrder::YZX: return {{1, 2, 0}, 3};
    case EulerOrder::ZXY: return {{2, 0, 1}, 3};
    case EulerOrder::ZYX: return {{2, 1, 0}, 3};
  }
  throw std::invalid_argument("unknown Euler order");
}

RotationAxes RotationAxes::of(const std::vector<ChannelType>& channels) {
  RotationAxes axes;
  for (ChannelType c : channels) {
    if (!isRotation(c)) continue;
    const int axis = axisOf(c);
    for (int n = 0; n < axes.count; ++n)
      if (axes.axis[n] == axis) throw std::invalid_argument("rotation channel " + std::string(channelName(c)) + " repeats");
    if (axes.count == 3) throw std::invalid_argument("more than three rotation channels");
    axes.axis[axes.count++] = axis;
  }
  return axes;
}

Eigen::Quaterniond axisRotation(int axis, double degrees) {
  const SinCos half = halfAngleSinCosOf(degrees);
  Eigen::Quaterniond q(half.cos, 0.0, 0.0, 0.0);
  q.vec()[axis] = half.sin;
  return q;
}

void halfAngleSinCos(std::span<const double> degrees, std::span<double> sines, std::span<double> cosines) {
  if (sines.size() != degrees.size() || cosines.size() != degrees.size())
    throw std::invalid_argument("halfAngleSinCos: " + std::to_string(degrees.size()) + " angles but " +
                                std::to_string(sines.size()) + " sines and " + std::to_string(cosines.size()) +
                                " cosines");
  const size_t n = degrees.size();
  bool large = false;
  for (size_t i = 0; i < n; ++i) large |= !(std::abs(degrees[i]) < kLargeHalfAngle);  // also NaN
  if (large) {
    for (size_t i = 0; i < n; ++i) {
      const SinCos value = halfAngleSinCosOf(degrees[i]);
      sines[i] = value.sin;
      cosines[i] = value.cos;
    }
    return;
  }
  // Blocks of kBlock angles, the last one padded, all through the one call below (vectorised): an
  // angle's result then does not depend on its position in the array, as it could if a scalar
  // remainder loop contracted multiply-adds differently.
  constexpr size_t kBlock = 8;
  std::array<double, kBlock> padded_in{}, padded_sin{}, padded_cos{};
  for (size_t first = 0; first < n; first += kBlock) {
    const size_t count = std::min(kBlock, n - first);
    const bool whole = count == kBlock;
    if (!whole) std::copy_n(degrees.data() + first, count, padded_in.begin());
    const double* in = whole ? degrees.data() + first : padded_in.data();
    double* sin_out = whole ? sines.data() + first : padded_sin.data();
    double* cos_out = whole ? cosines.data() + first : padded_cos.data();
    halfAngleSinCosBlock<kBlock>(in, sin_out, cos_out);
    if (!whole) {
      std::copy_n(padded_sin.begin(), count, sines.data() + first);
      std::copy_n(padded_cos.begin(), count, cosines.data() + first);
    }
  }
}

Eigen::Quaterniond eulerToQuaternion(const Eigen::Vector3d& degrees, const RotationAxes& axes) {
  checkAxes(axes);
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (int n = 0; n < axes.count; ++n) {
    const SinCos half = halfAngleSinCosOf(degrees[n]);
    q = composeAxisRotation(q, axes.axis[static_cast<size_t>(n)], half.cos, half.sin);
  }
  return q;
}

Eigen::Vector3d quaternionToEuler(const Eigen::Quaterniond& rotation, const RotationAxes& axes) {
  checkAxes(axes);
  return decompose(rotation, axes, nullptr);
}

Eigen::Vector3d quaternionToEuler(const Eigen::Quaterniond& rotation, const RotationAxes& axes,
                                  const Eigen::Vector3d& previous_degrees) {
  checkAxes(axes);
  return decompose(rotation, axes, &previous_degrees);
}

double rotationDistance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  // atan2 of the relative rotation keeps full precision for tiny angles (acos of the dot does not).
  const Eigen::Quaterniond relative = a.normalized().conjugate() * b.normalized();
  return 2.0 * std::atan2(relative.vec().norm(), std::abs(relative.w()));
}

}  // namespace motionstyle
