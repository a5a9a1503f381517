#include "mapping/canonical_joints.h"

#include <cctype>

namespace motionstyle {

namespace {

constexpr std::array<std::string_view, kCanonicalJointCount> kNames = {
    "Hips",
    "LeftHip", "LeftKnee", "LeftAnkle", "LeftToe",
    "RightHip", "RightKnee", "RightAnkle", "RightToe",
    "Spine", "Chest", "Neck", "Head",
    "LeftUpperArm", "LeftElbow", "LeftWrist", "LeftHandEnd",
    "RightUpperArm", "RightElbow", "RightWrist", "RightHandEnd",
};

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

}  // namespace

std::string_view canonicalJointName(CanonicalJoint joint) {
  const int i = index(joint);
  if (i < 0 || i >= kCanonicalJointCount) return "?";
  return kNames[static_cast<size_t>(i)];
}

std::string_view contactLabelName(int label) {
  static constexpr std::array<std::string_view, kContactCount> kLabelNames = {"left heel", "left toe", "right heel",
                                                                            "right toe"};
  if (label < 0 || label >= kContactCount) return "?";
  return kLabelNames[static_cast<size_t>(label)];
}

std::optional<CanonicalJoint> canonicalJointFromName(std::string_view name) {
  for (CanonicalJoint joint : kAllCanonicalJoints)
    if (equalsIgnoringCase(name, canonicalJointName(joint))) return joint;
  return std::nullopt;
}

CanonicalJoint mirrorJoint(CanonicalJoint joint) {
  for (const auto& [left, right] : kMirrorPairs) {
    if (joint == left) return right;
    if (joint == right) return left;
  }
  return joint;
}

BodySide sideOf(CanonicalJoint joint) {
  for (const auto& [left, right] : kMirrorPairs) {
    if (joint == left) return BodySide::Left;
    if (joint == right) return BodySide::Right;
  }
  return BodySide::Center;
}

std::optional<CanonicalJoint> canonicalParent(CanonicalJoint joint) {
  const int parent = kCanonicalParent[static_cast<size_t>(index(joint))];
  if (parent < 0) return std::nullopt;
  return static_cast<CanonicalJoint>(parent);
}

}  // namespace motionstyle
