#pragma once
// Where a contact lock holds its joint on the floor plane: the stance targets' median, moved toward the
// centre of their smallest circle (the minimax point) by at most a bound.
//
//   c* = argmin_c max_t |P (p_t - c)|,   P = I - up up^T (the floor plane)
//   lock = m + min(1, d / |c* - m|) (c* - m),   m = the targets' median per axis on the plane, d the bound
//
// Why: the clean-up's worst residual in a stance is the farthest target from its lock. A network that
// slides a foot through a long stance puts the median near the still part and the farthest target a
// whole slide away; the minimax point halves that (other studios over 8 cm 13 -> 9 of 63). Why bounded:
// where a stance holds a real step (a contact the user extended over a walking foot), the minimax point
// lies mid-step and would move the stance's still part off its targets; the shifts that halve a slide
// were all under 3 cm (docs/decisions.md, "The lock at the stance's minimax point").

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

// The lock point above (on the plane through the origin) for a stance's targets, in their units;
// max_shift >= 0 in the same units (0: the median). Throws as smallestFloorCircle, and
// std::invalid_argument for a negative or non-finite max_shift.
Eigen::Vector3d lockPoint(const std::vector<Eigen::Vector3d>& targets, const Eigen::Vector3d& up, double max_shift);

}  // namespace motionstyle
