// smallestFloorCircle and lockPoint: invalid input first, then the circle's properties (it holds every
// point, no smaller circle does, heights along `up` do not matter, it turns with the points) and the
// lock's bounded move from the median.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "ik/lock_centre.h"

namespace motionstyle {
namespace {

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitY();

Eigen::Vector3d onFloor(double x, double z, double height = 0.0) { return {x, height, z}; }

double farthest(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& centre) {
  double radius = 0.0;
  for (const Eigen::Vector3d& p : points) radius = std::max(radius, std::hypot(p.x() - centre.x(), p.z() - centre.z()));
  return radius;
}

TEST(SmallestFloorCircle, RejectsNoPointsAPointNotFiniteAndAnUpNotOfUnitLength) {
  EXPECT_THROW(smallestFloorCircle({}, kUp), std::invalid_argument);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(smallestFloorCircle({onFloor(0, 0), onFloor(nan, 1)}, kUp), std::invalid_argument);
  EXPECT_THROW(smallestFloorCircle({onFloor(0, 0)}, Eigen::Vector3d(0, 2, 0)), std::invalid_argument);
  EXPECT_THROW(smallestFloorCircle({onFloor(0, 0)}, Eigen::Vector3d(0, nan, 0)), std::invalid_argument);
}

TEST(SmallestFloorCircle, OnePointIsItsOwnCentreAndTwoMeetAtTheirMiddle) {
  const FloorCircle one = smallestFloorCircle({onFloor(3, -4, 7)}, kUp);
  EXPECT_TRUE(one.centre.isApprox(onFloor(3, -4), 1e-12));  // on the plane through the origin
  EXPECT_EQ(one.radius, 0.0);
  const FloorCircle two = smallestFloorCircle({onFloor(0, 0, 2), onFloor(10, 0, -5)}, kUp);
  EXPECT_TRUE(two.centre.isApprox(onFloor(5, 0), 1e-12));
  EXPECT_NEAR(two.radius, 5.0, 1e-12);
}

TEST(SmallestFloorCircle, AnAcuteTriangleGivesItsCircumcircleAnObtuseOneItsLongestSide) {
  const double h = std::sqrt(3.0);  // equilateral, side 2: centre at the centroid, radius 2 / sqrt(3)
  const FloorCircle acute = smallestFloorCircle({onFloor(-1, 0), onFloor(1, 0), onFloor(0, h)}, kUp);
  EXPECT_TRUE(acute.centre.isApprox(onFloor(0, h / 3), 1e-9));
  EXPECT_NEAR(acute.radius, 2.0 / h, 1e-9);
  const FloorCircle obtuse = smallestFloorCircle({onFloor(-4, 0), onFloor(4, 0), onFloor(0, 1)}, kUp);
  EXPECT_TRUE(obtuse.centre.isApprox(onFloor(0, 0), 1e-9));
  EXPECT_NEAR(obtuse.radius, 4.0, 1e-9);
  const FloorCircle collinear = smallestFloorCircle({onFloor(0, 0), onFloor(1, 1), onFloor(3, 3), onFloor(2, 2)}, kUp);
  EXPECT_TRUE(collinear.centre.isApprox(onFloor(1.5, 1.5), 1e-9));
}

// Against every circle through two or three of the points (the smallest enclosing circle is one of
// them), on random clouds of a stance's size.
TEST(SmallestFloorCircle, HoldsEveryPointAndNoSmallerCircleThroughTheirBoundaryDoes) {
  std::mt19937 random(7);
  std::normal_distribution<double> spread(0.0, 5.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Eigen::Vector3d> points;
    const int count = 3 + trial % 12;
    for (int i = 0; i < count; ++i) points.push_back(onFloor(spread(random), 0.3 * spread(random), spread(random)));
    const FloorCircle circle = smallestFloorCircle(points, kUp);
    EXPECT_LE(farthest(points, circle.centre), circle.radius + 1e-9);
    EXPECT_NEAR(circle.centre.y(), 0.0, 1e-12);
    double best = std::numeric_limits<double>::infinity();
    for (int a = 0; a < count; ++a)
      for (int b = a + 1; b < count; ++b) {
        best = std::min(best, farthest(points, 0.5 * (points[a] + points[b])));
        for (int c = b + 1; c < count; ++c) {
          const FloorCircle three = smallestFloorCircle({points[a], points[b], points[c]}, kUp);
          best = std::min(best, farthest(points, three.centre));
        }
      }
    EXPECT_LE(circle.radius, best + 1e-9) << "trial " << trial;
  }
}

TEST(SmallestFloorCircle, TurnsWithThePointsAndWorksForAZUpFloor) {
  const std::vector<Eigen::Vector3d> points = {onFloor(0, 0), onFloor(6, 1), onFloor(2, 5), onFloor(3, 2), onFloor(-1, 3)};
  const FloorCircle circle = smallestFloorCircle(points, kUp);
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.7, kUp).toRotationMatrix();
  std::vector<Eigen::Vector3d> turned;
  for (const Eigen::Vector3d& p : points) turned.push_back(turn * p);
  const FloorCircle turned_circle = smallestFloorCircle(turned, kUp);
  EXPECT_TRUE(turned_circle.centre.isApprox(turn * circle.centre, 1e-9));
  EXPECT_NEAR(turned_circle.radius, circle.radius, 1e-9);
  // The same points in a Z-up file (x, -z, y): the same circle there.
  std::vector<Eigen::Vector3d> z_up;
  for (const Eigen::Vector3d& p : points) z_up.push_back({p.x(), -p.z(), p.y() + 3.0});
  const FloorCircle z_circle = smallestFloorCircle(z_up, Eigen::Vector3d::UnitZ());
  EXPECT_TRUE(z_circle.centre.isApprox(Eigen::Vector3d(circle.centre.x(), -circle.centre.z(), 0.0), 1e-9));
  EXPECT_NEAR(z_circle.radius, circle.radius, 1e-9);
}

TEST(LockPoint, RejectsAShiftBoundThatIsNegativeOrNotFinite) {
  EXPECT_THROW(lockPoint({onFloor(0, 0)}, kUp, -1.0), std::invalid_argument);
  EXPECT_THROW(lockPoint({onFloor(0, 0)}, kUp, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(lockPoint({}, kUp, 1.0), std::invalid_argument);
}

// A foot still at the origin for seven frames, then slid 8 cm along x over three: the median is the
// still point, the minimax point 4 cm along; the lock goes from one toward the other by at most the bound.
TEST(LockPoint, MovesFromTheMedianTowardTheMinimaxPointByAtMostTheBound) {
  std::vector<Eigen::Vector3d> stance(7, onFloor(0, 0, 3.0));
  for (double x : {3.0, 6.0, 8.0}) stance.push_back(onFloor(x, 0, 3.0));
  EXPECT_TRUE(lockPoint(stance, kUp, 0.0).isApprox(onFloor(0, 0), 1e-12));
  EXPECT_TRUE(lockPoint(stance, kUp, 10.0).isApprox(onFloor(4, 0), 1e-9));
  EXPECT_TRUE(lockPoint(stance, kUp, 2.5).isApprox(onFloor(2.5, 0), 1e-9));
  EXPECT_NEAR(lockPoint(stance, kUp, 4.0).y(), 0.0, 1e-12);  // on the plane through the origin
}

}  // namespace
}  // namespace motionstyle
