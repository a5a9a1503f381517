#include "gait_signature.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "features/feature_layout.h"

namespace motionstyle::bench {
namespace {

// Differences smaller than these say nothing about style: each figure's standard deviation over ten
// dataset-2 walks of one style, the median over seven styles (normal, elderly, exhausted, feminine,
// youthful, masculine, active), rounded (cm, or rad for the lean and the joint angles).
constexpr GaitSignature kResolution = {0.5, 0.5, 0.015, 0.03, 0.035, 0.6, 0.6, 0.7, 1.0};

Eigen::Vector3d joint(const Eigen::MatrixXd& features, CanonicalJoint j, Eigen::Index frame) {
  return features.block<3, 1>(3 * index(j), frame);
}

// The angle at `middle` between the bones to `a` and to `b`, rad.
double angleAt(const Eigen::MatrixXd& f, CanonicalJoint a, CanonicalJoint middle, CanonicalJoint b, Eigen::Index t) {
  const Eigen::Vector3d u = joint(f, a, t) - joint(f, middle, t), v = joint(f, b, t) - joint(f, middle, t);
  const double norms = u.norm() * v.norm();
  return norms > 0 ? std::acos(std::clamp(u.dot(v) / norms, -1.0, 1.0)) : 0.0;
}

double standardDeviation(const Eigen::VectorXd& values) {
  return std::sqrt((values.array() - values.mean()).square().mean());
}

}  // namespace

GaitSignature gaitSignature(const Eigen::MatrixXd& f) {
  if (f.rows() != kFeatureCount || f.cols() < 1)
    throw std::invalid_argument("gaitSignature: expected 66 x frames features (frames >= 1)");
  using J = CanonicalJoint;
  const Eigen::Index frames = f.cols();
  GaitSignature mean{};  // each figure's sum over the frames, then its mean; the arm swing apart
  Eigen::VectorXd left_swing(frames), right_swing(frames);
  for (Eigen::Index t = 0; t < frames; ++t) {
    const Eigen::Vector3d hips = joint(f, J::Hips, t), trunk = joint(f, J::Neck, t) - hips;
    const Eigen::Vector3d left_hand = joint(f, J::LeftWrist, t) - hips, right_hand = joint(f, J::RightWrist, t) - hips;
    mean[kHeadHeight] += joint(f, J::Head, t).y();
    mean[kHipsHeight] += hips.y();
    mean[kTrunkLean] += std::atan2(trunk.z(), trunk.y());
    mean[kKneeAngle] += 0.5 * (angleAt(f, J::LeftHip, J::LeftKnee, J::LeftAnkle, t) +
                               angleAt(f, J::RightHip, J::RightKnee, J::RightAnkle, t));
    mean[kElbowAngle] += 0.5 * (angleAt(f, J::LeftUpperArm, J::LeftElbow, J::LeftWrist, t) +
                                angleAt(f, J::RightUpperArm, J::RightElbow, J::RightWrist, t));
    mean[kHandHeight] += 0.5 * (left_hand.y() + right_hand.y());
    mean[kStanceWidth] += std::abs(joint(f, J::LeftAnkle, t).x() - joint(f, J::RightAnkle, t).x());
    mean[kHandSpread] += 0.5 * (std::abs(left_hand.x()) + std::abs(right_hand.x()));
    left_swing(t) = left_hand.z();
    right_swing(t) = right_hand.z();
  }
  for (double& figure : mean) figure /= static_cast<double>(frames);
  mean[kArmSwing] = 0.5 * (standardDeviation(left_swing) + standardDeviation(right_swing));
  return mean;
}

double gaitSignatureShare(const GaitSignature& content, const GaitSignature& style, const GaitSignature& output) {
  double sum = 0.0;
  int counted = 0;
  for (int k = 0; k < kGaitFigureCount; ++k) {
    const double difference = style[k] - content[k];
    if (std::abs(difference) <= kResolution[k]) continue;
    sum += std::clamp((output[k] - content[k]) / difference, -1.0, 2.0);
    ++counted;
  }
  return counted > 0 ? sum / counted : 0.0;
}

}  // namespace motionstyle::bench
