#pragma once
// Where a contact lock holds its joint on the floor plane: the centre of the smallest circle that
// holds every target position of the stance (the minimax point).
//
//   c* = argmin_c max_t |P (p_t - c)|,   P = I - up up^T (the floor plane)
//
// Why the minimax point and not the median: the clean-up's worst residual in a stance is the farthest
// target from its lock, and a network that slides a foot through a long stance puts the median near
// one end of the slide (the still part), the farthest target a whole slide away; the minimax point
// halves that (docs/decisions.md, "The lock at the stance's minimax point").

#include <Eigen/Core>
#include <vector>

namespace motionstyle {

struct FloorCircle {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  // on the plane through the origin, normal `up`
  double radius = 0.0;
};

// The smallest circle holding the points projected on the plane normal to `up` (a unit vector), by
// Welzl's algorithm (expected linear time; the points are visited in a fixed pseudo-random order, so
// the result is reproducible). Exact up to rounding. Throws std::invalid_argument for no points, a
// non-finite point or an `up` that is not of unit length.
FloorCircle smallestFloorCircle(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& up);

}  // namespace motionstyle
