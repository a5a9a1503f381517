#pragma once
// The hand-built humanoid (cm, Y-up, 90 frames at 60 fps) the clean-up's property tests run on: its
// clip, mapping, world positions, canonical targets (the clip's own: a clean input) and an input
// with a floor of the test's choosing.

#include <gtest/gtest.h>

#include "ik/cleanup.h"
#include "ik_test_support.h"

namespace motionstyle::test {

class CleanupHumanoid : public ::testing::Test {
 protected:
  static constexpr int kFrames = 90;
  Motion clip = test::makeHumanoidClip(kFrames, 60.0);
  JointMapping mapping = test::humanoidMapping(clip.skeleton);
  Eigen::MatrixXd world = worldPositions(clip);
  Eigen::MatrixXd targets = test::canonicalPositions(world, mapping);
  Eigen::MatrixXi no_contacts = Eigen::MatrixXi::Zero(kFrames, kContactCount);

  CleanupInput input(const Eigen::MatrixXd& t, const Eigen::MatrixXi& c, double floor = -50.0) const {
    return CleanupInput{clip, mapping, t, c, Eigen::Vector3d::UnitY(), floor, 1.0};
  }
  // The targets with the left wrist 30 cm further from the shoulder over frames 10-20: out of reach.
  Eigen::MatrixXd leftWristPulledAway() const {
    Eigen::MatrixXd stretched = targets;
    const int wrist = index(CanonicalJoint::LeftWrist), shoulder = index(CanonicalJoint::LeftUpperArm);
    for (int f = 10; f <= 20; ++f) {
      const Eigen::Vector3d direction =
          (stretched.block<1, 3>(f, 3 * wrist) - stretched.block<1, 3>(f, 3 * shoulder)).transpose().normalized();
      stretched.block<1, 3>(f, 3 * wrist) += 30.0 * direction.transpose();
    }
    return stretched;
  }
  static double meanDistanceCm(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    double sum = 0.0;
    for (Eigen::Index f = 0; f < a.rows(); ++f)
      for (Eigen::Index j = 0; j < a.cols() / 3; ++j) sum += (a.block<1, 3>(f, 3 * j) - b.block<1, 3>(f, 3 * j)).norm();
    return sum / static_cast<double>(a.rows() * (a.cols() / 3));
  }
};

}  // namespace motionstyle::test
