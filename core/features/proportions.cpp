#include "features/proportions.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "features/root_path.h"
#include "features/signal_filters.h"

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

namespace {

// w per contact label and frame: 1 on a contact frame, 1 - k / (ramp + 1) k frames away (k <= ramp).
Eigen::MatrixXd contactWeights(const Eigen::MatrixXd& contacts) {
  const Eigen::Index frames = contacts.cols();
  Eigen::MatrixXd weight = Eigen::MatrixXd::Zero(contacts.rows(), frames);
  for (Eigen::Index label = 0; label < contacts.rows(); ++label)
    for (Eigen::Index s = 0; s < frames; ++s) {
      if (contacts(label, s) < 0.5) continue;
      for (Eigen::Index t = std::max<Eigen::Index>(0, s - kKeptFootRampFrames);
           t <= std::min<Eigen::Index>(frames - 1, s + kKeptFootRampFrames); ++t)
        weight(label, t) = std::max(weight(label, t), 1.0 - static_cast<double>(std::abs(t - s)) / (kKeptFootRampFrames + 1));
    }
  return weight;
}

// The knee of a leg with hip joint h, thigh l1 and shin l2 whose ankle is at a, on the side of `pole`
// (the plane through h, a and pole). False when a is at the hip or the pole on the line through both.
bool kneeFor(const Eigen::Vector3d& h, const Eigen::Vector3d& a, const Eigen::Vector3d& pole, double l1, double l2,
             Eigen::Vector3d& knee) {
  const double d = (a - h).norm();
  if (d < kMinimumBoneLengthCm) return false;
  const Eigen::Vector3d u = (a - h) / d;
  Eigen::Vector3d v = (pole - h) - (pole - h).dot(u) * u;
  if (v.norm() < kMinimumBoneLengthCm) return false;
  v.normalize();
  const double along = (l1 * l1 - l2 * l2 + d * d) / (2.0 * d);
  knee = h + along * u + std::sqrt(std::max(0.0, l1 * l1 - along * along)) * v;
  return true;
}

// Per frame, the floor place (x, z) of the stance of contact `label` the frame lies in or ramps to
// (kKeptFootRampFrames, the nearer stance), or none: the median of the joint's world places over the
// stance's contact frames, for a stance whose places all lie within kLockableSpreadCm of it (further,
// the style moved the step: no stance to keep). world: the joint's place per frame.
std::vector<std::optional<Eigen::Vector2d>> stancePlaces(const Eigen::MatrixXd& contacts, int label,
                                                        const std::vector<Eigen::Vector2d>& world) {
  const Eigen::Index frames = contacts.cols();
  std::vector<std::optional<Eigen::Vector2d>> stance(static_cast<std::size_t>(frames));
  std::vector<Eigen::Index> distance(stance.size(), frames + 1);
  for (Eigen::Index first = 0; first < frames;) {
    if (contacts(label, first) < 0.5) {
      ++first;
      continue;
    }
    Eigen::Index end = first;
    while (end < frames && contacts(label, end) >= 0.5) ++end;
    Eigen::Vector2d place;  // the median of each axis
    for (int axis = 0; axis < 2; ++axis) {
      std::vector<double> along;
      for (Eigen::Index f = first; f < end; ++f) along.push_back(world[static_cast<std::size_t>(f)][axis]);
      place[axis] = median(std::move(along));
    }
    double spread = 0.0;
    for (Eigen::Index f = first; f < end; ++f) spread = std::max(spread, (world[static_cast<std::size_t>(f)] - place).norm());
    if (spread <= kLockableSpreadCm)
      for (Eigen::Index f = std::max<Eigen::Index>(0, first - kKeptFootRampFrames);
           f < std::min<Eigen::Index>(frames, end + kKeptFootRampFrames); ++f) {
        const Eigen::Index away = f < first ? first - f : f >= end ? f - end + 1 : 0;
        const auto i = static_cast<std::size_t>(f);
        if (away < distance[i]) {
          distance[i] = away;
          stance[i] = place;
        }
      }
    first = end;
  }
  return stance;
}

// A joint's place on the floor in its frame's root frame (`root`), pulled to within kKeptFootRadiusCm of
// its stance's place: `world`, its place on the floor, when it has a stance and strays further; `joint`
// (root-frame features) unchanged, when it has no stance or lies within reach of it.
Eigen::Vector2d keptPlace(const RootFrame& root, const std::optional<Eigen::Vector2d>& stance,
                          const Eigen::Vector2d& world, const Eigen::Vector3d& joint) {
  if (!stance || (world - *stance).norm() <= kKeptFootRadiusCm) return {joint.x(), joint.z()};
  const Eigen::Vector2d off = world - *stance;
  return root.toRootFrame(*stance + off * (kKeptFootRadiusCm / off.norm()));
}

// The foot's direction d (unit, or zero) from an ankle at height `ankle_y`, turned up about the ankle by
// share w toward the direction of the same heading whose toe, `foot` cm along it, stands at `floor`;
// d itself where its toe already stands there or higher, or it has no heading.
Eigen::Vector3d footOverFloor(const Eigen::Vector3d& d, double ankle_y, double foot, double floor, double w) {
  const Eigen::Vector2d heading(d.x(), d.z());
  if (ankle_y + foot * d.y() >= floor || heading.norm() < 1e-6 || foot < kMinimumBoneLengthCm) return d;
  const double up = std::clamp((floor - ankle_y) / foot, -1.0, 1.0);
  const Eigen::Vector2d along = heading.normalized() * std::sqrt(1.0 - up * up);
  const Eigen::Vector3d over(along.x(), up, along.y());
  const Eigen::Vector3d turned = d + w * (over - d);
  return turned.norm() >= 1e-9 ? Eigen::Vector3d(turned.normalized()) : d;
}

}  // namespace

void enforceBoneLengths(Eigen::MatrixXd& features, const Proportions& proportions, const Eigen::MatrixXd& contacts,
                        double planted_toe_height) {
  if (contacts.size() > 0 && (contacts.rows() != kContactCount || contacts.cols() != features.cols()))
    throw std::invalid_argument("enforceBoneLengths: the contacts must be 4 x the features' frames");
  const Eigen::MatrixXd before = features;
  enforceBoneLengths(features, proportions);
  if (contacts.size() == 0) return;
  const Eigen::MatrixXd weight = contactWeights(contacts);
  const Eigen::Index frames = features.cols();
  const std::vector<RootFrame> roots = rootFrames(before);  // the root path, root_path.h
  for (const bool left : {true, false}) {
    const int hip = index(left ? C::LeftHip : C::RightHip), knee = hip + 1, ankle = hip + 2, toe = hip + 3;
    const int heel_label = static_cast<int>(left ? ContactLabel::LeftHeel : ContactLabel::RightHeel);
    const int toe_label = static_cast<int>(left ? ContactLabel::LeftToe : ContactLabel::RightToe);
    const double thigh = proportions.bone_length[static_cast<std::size_t>(knee)];
    const double shin = proportions.bone_length[static_cast<std::size_t>(ankle)];
    const double foot = proportions.bone_length[static_cast<std::size_t>(toe)];
    // The heel's and toe's stances, from their world places before.
    std::vector<Eigen::Vector2d> heel_world(static_cast<std::size_t>(frames)), toe_world(heel_world.size());
    for (Eigen::Index f = 0; f < frames; ++f) {
      const RootFrame& root = roots[static_cast<std::size_t>(f)];
      heel_world[static_cast<std::size_t>(f)] = root.toWorld(before(3 * ankle, f), before(3 * ankle + 2, f));
      toe_world[static_cast<std::size_t>(f)] = root.toWorld(before(3 * toe, f), before(3 * toe + 2, f));
    }
    const auto heel_stance = stancePlaces(contacts, heel_label, heel_world);
    const auto toe_stance = stancePlaces(contacts, toe_label, toe_world);
    // Per frame: w, the foot's direction from before, and the ankle's place to keep.
    Eigen::VectorXd w(frames);
    std::vector<Eigen::Vector3d> direction(static_cast<std::size_t>(frames)), kept(static_cast<std::size_t>(frames));
    for (Eigen::Index f = 0; f < frames; ++f) {
      const auto i = static_cast<std::size_t>(f);
      w(f) = std::max(weight(heel_label, f), weight(toe_label, f));
      const Eigen::Vector3d foot_bone = jointAt(before, f, toe) - jointAt(before, f, ankle);
      const Eigen::Vector3d enforced_foot = jointAt(features, f, toe) - jointAt(features, f, ankle);
      direction[i] = foot_bone.norm() >= kMinimumBoneLengthCm       ? Eigen::Vector3d(foot_bone.normalized())
                     : enforced_foot.norm() >= kMinimumBoneLengthCm ? Eigen::Vector3d(enforced_foot.normalized())
                                                                    : Eigen::Vector3d::Zero();
      if (std::isfinite(planted_toe_height) && weight(toe_label, f) > 0.0)
        direction[i] = footOverFloor(direction[i], before(3 * ankle + 1, f), foot, planted_toe_height, weight(toe_label, f));
      // Between the ankle from before and the one that keeps the toe's place, by the toe's share; on
      // the floor, each of the two places first pulled to its stance (keptPlace).
      const double toe_share = w(f) > 0.0 ? weight(toe_label, f) / (weight(heel_label, f) + weight(toe_label, f)) : 0.0;
      kept[i] = jointAt(before, f, ankle) + toe_share * (foot_bone.norm() - foot) * direction[i];
      if (w(f) <= 0.0) continue;
      const Eigen::Vector2d heel_place = keptPlace(roots[i], heel_stance[i], heel_world[i], jointAt(before, f, ankle));
      const Eigen::Vector2d toe_place = keptPlace(roots[i], toe_stance[i], toe_world[i], jointAt(before, f, toe)) -
                                        foot * Eigen::Vector2d(direction[i].x(), direction[i].z());
      const Eigen::Vector2d place = (1.0 - toe_share) * heel_place + toe_share * toe_place;
      kept[i].x() = place.x();
      kept[i].z() = place.y();
    }
    // The height to add, w times: the kept height's difference to the enforced one, less its mean over
    // the span's contact frames (a span: consecutive frames with w > 0) where that mean is negative (the
    // enforcement raised the foot: its level is the enforced one); where it is positive (the enforcement
    // sank the foot) nothing is taken off: the span keeps its level from before too.
    Eigen::VectorXd rise = Eigen::VectorXd::Zero(frames);
    for (Eigen::Index first = 0; first < frames;) {
      if (w(first) <= 0.0) {
        ++first;
        continue;
      }
      Eigen::Index end = first;
      double sum = 0.0;
      int planted = 0;
      for (; end < frames && w(end) > 0.0; ++end) {
        rise(end) = kept[static_cast<std::size_t>(end)].y() - jointAt(features, end, ankle).y();
        if (w(end) >= 1.0) {
          sum += rise(end);
          ++planted;
        }
      }
      if (planted > 0) rise.segment(first, end - first).array() -= std::min(0.0, sum / planted);
      first = end;
    }
    // Reachable ankles: from just past the folded leg to just short of the straight one.
    const double nearest = std::abs(thigh - shin) + 1e-3, furthest = (thigh + shin) * (1.0 - 1e-6);
    for (Eigen::Index f = 0; f < frames; ++f) {
      if (w(f) <= 0.0) continue;
      const auto i = static_cast<std::size_t>(f);
      const Eigen::Vector3d h = jointAt(features, f, hip);
      Eigen::Vector3d a = jointAt(features, f, ankle);
      a.x() += w(f) * (kept[i].x() - a.x());
      a.z() += w(f) * (kept[i].z() - a.z());
      a.y() += w(f) * rise(f);
      const double reach = (a - h).norm();
      if (reach < nearest) continue;
      if (reach > furthest) a = h + (a - h) * (furthest / reach);
      Eigen::Vector3d k;
      if (!kneeFor(h, a, jointAt(features, f, knee), thigh, shin, k)) continue;
      features.col(f).segment<3>(3 * knee) = k;
      features.col(f).segment<3>(3 * ankle) = a;
      features.col(f).segment<3>(3 * toe) = a + foot * direction[i];
    }
    // A toe the style swings under its planted height where it is not planted (the zombie with angry:
    // 8 cm under the floor as it drags): the foot turned up about its ankle until the toe stands there.
    if (!std::isfinite(planted_toe_height)) continue;
    for (Eigen::Index f = 0; f < frames; ++f) {
      if (weight(toe_label, f) > 0.0) continue;
      const Eigen::Vector3d a = jointAt(features, f, ankle);
      const Eigen::Vector3d bone = jointAt(features, f, toe) - a;
      if (bone.norm() < kMinimumBoneLengthCm) continue;
      features.col(f).segment<3>(3 * toe) =
          a + bone.norm() * footOverFloor(bone.normalized(), a.y(), bone.norm(), planted_toe_height, 1.0);
    }
  }
}

}  // namespace motionstyle
