#pragma once
// Private to core/ik: the small fixed-size kernels of the tree solver (cleanup_frame_solver.cpp): the
// cross-product matrix, the exponential map of a rotation vector, the rotation residual with its
// Jacobian, and a 3 x 3 Cholesky with its triangular solves (Eigen's generic LLT and triangular paths
// took about a tenth of bench_ik's time on 3 x 3 blocks in perf).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace motionstyle::ik_detail {

inline Eigen::Matrix3d crossMatrix(const Eigen::Vector3d& v) {  // [v]x
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// exp of a rotation vector, as a unit quaternion.
inline Eigen::Quaterniond rotationFromVector(const Eigen::Vector3d& d) {
  const double angle = d.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1.0, 0.5 * d.x(), 0.5 * d.y(), 0.5 * d.z()).normalized();
  const double scale = std::sin(0.5 * angle) / angle;
  return Eigen::Quaterniond(std::cos(0.5 * angle), scale * d.x(), scale * d.y(), scale * d.z());
}

// Cholesky of a symmetric 3 x 3 block in place (lower triangle = L); false unless positive definite.
inline bool choleskyInPlace(Eigen::Matrix3d& a) {
  const double l00 = a(0, 0);
  if (!(l00 > 0.0)) return false;
  const double d0 = std::sqrt(l00);
  const double l10 = a(1, 0) / d0, l20 = a(2, 0) / d0;
  const double r1 = a(1, 1) - l10 * l10;
  if (!(r1 > 0.0)) return false;
  const double d1 = std::sqrt(r1);
  const double l21 = (a(2, 1) - l20 * l10) / d1;
  const double r2 = a(2, 2) - l20 * l20 - l21 * l21;
  if (!(r2 > 0.0)) return false;
  a << d0, 0.0, 0.0, l10, d1, 0.0, l20, l21, std::sqrt(r2);
  return true;
}

// x <- L^-1 x and x <- L^-T x for a lower-triangular 3 x 3 L, on a vector or on each column.
template <typename Block>
void forwardSolveInPlace(const Eigen::Matrix3d& l, Block& x) {
  x.row(0) /= l(0, 0);
  x.row(1) = (x.row(1) - l(1, 0) * x.row(0)) / l(1, 1);
  x.row(2) = (x.row(2) - l(2, 0) * x.row(0) - l(2, 1) * x.row(1)) / l(2, 2);
}

inline void backwardSolveInPlace(const Eigen::Matrix3d& l, Eigen::Vector3d& x) {
  x[2] /= l(2, 2);
  x[1] = (x[1] - l(2, 1) * x[2]) / l(1, 1);
  x[0] = (x[0] - l(1, 0) * x[1] - l(2, 0) * x[2]) / l(0, 0);
}

// r = 2 sign vec(conj(a) q) (cost_functors.h: rotationDifference) and dr/dd for q <- q exp([d]x).
struct RotationResidual {
  Eigen::Vector3d value;
  Eigen::Matrix3d jacobian;
};

inline RotationResidual rotationResidual(const Eigen::Quaterniond& a, const Eigen::Quaterniond& q) {
  const Eigen::Quaterniond e = a.conjugate() * q;
  const double sign = e.w() < 0.0 ? -1.0 : 1.0;
  return {2.0 * sign * e.vec(), sign * (e.w() * Eigen::Matrix3d::Identity() + crossMatrix(e.vec()))};
}

inline Eigen::Vector3d rotationDifference(const Eigen::Quaterniond& a, const Eigen::Quaterniond& q) {
  const Eigen::Quaterniond e = a.conjugate() * q;
  return (e.w() < 0.0 ? -2.0 : 2.0) * e.vec();
}

}  // namespace motionstyle::ik_detail
