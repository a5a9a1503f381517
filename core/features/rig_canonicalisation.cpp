#include "features/rig_canonicalisation.h"

#include <stdexcept>
#include <string>

#include "features/proportions.h"

namespace motionstyle {
namespace {

using C = CanonicalJoint;

Eigen::Vector3d unit(double x, double y, double z) { return Eigen::Vector3d(x, y, z).normalized(); }

}  // namespace

const std::array<Eigen::Vector3d, kCanonicalJointCount>& referenceGirdleDirections() {
  static const std::array<Eigen::Vector3d, kCanonicalJointCount> directions = [] {
    std::array<Eigen::Vector3d, kCanonicalJointCount> d;
    d.fill(Eigen::Vector3d::Zero());
    // Left measured (0.9372, -0.3489, 0.0018), right (-0.9560, -0.2928, 0.0181): averaged mirror-wise.
    d[static_cast<std::size_t>(index(C::LeftHip))] = unit(0.9466, -0.3209, 0.0100);
    d[static_cast<std::size_t>(index(C::RightHip))] = unit(-0.9466, -0.3209, 0.0100);
    // (0.5865, 0.8095, 0.0285) and (-0.6302, 0.7761, 0.0215).
    d[static_cast<std::size_t>(index(C::LeftUpperArm))] = unit(0.6084, 0.7928, 0.0250);
    d[static_cast<std::size_t>(index(C::RightUpperArm))] = unit(-0.6084, 0.7928, 0.0250);
    // (0.1421, -0.8662, 0.4792) and (-0.1629, -0.8720, 0.4617).
    d[static_cast<std::size_t>(index(C::LeftToe))] = unit(0.1525, -0.8691, 0.4705);
    d[static_cast<std::size_t>(index(C::RightToe))] = unit(-0.1525, -0.8691, 0.4705);
    return d;
  }();
  return directions;
}

RigCorrection::RigCorrection() { rotation.fill(Eigen::Quaterniond::Identity()); }

bool RigCorrection::isIdentity() const {
  for (const Eigen::Quaterniond& q : rotation)
    if (!q.coeffs().isApprox(Eigen::Quaterniond::Identity().coeffs(), 0.0)) return false;
  return true;
}

RigCorrection measureRigCorrection(const Eigen::MatrixXd& features) {
  if (features.rows() != kFeatureCount || features.cols() < 1)
    throw std::invalid_argument("measureRigCorrection: features must be 66 x frames with at least one frame");
  RigCorrection correction;
  for (C bone : kGirdleBones) {
    const int c = index(bone), parent = kCanonicalParent[static_cast<std::size_t>(c)];
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (Eigen::Index f = 0; f < features.cols(); ++f) {
      const Eigen::Vector3d d = features.col(f).segment<3>(3 * c) - features.col(f).segment<3>(3 * parent);
      if (d.norm() >= kMinimumBoneLengthCm) sum += d.normalized();
    }
    if (sum.norm() < 1e-9) continue;  // no direction to correct
    correction.rotation[static_cast<std::size_t>(c)] =
        Eigen::Quaterniond::FromTwoVectors(sum.normalized(), referenceGirdleDirections()[static_cast<std::size_t>(c)]);
  }
  return correction;
}

void applyRigCorrection(Eigen::MatrixXd& features, const RigCorrection& correction, bool inverse) {
  if (features.rows() != kFeatureCount)
    throw std::invalid_argument("applyRigCorrection: features must have 66 rows, got " + std::to_string(features.rows()));
  if (correction.isIdentity()) return;
  std::array<Eigen::Matrix3d, kCanonicalJointCount> turn;
  for (int c = 0; c < kCanonicalJointCount; ++c) {
    const Eigen::Matrix3d r = correction.rotation[static_cast<std::size_t>(c)].normalized().toRotationMatrix();
    turn[static_cast<std::size_t>(c)] = inverse ? r.transpose() : r;
  }
  std::array<Eigen::Vector3d, kCanonicalJointCount> source, target;
  for (Eigen::Index f = 0; f < features.cols(); ++f) {
    for (int c = 0; c < kCanonicalJointCount; ++c) source[static_cast<std::size_t>(c)] = features.col(f).segment<3>(3 * c);
    target[0] = source[0];
    for (int c = 1; c < kCanonicalJointCount; ++c) {
      const auto joint = static_cast<std::size_t>(c);
      const auto parent = static_cast<std::size_t>(kCanonicalParent[joint]);
      target[joint] = target[parent] + turn[joint] * (source[joint] - source[parent]);
    }
    for (int c = 0; c < kCanonicalJointCount; ++c) features.col(f).segment<3>(3 * c) = target[static_cast<std::size_t>(c)];
  }
}

}  // namespace motionstyle
