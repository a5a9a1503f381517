#pragma once
// Hand-built rigs in each naming convention the automatic mapping reads, with the joint each canonical
// joint must map to. Offsets are plausible (Y up, the character's left at +X) but the mapping never
// reads geometry except to skip zero-length connector joints, so they only matter there.

#include <Eigen/Core>
#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mapping/canonical_joints.h"
#include "mapping/joint_mapping.h"
#include "motion/skeleton.h"

namespace motionstyle::test {

// Builds a skeleton parents-first. End Sites are named "<parent>_End" as the BVH reader names them.
class RigBuilder {
 public:
  RigBuilder& joint(const std::string& name, const std::string& parent, Eigen::Vector3d offset) {
    Joint joint;
    joint.name = name;
    joint.parent = parent.empty() ? -1 : indexOf(parent);
    joint.offset = offset;
    using C = ChannelType;
    joint.channels = {C::Zrotation, C::Xrotation, C::Yrotation};
    if (parent.empty()) joint.channels.insert(joint.channels.begin(), {C::Xposition, C::Yposition, C::Zposition});
    skeleton_.joints.push_back(std::move(joint));
    return *this;
  }
  RigBuilder& endSite(const std::string& parent, Eigen::Vector3d offset) {
    Joint joint;
    joint.name = parent + "_End";
    joint.parent = indexOf(parent);
    joint.offset = offset;
    joint.end_site = true;
    skeleton_.joints.push_back(std::move(joint));
    return *this;
  }
  // A chain below `parent`, each joint `step` further on; ends in an End Site when end_offset is given.
  RigBuilder& chain(const std::vector<std::string>& names, std::string parent, Eigen::Vector3d step,
                    bool end_site = true) {
    for (const std::string& name : names) {
      joint(name, parent, step);
      parent = name;
    }
    if (end_site) endSite(parent, step);
    return *this;
  }
  Skeleton build() const {
    skeleton_.validate();
    return skeleton_;
  }

 private:
  int indexOf(const std::string& name) const {
    const int index = skeleton_.find(name);
    if (index < 0) throw std::logic_error("test rig: no parent named " + name);
    return index;
  }
  Skeleton skeleton_;
};

using Expected = std::map<CanonicalJoint, std::string>;
using CJ = CanonicalJoint;

// The rig joint names a mapping selects, by canonical joint ("<missing>" for -1).
inline std::map<CanonicalJoint, std::string> mappedNames(const JointMapping& mapping, const Skeleton& skeleton) {
  std::map<CanonicalJoint, std::string> names;
  for (CanonicalJoint joint : kAllCanonicalJoints)
    names[joint] = mapping[joint] < 0 ? "<missing>" : skeleton.joints[static_cast<size_t>(mapping[joint])].name;
  return names;
}

struct TestRig {
  std::string label;
  Skeleton skeleton;
  Expected expected;      // all 21 canonical joints
  std::string convention;
};

// Bandai Namco Research motion dataset (both datasets share this header).
inline TestRig bandaiRig() {
  RigBuilder b;
  b.joint("joint_Root", "", {0, 0, 0}).joint("Hips", "joint_Root", {0.85, 93.98, -452.2});
  b.joint("Spine", "Hips", {15.7, 0, 0}).joint("Chest", "Spine", {9.0, -0.4, 0});
  b.joint("Neck", "Chest", {16.4, 0, 0}).joint("Head", "Neck", {6.5, 0, 0}).endSite("Head", {0, 0, 0});
  for (const auto& [s, z] : {std::pair{"L", 1.0}, std::pair{"R", -1.0}}) {
    const std::string side = s;
    b.joint("Shoulder_" + side, "Chest", {13.0, -0.24, 5.0 * z});
    b.chain({"UpperArm_" + side, "LowerArm_" + side, "Hand_" + side}, "Shoulder_" + side, {5.3 * z, 0, 0}, false);
    b.endSite("Hand_" + side, {0, 0, 0});
    b.joint("UpperLeg_" + side, "Hips", {-2.2, -6.5 * z, 0});
    b.chain({"LowerLeg_" + side, "Foot_" + side, "Toes_" + side}, "UpperLeg_" + side, {39.1 * z, 0, 0});
  }
  Expected e = {{CJ::Hips, "Hips"}, {CJ::Spine, "Spine"}, {CJ::Chest, "Chest"}, {CJ::Neck, "Neck"}, {CJ::Head, "Head"}};
  for (const auto& [side, left] : {std::pair{"L", true}, std::pair{"R", false}}) {
    auto c = [&](CanonicalJoint j) { return left ? j : mirrorJoint(j); };
    const std::string x = std::string("_") + side;
    e[c(CJ::LeftHip)] = "UpperLeg" + x, e[c(CJ::LeftKnee)] = "LowerLeg" + x, e[c(CJ::LeftAnkle)] = "Foot" + x;
    e[c(CJ::LeftToe)] = "Toes" + x, e[c(CJ::LeftUpperArm)] = "UpperArm" + x, e[c(CJ::LeftElbow)] = "LowerArm" + x;
    e[c(CJ::LeftWrist)] = "Hand" + x, e[c(CJ::LeftHandEnd)] = "Hand" + x + "_End";
  }
  return {"bandai", b.build(), e, "bandai"};
}

// CMU as converted by cgspeed (the naming of the 2016 code's 31-joint skeleton). The expected joints are
// the 21 the 2016 code kept: hips; UpLeg, Leg, Foot, ToeBase; Spine, Spine1, Neck1, Head; Arm, ForeArm,
// Hand, HandIndex1.
inline TestRig cgspeedRig() {
  RigBuilder b;
  b.joint("Hips", "", {0, 0, 0});
  for (const auto& [side, x] : {std::pair{"Left", 1.0}, std::pair{"Right", -1.0}}) {
    const std::string s = side, l = s.substr(0, 1);
    b.joint(l + "HipJoint", "Hips", {0, 0, 0}).joint(s + "UpLeg", l + "HipJoint", {1.36 * x, -1.79, 0.84});
    b.chain({s + "Leg", s + "Foot", s + "ToeBase"}, s + "UpLeg", {0.3 * x, -6.5, 0});
  }
  b.joint("LowerBack", "Hips", {0, 0, 0}).joint("Spine", "LowerBack", {0, 2.0, 0}).joint("Spine1", "Spine", {0, 2.0, 0});
  b.joint("Neck", "Spine1", {0, 0, 0}).joint("Neck1", "Neck", {0, 1.6, 0.1}).joint("Head", "Neck1", {0, 1.6, 0});
  b.endSite("Head", {0, 1.6, 0});
  for (const auto& [side, x] : {std::pair{"Left", 1.0}, std::pair{"Right", -1.0}}) {
    const std::string s = side, l = s.substr(0, 1);
    b.joint(s + "Shoulder", "Spine1", {0, 0, 0}).joint(s + "Arm", s + "Shoulder", {3.0 * x, 1.5, 0});
    b.joint(s + "ForeArm", s + "Arm", {4.2 * x, 0, 0}).joint(s + "Hand", s + "ForeArm", {3.3 * x, 0, 0});
    b.joint(s + "FingerBase", s + "Hand", {0, 0, 0}).chain({s + "HandIndex1"}, s + "FingerBase", {0.7 * x, 0, 0});
    b.chain({l + "Thumb"}, s + "Hand", {0.4 * x, 0, 0.4});
  }
  Expected e = {{CJ::Hips, "Hips"}, {CJ::Spine, "Spine"}, {CJ::Chest, "Spine1"}, {CJ::Neck, "Neck1"}, {CJ::Head, "Head"}};
  for (const auto& [side, left] : {std::pair{"Left", true}, std::pair{"Right", false}}) {
    auto c = [&](CanonicalJoint j) { return left ? j : mirrorJoint(j); };
    const std::string s = side;
    e[c(CJ::LeftHip)] = s + "UpLeg", e[c(CJ::LeftKnee)] = s + "Leg", e[c(CJ::LeftAnkle)] = s + "Foot";
    e[c(CJ::LeftToe)] = s + "ToeBase", e[c(CJ::LeftUpperArm)] = s + "Arm", e[c(CJ::LeftElbow)] = s + "ForeArm";
    e[c(CJ::LeftWrist)] = s + "Hand", e[c(CJ::LeftHandEnd)] = s + "HandIndex1";
  }
  return {"cgspeed", b.build(), e, "cmu"};
}

// Mixamo: "LeftShoulder" is the clavicle here, fingers in full, toe and head end joints. Names carry no
// prefix; withPrefix() adds "mixamorig:".
inline TestRig mixamoRig() {
  RigBuilder b;
  b.joint("Hips", "", {0, 100, 0}).chain({"Spine", "Spine1", "Spine2"}, "Hips", {0, 11, 0}, false);
  b.joint("Neck", "Spine2", {0, 15, 0}).joint("Head", "Neck", {0, 10, 0}).chain({"HeadTop_End"}, "Head", {0, 18, 0});
  for (const auto& [side, x] : {std::pair{"Left", 1.0}, std::pair{"Right", -1.0}}) {
    const std::string s = side;
    b.joint(s + "Shoulder", "Spine2", {6 * x, 10, 0}).joint(s + "Arm", s + "Shoulder", {12 * x, 0, 0});
    b.joint(s + "ForeArm", s + "Arm", {27 * x, 0, 0}).joint(s + "Hand", s + "ForeArm", {25 * x, 0, 0});
    for (const std::string finger : {"Thumb", "Index", "Middle", "Ring", "Pinky"}) {
      std::vector<std::string> names;
      for (int k = 1; k <= 4; ++k) names.push_back(s + "Hand" + finger + std::to_string(k));
      b.chain(names, s + "Hand", {3 * x, 0, 0});
    }
    b.joint(s + "UpLeg", "Hips", {9 * x, -6, 0}).chain({s + "Leg", s + "Foot"}, s + "UpLeg", {0, -41, 0}, false);
    b.chain({s + "ToeBase", s + "Toe_End"}, s + "Foot", {0, -4, 10});
  }
  Expected e = {{CJ::Hips, "Hips"}, {CJ::Spine, "Spine"}, {CJ::Chest, "Spine2"}, {CJ::Neck, "Neck"}, {CJ::Head, "Head"}};
  for (const auto& [side, left] : {std::pair{"Left", true}, std::pair{"Right", false}}) {
    auto c = [&](CanonicalJoint j) { return left ? j : mirrorJoint(j); };
    const std::string s = side;
    e[c(CJ::LeftHip)] = s + "UpLeg", e[c(CJ::LeftKnee)] = s + "Leg", e[c(CJ::LeftAnkle)] = s + "Foot";
    e[c(CJ::LeftToe)] = s + "ToeBase", e[c(CJ::LeftUpperArm)] = s + "Arm", e[c(CJ::LeftElbow)] = s + "ForeArm";
    e[c(CJ::LeftWrist)] = s + "Hand", e[c(CJ::LeftHandEnd)] = s + "HandIndex4";
  }
  return {"mixamo", b.build(), e, "mixamo"};
}

// Meta's AnimatedDrawings (zombie.bvh's rig): four spine joints, a HandEnd joint, Z up.
inline TestRig animatedDrawingsRig() {
  RigBuilder b;
  b.joint("Hips", "", {0, 0, 0}).chain({"Spine", "Spine1", "Spine2", "Spine3"}, "Hips", {0, 1, 2.3}, false);
  b.joint("Neck", "Spine3", {0, -0.9, 6}).chain({"Head"}, "Neck", {0, -0.5, 3.1});
  for (const auto& [side, x] : {std::pair{"Right", -1.0}, std::pair{"Left", 1.0}}) {
    const std::string s = side;
    b.joint(s + "Shoulder", "Spine3", {0.8 * x, -1.3, 4.3});
    b.chain({s + "Arm", s + "ForeArm", s + "Hand"}, s + "Shoulder", {6.5 * x, 0, 0}, false);
    b.chain({s + "HandEnd"}, s + "Hand", {1.75 * x, 0, 0}).chain({s + "HandThumb1"}, s + "Hand", {0.7 * x, -1.2, -0.5});
  }
  for (const auto& [side, x] : {std::pair{"Right", -1.0}, std::pair{"Left", 1.0}}) {
    const std::string s = side;
    b.joint(s + "UpLeg", "Hips", {2.3 * x, 0, -0.7}).chain({s + "Leg", s + "Foot", s + "ToeBase"}, s + "UpLeg", {0, 0, -10.8});
  }
  Expected e = {{CJ::Hips, "Hips"}, {CJ::Spine, "Spine"}, {CJ::Chest, "Spine3"}, {CJ::Neck, "Neck"}, {CJ::Head, "Head"}};
  for (const auto& [side, left] : {std::pair{"Left", true}, std::pair{"Right", false}}) {
    auto c = [&](CanonicalJoint j) { return left ? j : mirrorJoint(j); };
    const std::string s = side;
    e[c(CJ::LeftHip)] = s + "UpLeg", e[c(CJ::LeftKnee)] = s + "Leg", e[c(CJ::LeftAnkle)] = s + "Foot";
    e[c(CJ::LeftToe)] = s + "ToeBase", e[c(CJ::LeftUpperArm)] = s + "Arm", e[c(CJ::LeftElbow)] = s + "ForeArm";
    e[c(CJ::LeftWrist)] = s + "Hand", e[c(CJ::LeftHandEnd)] = s + "HandEnd";
  }
  return {"animated-drawings", b.build(), e, "animated-drawings"};
}

// Unreal's mannequin naming (lower case, "_l"/"_r" suffixes, calf/ball, clavicles, index_01..03).
inline TestRig unrealRig() {
  RigBuilder b;
  b.joint("root", "", {0, 0, 0}).joint("pelvis", "root", {0, 97, 0});
  b.chain({"spine_01", "spine_02", "spine_03"}, "pelvis", {0, 12, 0}, false);
  b.joint("neck_01", "spine_03", {0, 15, 0}).chain({"head"}, "neck_01", {0, 9, 0});
  for (const auto& [side, x] : {std::pair{"l", 1.0}, std::pair{"r", -1.0}}) {
    const std::string s = side;
    b.joint("clavicle_" + s, "spine_03", {4 * x, 12, 0});
    b.chain({"upperarm_" + s, "lowerarm_" + s, "hand_" + s}, "clavicle_" + s, {26 * x, 0, 0}, false);
    b.chain({"thumb_01_" + s, "thumb_02_" + s}, "hand_" + s, {2 * x, 0, 2});
    b.chain({"index_01_" + s, "index_02_" + s, "index_03_" + s}, "hand_" + s, {3 * x, 0, 0});
    b.joint("thigh_" + s, "pelvis", {9 * x, -5, 0}).chain({"calf_" + s, "foot_" + s}, "thigh_" + s, {0, -42, 0}, false);
    b.chain({"ball_" + s}, "foot_" + s, {0, -6, 12});
  }
  Expected e = {{CJ::Hips, "pelvis"}, {CJ::Spine, "spine_01"}, {CJ::Chest, "spine_03"}, {CJ::Neck, "neck_01"}, {CJ::Head, "head"}};
  for (const auto& [side, left] : {std::pair{"l", true}, std::pair{"r", false}}) {
    auto c = [&](CanonicalJoint j) { return left ? j : mirrorJoint(j); };
    const std::string x = std::string("_") + side;
    e[c(CJ::LeftHip)] = "thigh" + x, e[c(CJ::LeftKnee)] = "calf" + x, e[c(CJ::LeftAnkle)] = "foot" + x;
    e[c(CJ::LeftToe)] = "ball" + x, e[c(CJ::LeftUpperArm)] = "upperarm" + x, e[c(CJ::LeftElbow)] = "lowerarm" + x;
    e[c(CJ::LeftWrist)] = "hand" + x, e[c(CJ::LeftHandEnd)] = "index_03" + x;
  }
  return {"unreal", b.build(), e, "generic"};
}

// 3ds Max Biped: names with spaces and the side as a middle token, legs and spine under the pelvis.
inline TestRig bipedRig() {
  RigBuilder b;
  b.joint("Bip01", "", {0, 0, 0}).joint("Bip01 Pelvis", "Bip01", {0, 95, 0});
  b.chain({"Bip01 Spine", "Bip01 Spine1"}, "Bip01 Pelvis", {0, 14, 0}, false);
  b.joint("Bip01 Neck", "Bip01 Spine1", {0, 20, 0}).chain({"Bip01 Head"}, "Bip01 Neck", {0, 9, 0});
  for (const auto& [side, x] : {std::pair{"L", 1.0}, std::pair{"R", -1.0}}) {
    const std::string p = std::string("Bip01 ") + side + " ";
    b.joint(p + "Clavicle", "Bip01 Neck", {5 * x, -2, 0});
    b.chain({p + "UpperArm", p + "Forearm", p + "Hand"}, p + "Clavicle", {27 * x, 0, 0}, false);
    b.chain({p + "Finger0"}, p + "Hand", {2 * x, 0, 2}).chain({p + "Finger1", p + "Finger11"}, p + "Hand", {4 * x, 0, 0});
    b.joint(p + "Thigh", "Bip01 Pelvis", {9 * x, 0, 0}).chain({p + "Calf", p + "Foot", p + "Toe0"}, p + "Thigh", {0, -40, 0});
  }
  // Biped hangs the clavicles off the neck joint: the chest is the spine joint below it.
  Expected e = {{CJ::Hips, "Bip01 Pelvis"}, {CJ::Spine, "Bip01 Spine"}, {CJ::Chest, "Bip01 Spine1"},
                {CJ::Neck, "Bip01 Neck"}, {CJ::Head, "Bip01 Head"}};
  for (const auto& [side, left] : {std::pair{"L", true}, std::pair{"R", false}}) {
    auto c = [&](CanonicalJoint j) { return left ? j : mirrorJoint(j); };
    const std::string p = std::string("Bip01 ") + side + " ";
    e[c(CJ::LeftHip)] = p + "Thigh", e[c(CJ::LeftKnee)] = p + "Calf", e[c(CJ::LeftAnkle)] = p + "Foot";
    e[c(CJ::LeftToe)] = p + "Toe0", e[c(CJ::LeftUpperArm)] = p + "UpperArm", e[c(CJ::LeftElbow)] = p + "Forearm";
    e[c(CJ::LeftWrist)] = p + "Hand", e[c(CJ::LeftHandEnd)] = p + "Finger11";
  }
  return {"biped", b.build(), e, "generic"};
}

// The rig with every joint name prefixed (e.g. "mixamorig:").
inline Skeleton withPrefix(Skeleton skeleton, const std::string& prefix) {
  for (Joint& joint : skeleton.joints) joint.name = prefix + joint.name;
  return skeleton;
}

// The rig with some joints renamed (each `from` must exist).
inline Skeleton renamed(Skeleton skeleton, const std::map<std::string, std::string>& names) {
  for (const auto& [from, to] : names) {
    const int joint = skeleton.find(from);
    if (joint < 0) throw std::logic_error("test rig: no joint named " + from);
    skeleton.joints[static_cast<size_t>(joint)].name = to;
  }
  skeleton.validate();
  return skeleton;
}

}  // namespace motionstyle::test
