#pragma once
// Euler angles <-> unit quaternions, in the BVH convention.
//
// Convention: a joint whose rotation channels are listed as c1 c2 c3 (e.g. "Zrotation Xrotation
// Yrotation") has the local rotation R = R_c1(a1) * R_c2(a2) * R_c3(a3): column vectors, right-handed
// axes, positive angles counter-clockwise when looking down the axis towards the origin. Equivalently,
// the rotations are applied to a vector in the order c3, then c2, then c1 (intrinsic c1, c2, c3).
// Angles are in DEGREES at this interface (they are what a BVH file holds); radians never leave the
// implementation.
//
// Joints may have 3, 2, 1 or no rotation channels (RotationAxes::count). Angles are always passed as an
// Eigen::Vector3d whose first `count` entries follow the channel order; the remaining entries are
// ignored on input and set to 0 on output.
//
// Decomposition (quaternion -> Euler) for three distinct axes: every rotation has exactly two
// solutions (a1, a2, a3) and (a1 + 180, 180 - a2, a3 + 180), each up to multiples of 360 per angle,
// except at gimbal lock (a2 = +-90) where only a1 +- a3 is determined. Both overloads return angles that
// reproduce the rotation to rounding error (about 1e-15 rad), including at and near gimbal lock:
//   - the principal overload returns a2 in [-90, 90] and a1, a3 in (-180, 180]; at gimbal lock it puts
//     the whole free angle into a1 - well defined, but arbitrary;
//   - the `previous` overload returns the solution closest to the previous frame's angles (each angle
//     moved by multiples of 360 to lie within 180 of its predecessor, then the nearer of the two
//     solutions in summed squared degrees). At gimbal lock (|cos a2| < 1e-12) it splits the free angle
//     between a1 and a3 so that both move as little as possible. Use it when writing sequences: it
//     removes 360-degree jumps and the a2 -> 180 - a2 flips that the principal overload shows.
//
// Fewer than three channels: a rotation outside what the axes can express is PROJECTED onto them
// (exact whenever the rotation is expressible):
//   - one axis: the twist about that axis, a1 = 2 atan2(q.axis, q.w) (the swing is dropped);
//   - two axes c1 c2: the rotation is decomposed in the order (c1, c2, c3) with the third axis c3 and
//     the solution whose a3 is nearer 0 (mod 360) is kept, a3 dropped;
//   - no axis: identity, no angles.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "motion/skeleton.h"

namespace motionstyle {

// The six Tait-Bryan orders, named in channel order: ZXY means channels "Zrotation Xrotation Yrotation"
// and R = Rz * Rx * Ry.
enum class EulerOrder : std::uint8_t { XYZ, XZY, YXZ, YZX, ZXY, ZYX };
inline constexpr std::array<EulerOrder, 6> kAllEulerOrders = {EulerOrder::XYZ, EulerOrder::XZY, EulerOrder::YXZ,
                                                              EulerOrder::YZX, EulerOrder::ZXY, EulerOrder::ZYX};
std::string_view eulerOrderName(EulerOrder order);  // "XYZ", ...

// The rotation axes of one joint in channel order (0 = X, 1 = Y, 2 = Z); `count` of them (0..3), distinct.
struct RotationAxes {
  std::array<int, 3> axis{0, 1, 2};
  int count = 0;

  static RotationAxes of(EulerOrder order);
  // The rotation channels of a channel list, in order (position channels are skipped).
  // Throws std::invalid_argument if a rotation axis repeats.
  static RotationAxes of(const std::vector<ChannelType>& channels);
};

// Rotation by `degrees` about one coordinate axis (0 = X, 1 = Y, 2 = Z).
Eigen::Quaterniond axisRotation(int axis, double degrees);

// Sine and cosine of HALF of each angle, the scalar and vector parts of an axis rotation's quaternion:
// sines[n] = sin(degrees[n] / 2), cosines[n] = cos(degrees[n] / 2) (angles in degrees). The reduction
// to +-45 degrees is exact (done in degrees), so results are within about 1 ulp of the true values for
// any finite angle (NaN for a non-finite one); axisRotation and eulerToQuaternion use the same method.
// Vectorised, without allocation: the fast path for whole clips. Every angle goes through the same
// instructions, so its result does not depend on its position in the span. std::invalid_argument when
// the three spans differ in size.
void halfAngleSinCos(std::span<const double> degrees, std::span<double> sines, std::span<double> cosines);

// q * axisRotation(axis, a), given cos(a / 2) and sin(a / 2): the product with a quaternion that has a
// single vector component, in 8 multiplications instead of 16.
inline Eigen::Quaterniond composeAxisRotation(const Eigen::Quaterniond& q, int axis, double half_cos, double half_sin) {
  const int b = (axis + 1) % 3, d = (axis + 2) % 3;
  Eigen::Quaterniond r;
  r.w() = half_cos * q.w() - half_sin * q.vec()[axis];
  r.vec()[axis] = half_cos * q.vec()[axis] + half_sin * q.w();
  r.vec()[b] = half_cos * q.vec()[b] + half_sin * q.vec()[d];
  r.vec()[d] = half_cos * q.vec()[d] - half_sin * q.vec()[b];
  return r;
}

// Euler angles (degrees, channel order) -> unit quaternion R = R_c1(a1) * R_c2(a2) * R_c3(a3).
Eigen::Quaterniond eulerToQuaternion(const Eigen::Vector3d& degrees, const RotationAxes& axes);
inline Eigen::Quaterniond eulerToQuaternion(const Eigen::Vector3d& degrees, EulerOrder order) {
  return eulerToQuaternion(degrees, RotationAxes::of(order));
}

// Unit quaternion (normalised here; any sign) -> Euler angles in degrees, principal solution (see above).
// std::invalid_argument for a zero or non-finite quaternion, or malformed axes.
Eigen::Vector3d quaternionToEuler(const Eigen::Quaterniond& rotation, const RotationAxes& axes);
inline Eigen::Vector3d quaternionToEuler(const Eigen::Quaterniond& rotation, EulerOrder order) {
  return quaternionToEuler(rotation, RotationAxes::of(order));
}

// As above, but the solution nearest `previous_degrees` (the previous frame's angles, degrees).
Eigen::Vector3d quaternionToEuler(const Eigen::Quaterniond& rotation, const RotationAxes& axes,
                                  const Eigen::Vector3d& previous_degrees);
inline Eigen::Vector3d quaternionToEuler(const Eigen::Quaterniond& rotation, EulerOrder order,
                                         const Eigen::Vector3d& previous_degrees) {
  return quaternionToEuler(rotation, RotationAxes::of(order), previous_degrees);
}

// Angle between two rotations in radians, in [0, pi] (q and -q are the same rotation).
double rotationDistance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

}  // namespace motionstyle
