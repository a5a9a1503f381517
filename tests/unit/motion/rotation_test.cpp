// Euler <-> quaternion (rotation.h): the BVH convention checked by hand and against an independent
// construction, exact round trips for every order (also at and near gimbal lock), continuity.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>

#include "motion/rotation.h"
#include "motion_test_helpers.h"

namespace motionstyle {
namespace {

using test::C;

constexpr double kRadians = std::numbers::pi / 180.0;

// Independent construction: Eigen AngleAxis products R = R_c1(a1) R_c2(a2) R_c3(a3).
Eigen::Matrix3d referenceMatrix(const Eigen::Vector3d& degrees, const RotationAxes& axes) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  for (int n = 0; n < axes.count; ++n)
    r = r * Eigen::AngleAxisd(degrees[n] * kRadians, Eigen::Vector3d::Unit(axes.axis[static_cast<size_t>(n)])).toRotationMatrix();
  return r;
}

double angleDifference(double a, double b) { return std::abs(std::remainder(a - b, 360.0)); }

// ---- invalid input -------------------------------------------------------------------------------

TEST(RotationInvalid, RejectsRepeatedRotationChannels) {
  EXPECT_THROW(RotationAxes::of(std::vector<ChannelType>{C::Xrotation, C::Yrotation, C::Xrotation}), std::invalid_argument);
}

TEST(RotationInvalid, RejectsMalformedAxes) {
  RotationAxes too_many;
  too_many.count = 4;
  EXPECT_THROW(eulerToQuaternion(Eigen::Vector3d::Zero(), too_many), std::invalid_argument);
  EXPECT_THROW(quaternionToEuler(Eigen::Quaterniond::Identity(), too_many), std::invalid_argument);
  RotationAxes repeated{{1, 1, 0}, 2};
  EXPECT_THROW(eulerToQuaternion(Eigen::Vector3d::Zero(), repeated), std::invalid_argument);
  RotationAxes out_of_range{{0, 3, 1}, 3};
  EXPECT_THROW(quaternionToEuler(Eigen::Quaterniond::Identity(), out_of_range, Eigen::Vector3d::Zero()),
               std::invalid_argument);
}

TEST(RotationInvalid, RejectsZeroAndNonFiniteQuaternions) {
  EXPECT_THROW(quaternionToEuler(Eigen::Quaterniond(0, 0, 0, 0), EulerOrder::XYZ), std::invalid_argument);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(quaternionToEuler(Eigen::Quaterniond(nan, 0, 0, 0), EulerOrder::ZXY, Eigen::Vector3d::Zero()),
               std::invalid_argument);
  EXPECT_THROW(quaternionToEuler(Eigen::Quaterniond(std::numeric_limits<double>::infinity(), 0, 0, 0),
                                 RotationAxes{{0, 0, 0}, 1}),
               std::invalid_argument);
}

TEST(RotationInvalid, HalfAngleSinCosRejectsSpansOfDifferentSizes) {
  std::vector<double> degrees(3, 10.0), sines(3), cosines(2);
  EXPECT_THROW(halfAngleSinCos(degrees, sines, cosines), std::invalid_argument);
  EXPECT_THROW(halfAngleSinCos(degrees, cosines, sines), std::invalid_argument);
}

// ---- convention ----------------------------------------------------------------------------------

TEST(RotationConvention, ChannelsComposeInFileOrderRightHanded) {
  // Right-handed: +90 about Z takes X to Y.
  EXPECT_TRUE((eulerToQuaternion({90, 0, 0}, EulerOrder::ZXY) * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  // XYZ (90, 90, 0) is Rx(90) * Ry(90): Ry takes Z to X first, Rx keeps X.
  EXPECT_TRUE((eulerToQuaternion({90, 90, 0}, EulerOrder::XYZ) * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX(), 1e-12));
  // YXZ (90, 90, 0) is Ry(90) * Rx(90): Rx takes Z to -Y first, Ry keeps -Y.
  EXPECT_TRUE((eulerToQuaternion({90, 90, 0}, EulerOrder::YXZ) * Eigen::Vector3d::UnitZ()).isApprox(-Eigen::Vector3d::UnitY(), 1e-12));
}

TEST(RotationConvention, AxesFollowTheRotationChannelsOnly) {
  const RotationAxes axes = RotationAxes::of(std::vector<ChannelType>{C::Xposition, C::Zrotation, C::Yposition, C::Xrotation, C::Zposition, C::Yrotation});
  EXPECT_EQ(axes.count, 3);
  EXPECT_EQ(axes.axis, (std::array<int, 3>{2, 0, 1}));
  EXPECT_EQ(RotationAxes::of(std::vector<ChannelType>{C::Xposition}).count, 0);
  for (EulerOrder order : kAllEulerOrders) {
    const RotationAxes from_order = RotationAxes::of(order);
    std::string name;
    for (int n = 0; n < 3; ++n) name += static_cast<char>('X' + from_order.axis[static_cast<size_t>(n)]);
    EXPECT_EQ(name, eulerOrderName(order));
  }
}

TEST(RotationConvention, MatchesAnIndependentConstructionForEveryOrder) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-400.0, 400.0);
  for (EulerOrder order : kAllEulerOrders) {
    for (int trial = 0; trial < 200; ++trial) {
      const Eigen::Vector3d degrees(angle(rng), angle(rng), angle(rng));
      const Eigen::Matrix3d expected = referenceMatrix(degrees, RotationAxes::of(order));
      const Eigen::Matrix3d actual = eulerToQuaternion(degrees, order).toRotationMatrix();
      ASSERT_LT((actual - expected).cwiseAbs().maxCoeff(), 1e-12) << eulerOrderName(order) << " " << degrees.transpose();
    }
  }
}

TEST(RotationConvention, PartialAxesMatchAnIndependentConstruction) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> angle(-180.0, 180.0);
  for (int first = 0; first < 3; ++first) {
    for (int second = 0; second < 3; ++second) {
      const RotationAxes one{{first, 0, 0}, 1};
      const RotationAxes two{{first, second, 0}, 2};
      const Eigen::Vector3d degrees(angle(rng), angle(rng), 1234.0);  // the unused entry must be ignored
      EXPECT_LT((eulerToQuaternion(degrees, one).toRotationMatrix() - referenceMatrix(degrees, one)).norm(), 1e-12);
      if (first == second) continue;
      EXPECT_LT((eulerToQuaternion(degrees, two).toRotationMatrix() - referenceMatrix(degrees, two)).norm(), 1e-12);
    }
  }
  EXPECT_TRUE(eulerToQuaternion({10, 20, 30}, RotationAxes{}).isApprox(Eigen::Quaterniond::Identity()));
}

// ---- round trips ---------------------------------------------------------------------------------

TEST(RotationRoundTrip, PrincipalSolutionReproducesRotationAndAnglesForEveryOrder) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> outer(-179.9, 179.9);
  std::uniform_real_distribution<double> middle(-89.9, 89.9);
  for (EulerOrder order : kAllEulerOrders) {
    for (int trial = 0; trial < 500; ++trial) {
      const Eigen::Vector3d degrees(outer(rng), middle(rng), outer(rng));
      const Eigen::Quaterniond q = eulerToQuaternion(degrees, order);
      const Eigen::Vector3d back = quaternionToEuler(q, order);
      ASSERT_LT(rotationDistance(eulerToQuaternion(back, order), q), 1e-12) << eulerOrderName(order);
      // Inside the principal ranges the solution is unique, so the angles themselves come back.
      ASSERT_LT((back - degrees).cwiseAbs().maxCoeff(), 1e-9) << eulerOrderName(order) << " " << degrees.transpose();
      ASSERT_LE(std::abs(back[1]), 90.0);
      ASSERT_LE(std::abs(back[0]), 180.0);
      ASSERT_LE(std::abs(back[2]), 180.0);
    }
  }
}

TEST(RotationRoundTrip, SignAndScaleOfTheQuaternionDoNotMatter) {
  const Eigen::Quaterniond q = eulerToQuaternion({30, -40, 150}, EulerOrder::ZYX);
  const Eigen::Quaterniond negated(-q.w(), -q.x(), -q.y(), -q.z());
  const Eigen::Quaterniond scaled(3 * q.w(), 3 * q.x(), 3 * q.y(), 3 * q.z());
  EXPECT_LT((quaternionToEuler(negated, EulerOrder::ZYX) - Eigen::Vector3d(30, -40, 150)).norm(), 1e-9);
  EXPECT_LT((quaternionToEuler(scaled, EulerOrder::ZYX) - Eigen::Vector3d(30, -40, 150)).norm(), 1e-9);
}

TEST(RotationRoundTrip, NearestSolutionRecoversAnglesOutsideThePrincipalRanges) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> angle(-500.0, 500.0);
  std::uniform_real_distribution<double> nudge(-20.0, 20.0);
  for (EulerOrder order : kAllEulerOrders) {
    for (int trial = 0; trial < 500; ++trial) {
      const Eigen::Vector3d degrees(angle(rng), angle(rng), angle(rng));
      const double cos_middle = std::abs(std::cos(degrees[1] * kRadians));
      if (cos_middle < 0.35) continue;  // within ~20 degrees of lock a nudge can legitimately prefer the other split
      const Eigen::Vector3d previous = degrees + Eigen::Vector3d(nudge(rng), nudge(rng), nudge(rng));
      const Eigen::Vector3d back = quaternionToEuler(eulerToQuaternion(degrees, order), order, previous);
      ASSERT_LT((back - degrees).cwiseAbs().maxCoeff(), 1e-9) << eulerOrderName(order) << " " << degrees.transpose();
    }
  }
}

TEST(RotationRoundTrip, ExactAtAndNearGimbalLockForEveryOrder) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> outer(-179.0, 179.0);
  const double offsets[] = {0.0, 1e-12, 1e-9, 1e-6, 1e-3, 0.1};
  for (EulerOrder order : kAllEulerOrders) {
    for (double lock : {90.0, -90.0}) {
      for (double offset : offsets) {
        for (double sign : {1.0, -1.0}) {
          const Eigen::Vector3d degrees(outer(rng), lock + sign * offset, outer(rng));
          const Eigen::Quaterniond q = eulerToQuaternion(degrees, order);
          const Eigen::Vector3d principal = quaternionToEuler(q, order);
          ASSERT_LT(rotationDistance(eulerToQuaternion(principal, order), q), 1e-12)
              << eulerOrderName(order) << " " << degrees.transpose();
          ASSERT_LE(std::abs(principal[1]), 90.0);
          // With the true angles as the previous frame, the continuous overload stays on them: the
          // rotation exactly, the angles to the conditioning the nearly locked middle angle allows.
          // The outer angles of a nearly locked rotation are determined only to about 1e-16 / cos(b) rad.
          const Eigen::Vector3d nearest = quaternionToEuler(q, order, degrees);
          ASSERT_LT(rotationDistance(eulerToQuaternion(nearest, order), q), 1e-12)
              << eulerOrderName(order) << " " << degrees.transpose();
          const double conditioning = 1e-14 / std::abs(std::cos(degrees[1] * kRadians)) / kRadians;
          ASSERT_LT((nearest - degrees).cwiseAbs().maxCoeff(), 1e-9 + conditioning)
              << eulerOrderName(order) << " " << degrees.transpose() << " -> " << nearest.transpose();
        }
      }
    }
  }
}

TEST(RotationRoundTrip, AtExactGimbalLockTheFreeAngleIsSplitNearThePreviousFrame) {
  for (EulerOrder order : kAllEulerOrders) {
    // At b = 90 only a combination of a and c is determined: a previous frame of (a + 10, b, c + 10)
    // must get a split close to it, not the principal "everything in a" answer.
    const Eigen::Vector3d degrees(40.0, 90.0, -25.0);
    const Eigen::Quaterniond q = eulerToQuaternion(degrees, order);
    const Eigen::Vector3d previous(50.0, 89.0, -15.0);
    const Eigen::Vector3d nearest = quaternionToEuler(q, order, previous);
    EXPECT_LT(rotationDistance(eulerToQuaternion(nearest, order), q), 1e-12) << eulerOrderName(order);
    const Eigen::Vector3d principal = quaternionToEuler(q, order);
    EXPECT_NEAR(principal[2], 0.0, 1e-9) << eulerOrderName(order);
    EXPECT_LT((nearest - previous).norm(), (principal - previous).norm()) << eulerOrderName(order);
    EXPECT_LT(std::abs(nearest[0] - previous[0]), 15.0) << eulerOrderName(order) << " " << nearest.transpose();
    EXPECT_LT(std::abs(nearest[2] - previous[2]), 15.0) << eulerOrderName(order) << " " << nearest.transpose();
  }
}

// ---- continuity ----------------------------------------------------------------------------------

TEST(RotationContinuity, SequenceThroughGimbalLockAndPastHalfTurnsStaysContinuous) {
  for (EulerOrder order : kAllEulerOrders) {
    // The middle angle sweeps through +90 (to 120) while the outer ones wind past 180: the principal
    // solution flips and wraps, the nearest one follows the original smooth angles.
    Eigen::Vector3d previous = Eigen::Vector3d::Zero();
    bool first = true;
    for (int f = 0; f <= 200; ++f) {
      const Eigen::Vector3d degrees(100.0 + 1.5 * f, 60.0 + 0.3 * f, -120.0 - 1.2 * f);
      const Eigen::Quaterniond q = eulerToQuaternion(degrees, order);
      const Eigen::Vector3d decoded = first ? quaternionToEuler(q, order, degrees) : quaternionToEuler(q, order, previous);
      ASSERT_LT(rotationDistance(eulerToQuaternion(decoded, order), q), 1e-12) << eulerOrderName(order) << " frame " << f;
      // At the locked frame (f = 100, b = 90) the split of the free angle follows the previous frame
      // rather than the (unknowable) original; everywhere else the original angles come back.
      const double tolerance = f == 100 ? 2.0 : 1e-6;
      ASSERT_LT((decoded - degrees).cwiseAbs().maxCoeff(), tolerance) << eulerOrderName(order) << " frame " << f
                                                                      << ": " << decoded.transpose();
      if (!first) {
        ASSERT_LT((decoded - previous).cwiseAbs().maxCoeff(), 3.0) << eulerOrderName(order) << " frame " << f;
      }
      previous = decoded;
      first = false;
    }
  }
}

TEST(RotationContinuity, PrincipalSolutionWrapsWhereTheNearestDoesNot) {
  // The property the `previous` overload exists for, shown on the case that defeats the principal one.
  const Eigen::Quaterniond q = eulerToQuaternion({190, 10, 0}, EulerOrder::XYZ);
  EXPECT_NEAR(quaternionToEuler(q, EulerOrder::XYZ)[0], -170.0, 1e-9);
  EXPECT_NEAR(quaternionToEuler(q, EulerOrder::XYZ, Eigen::Vector3d(185, 10, 0))[0], 190.0, 1e-9);
}

// ---- fewer than three axes -----------------------------------------------------------------------

TEST(RotationPartialAxes, OneAxisRoundTripsAndWrapsNearThePrevious) {
  for (int axis = 0; axis < 3; ++axis) {
    const RotationAxes one{{axis, 0, 0}, 1};
    for (double degrees : {-179.0, -90.0, 0.0, 33.3, 135.0, 180.0}) {
      const Eigen::Vector3d back = quaternionToEuler(axisRotation(axis, degrees), one);
      EXPECT_LT(angleDifference(back[0], degrees), 1e-10);
      EXPECT_EQ(back[1], 0.0);
      EXPECT_EQ(back[2], 0.0);
    }
    EXPECT_NEAR(quaternionToEuler(axisRotation(axis, 400.0), one, Eigen::Vector3d(390, 0, 0))[0], 400.0, 1e-10);
    // A swing about another axis is dropped: only the twist remains.
    const Eigen::Quaterniond with_swing = axisRotation(axis, 25.0) * axisRotation((axis + 1) % 3, 1e-4);
    EXPECT_NEAR(quaternionToEuler(with_swing, one)[0], 25.0, 1e-6);
  }
}

TEST(RotationPartialAxes, TwoAxesRoundTripIncludingMiddleAnglesBeyondNinety) {
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> angle(-179.0, 179.0);
  for (int first = 0; first < 3; ++first) {
    for (int second = 0; second < 3; ++second) {
      if (first == second) continue;
      const RotationAxes two{{first, second, 0}, 2};
      for (int trial = 0; trial < 200; ++trial) {
        const Eigen::Vector3d degrees(angle(rng), angle(rng), 0.0);  // second angle beyond +-90 too
        const Eigen::Quaterniond q = eulerToQuaternion(degrees, two);
        const Eigen::Vector3d back = quaternionToEuler(q, two);
        ASSERT_LT(rotationDistance(eulerToQuaternion(back, two), q), 1e-12) << degrees.transpose();
        ASSERT_LT(angleDifference(back[0], degrees[0]) + angleDifference(back[1], degrees[1]), 1e-8) << degrees.transpose();
        ASSERT_EQ(back[2], 0.0);
        const Eigen::Vector3d nearest = quaternionToEuler(q, two, degrees + Eigen::Vector3d(360, -360, 0));
        ASSERT_LT((nearest - degrees - Eigen::Vector3d(360, -360, 0)).cwiseAbs().maxCoeff(), 1e-8);
      }
      for (double lock : {90.0, -90.0}) {  // exact at gimbal lock too
        const Eigen::Quaterniond q = eulerToQuaternion({37.0, lock, 0.0}, two);
        const Eigen::Vector3d back = quaternionToEuler(q, two);
        EXPECT_LT(rotationDistance(eulerToQuaternion(back, two), q), 1e-12);
        EXPECT_NEAR(back[0], 37.0, 1e-6);
      }
    }
  }
}

TEST(RotationPartialAxes, NoAxesGiveNoAngles) {
  const Eigen::Vector3d back = quaternionToEuler(axisRotation(1, 30.0), RotationAxes{}, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(back, Eigen::Vector3d::Zero());
}

TEST(RotationDistance, MeasuresTheAngleBetweenRotations) {
  EXPECT_NEAR(rotationDistance(axisRotation(2, 10.0), axisRotation(2, 40.0)), 30.0 * kRadians, 1e-12);
  EXPECT_NEAR(rotationDistance(axisRotation(0, 170.0), axisRotation(0, -170.0)), 20.0 * kRadians, 1e-12);
  EXPECT_NEAR(rotationDistance(axisRotation(1, 1e-7), Eigen::Quaterniond::Identity()), 1e-7 * kRadians, 1e-20);
}

// ---- batch half angles (the localPoses fast path) -----------------------------------------------

// sin and cos of half of `degrees`, in long double with the whole turns removed exactly first.
std::pair<long double, long double> referenceHalfAngle(double degrees) {
  const long double half = std::fmod(static_cast<long double>(degrees), 720.0L) / 2.0L *
                           (3.14159265358979323846264338327950288L / 180.0L);
  return {std::sin(half), std::cos(half)};
}

TEST(HalfAngleSinCos, WithinAnUlpOfTheTrueValuesForAnyFiniteAngle) {
  std::vector<double> degrees = {0.0, -0.0, 1e-300, 90.0, -90.0, 180.0, 360.0, 540.0, -720.0, 1e17, -3e20, 1e300};
  for (int k = -64; k <= 64; ++k)  // the reduction's boundaries (half angles at multiples of 45 degrees) and beyond
    for (double nudge : {-1e-9, 0.0, 1e-9}) degrees.push_back(90.0 * k + nudge);
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> moderate(-5000.0, 5000.0), wide(-1e9, 1e9);
  for (int n = 0; n < 2000; ++n) degrees.push_back(n % 2 ? moderate(rng) : wide(rng));
  std::vector<double> sines(degrees.size()), cosines(degrees.size());
  halfAngleSinCos(degrees, sines, cosines);
  for (size_t n = 0; n < degrees.size(); ++n) {
    const auto [sine, cosine] = referenceHalfAngle(degrees[n]);
    EXPECT_NEAR(sines[n], static_cast<double>(sine), 2.5e-16) << degrees[n];
    EXPECT_NEAR(cosines[n], static_cast<double>(cosine), 2.5e-16) << degrees[n];
  }
  // Exact at whole quarter turns of the half angle, since the reduction happens in degrees (in radians,
  // cos(pi / 2) would be 6e-17).
  EXPECT_EQ(sines[5], 1.0);    // 180 degrees
  EXPECT_EQ(cosines[5], 0.0);
  EXPECT_EQ(sines[6], 0.0);    // 360
  EXPECT_EQ(cosines[6], -1.0);
  EXPECT_EQ(sines[7], -1.0);   // 540
  EXPECT_EQ(cosines[7], 0.0);
  EXPECT_EQ(cosines[8], 1.0);  // -720
}

TEST(HalfAngleSinCos, NonFiniteAnglesGiveNaN) {
  const std::vector<double> degrees = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()};
  std::vector<double> sines(2), cosines(2);
  halfAngleSinCos(degrees, sines, cosines);
  for (size_t n = 0; n < 2; ++n) {
    EXPECT_TRUE(std::isnan(sines[n]));
    EXPECT_TRUE(std::isnan(cosines[n]));
  }
}

TEST(HalfAngleSinCos, AxisRotationIsAsAccurateForAnyAngle) {
  for (const double degrees : {-250.0, 33.3, 179.0, 360.0, 1e17, -7e19}) {
    const auto [sine, cosine] = referenceHalfAngle(degrees);
    for (int axis = 0; axis < 3; ++axis) {
      const Eigen::Quaterniond q = axisRotation(axis, degrees);
      EXPECT_NEAR(q.w(), static_cast<double>(cosine), 2.5e-16) << degrees;
      EXPECT_NEAR(q.vec()[axis], static_cast<double>(sine), 2.5e-16) << degrees;
      EXPECT_EQ(q.vec()[(axis + 1) % 3], 0.0);
      EXPECT_EQ(q.vec()[(axis + 2) % 3], 0.0);
    }
  }
}

TEST(ComposeAxisRotation, EqualsTheProductWithTheAxisQuaternion) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> angle(-400.0, 400.0);
  for (int n = 0; n < 200; ++n) {
    const Eigen::Quaterniond q = eulerToQuaternion(Eigen::Vector3d(angle(rng), angle(rng), angle(rng)), EulerOrder::YZX);
    const int axis = n % 3;
    const double degrees = angle(rng);
    const Eigen::Quaterniond expected = q * axisRotation(axis, degrees);
    const Eigen::Quaterniond half = axisRotation(axis, degrees);
    const Eigen::Quaterniond composed = composeAxisRotation(q, axis, half.w(), half.vec()[axis]);
    EXPECT_LT((composed.coeffs() - expected.coeffs()).cwiseAbs().maxCoeff(), 1e-15) << "axis " << axis;
  }
}

}  // namespace
}  // namespace motionstyle
