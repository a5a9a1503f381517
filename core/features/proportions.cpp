#include "features/proportions.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace motionstyle {
namespace {

using C = CanonicalJoint;

Eigen::Vector3d jointAt(const Eigen::MatrixXd& features, Eigen::Index frame, int joint) {
  return features.col(frame).segment<3>(3 * joint);
}

}  // namespace

double Proportions::legLength() const {
  return 0.5 * (bone_length[index(C::LeftKnee)] + bone_length[index(C::LeftAnkle)] +
                bone_length[index(C::RightKnee)] + bone_length[index(C::RightAnkle)]);
}

void Proportions::validate() const {
  for (int c = 0; c < kCanonicalJointCount; ++c)
    if (!std::isfinite(bone_length[static_cast<std::size_t>(c)]) || bone_length[static_cast<std::size_t>(c)] < 0.0)
      throw std::invalid_argument("proportions: bone " + std::to_string(c) + " has no finite, non-negative length");
  if (!(legLength() > kMinimumBoneLengthCm)) throw std::invalid_argument("proportions: the legs have no length");
}

const Proportions& referenceProportions() {
  static const Proportions reference{{
      0.0,                            // Hips
      6.80, 38.89, 40.78, 11.70,      // left hip, knee, ankle, toe
      6.80, 38.89, 40.78, 11.70,      // right leg
      15.66, 8.95, 16.30, 6.43,       // spine, chest, neck, head
      16.68, 24.21, 22.18, 4.98,      // left upper arm (from the chest), elbow, wrist, hand end
      16.12, 24.21, 22.18, 4.98,      // right arm
  }};
  return reference;
}

Proportions measureProportions(const Eigen::MatrixXd& features) {
  if (features.rows() != kFeatureCount || features.cols() < 1)
    throw std::invalid_argument("measureProportions: features must be 66 x frames with at least one frame");
  Proportions proportions;
  for (int c = 1; c < kCanonicalJointCount; ++c) {
    const int parent = kCanonicalParent[static_cast<std::size_t>(c)];
    proportions.bone_length[static_cast<std::size_t>(c)] =
        (features.middleRows<3>(3 * c) - features.middleRows<3>(3 * parent)).colwise().norm().mean();
  }
  return proportions;
}

void retargetFeatures(Eigen::MatrixXd& features, const Proportions& from, const Proportions& to) {
  if (features.rows() != kFeatureCount)
    throw std::invalid_argument("retargetFeatures: features must have 66 rows, got " + std::to_string(features.rows()));
  from.validate();
  to.validate();
  if (from.bone_length == to.bone_length) return;  // exactly the identity, zero-length bones included
  const double leg_ratio = to.legLength() / from.legLength();
  std::array<Eigen::Vector3d, kCanonicalJointCount> source, target;
  for (Eigen::Index f = 0; f < features.cols(); ++f) {
    for (int c = 0; c < kCanonicalJointCount; ++c) source[static_cast<std::size_t>(c)] = jointAt(features, f, c);
    target[0] = leg_ratio * source[0];
    for (int c = 1; c < kCanonicalJointCount; ++c) {
      const auto joint = static_cast<std::size_t>(c);
      const auto parent = static_cast<std::size_t>(kCanonicalParent[joint]);
      const double from_length = from.bone_length[joint];
      if (from_length < kMinimumBoneLengthCm && to.bone_length[joint] < kMinimumBoneLengthCm) {
        target[joint] = target[parent] + (source[joint] - source[parent]);  // no length either side: as is
        continue;
      }
      if (from_length >= kMinimumBoneLengthCm) {
        target[joint] = target[parent] + (source[joint] - source[parent]) * (to.bone_length[joint] / from_length);
        continue;
      }
      // No direction in the source: lay the bone along its parent bone (up from the hips).
      Eigen::Vector3d direction = Eigen::Vector3d::UnitY();
      if (parent != 0) {
        const Eigen::Vector3d parent_bone =
            target[parent] - target[static_cast<std::size_t>(kCanonicalParent[parent])];
        if (parent_bone.norm() >= kMinimumBoneLengthCm) direction = parent_bone.normalized();
      }
      target[joint] = target[parent] + to.bone_length[joint] * direction;
    }
    for (int c = 0; c < kCanonicalJointCount; ++c)
      features.col(f).segment<3>(3 * c) = target[static_cast<std::size_t>(c)];
    features(kSidewaysVelocity, f) *= leg_ratio;
    features(kForwardVelocity, f) *= leg_ratio;
  }
}

void enforceBoneLengths(Eigen::MatrixXd& features, const Proportions& proportions) {
  if (features.rows() != kFeatureCount)
    throw std::invalid_argument("enforceBoneLengths: features must have 66 rows, got " + std::to_string(features.rows()));
  proportions.validate();
  std::array<Eigen::Vector3d, kCanonicalJointCount> source, target;
  for (Eigen::Index f = 0; f < features.cols(); ++f) {
    for (int c = 0; c < kCanonicalJointCount; ++c) source[static_cast<std::size_t>(c)] = jointAt(features, f, c);
    target[0] = source[0];
    for (int c = 1; c < kCanonicalJointCount; ++c) {
      const auto joint = static_cast<std::size_t>(c);
      const auto parent = static_cast<std::size_t>(kCanonicalParent[joint]);
      const Eigen::Vector3d bone = source[joint] - source[parent];
      Eigen::Vector3d direction = Eigen::Vector3d::UnitY();
      if (bone.norm() >= kMinimumBoneLengthCm) {
        direction = bone.normalized();
      } else if (parent != 0) {
        const Eigen::Vector3d parent_bone = target[parent] - target[static_cast<std::size_t>(kCanonicalParent[parent])];
        if (parent_bone.norm() >= kMinimumBoneLengthCm) direction = parent_bone.normalized();
      }
      target[joint] = target[parent] + proportions.bone_length[joint] * direction;
    }
    for (int c = 0; c < kCanonicalJointCount; ++c) features.col(f).segment<3>(3 * c) = target[static_cast<std::size_t>(c)];
  }
}

}  // namespace motionstyle
