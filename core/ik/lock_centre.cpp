#include "ik/lock_centre.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "features/signal_filters.h"

namespace motionstyle {
namespace {

FloorCircle throughTwo(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return {0.5 * (a + b), 0.5 * (a - b).norm()};
}

// The circumcircle of three coplanar points; collinear points: the circle over the farthest pair.
FloorCircle throughThree(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, normal = ab.cross(ac);
  const double area2 = normal.squaredNorm();
  if (area2 <= 1e-18 * ab.squaredNorm() * ac.squaredNorm()) {
    FloorCircle best = throughTwo(a, b);
    for (const FloorCircle& other : {throughTwo(a, c), throughTwo(b, c)})
      if (other.radius > best.radius) best = other;
    return best;
  }
  // c = a + (|ac|^2 (n x ab) + |ab|^2 (ac x n)) / (2 |n|^2)
  const Eigen::Vector3d offset = (ac.squaredNorm() * normal.cross(ab) + ab.squaredNorm() * ac.cross(normal)) / (2.0 * area2);
  return {a + offset, offset.norm()};
}

bool holds(const FloorCircle& circle, const Eigen::Vector3d& p) {
  return (p - circle.centre).norm() <= circle.radius * (1.0 + 1e-12) + 1e-12;
}

}  // namespace

FloorCircle smallestFloorCircle(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& up) {
  if (points.empty()) throw std::invalid_argument("smallestFloorCircle: no points");
  if (!up.allFinite() || std::abs(up.norm() - 1.0) > 1e-9)
    throw std::invalid_argument("smallestFloorCircle: up must be a unit vector");
  std::vector<Eigen::Vector3d> p;
  p.reserve(points.size());
  for (const Eigen::Vector3d& point : points) {
    if (!point.allFinite()) throw std::invalid_argument("smallestFloorCircle: a point is not finite");
    p.push_back(point - up.dot(point) * up);
  }
  std::mt19937 order(20261130u);
  std::shuffle(p.begin(), p.end(), order);
  // Welzl's incremental form: a point outside the circle of the points before it lies on the circle
  // of those points and it, and so on for a second and third boundary point.
  FloorCircle circle{p[0], 0.0};
  for (std::size_t i = 1; i < p.size(); ++i) {
    if (holds(circle, p[i])) continue;
    circle = {p[i], 0.0};
    for (std::size_t j = 0; j < i; ++j) {
      if (holds(circle, p[j])) continue;
      circle = throughTwo(p[i], p[j]);
      for (std::size_t k = 0; k < j; ++k)
        if (!holds(circle, p[k])) circle = throughThree(p[i], p[j], p[k]);
    }
  }
  return circle;
}

Eigen::Vector3d lockPoint(const std::vector<Eigen::Vector3d>& targets, const Eigen::Vector3d& up, double max_shift) {
  if (!std::isfinite(max_shift) || max_shift < 0.0)
    throw std::invalid_argument("lockPoint: max_shift must be finite and >= 0");
  const Eigen::Vector3d centre = smallestFloorCircle(targets, up).centre;  // validates
  Eigen::Vector3d median_point;
  std::vector<double> values(targets.size());
  for (int axis = 0; axis < 3; ++axis) {
    for (std::size_t i = 0; i < targets.size(); ++i) values[i] = (targets[i] - up.dot(targets[i]) * up)[axis];
    median_point[axis] = median(values);
  }
  const Eigen::Vector3d shift = centre - median_point;
  const double length = shift.norm();
  return length > max_shift ? Eigen::Vector3d(median_point + shift * (max_shift / length)) : centre;
}

}  // namespace motionstyle
