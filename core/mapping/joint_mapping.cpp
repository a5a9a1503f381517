#include "mapping/joint_mapping.h"

#include <algorithm>
#include <stdexcept>

#include "common/errors.h"
#include "mapping/rig_structure.h"

namespace motionstyle {

using mapping_detail::Aliases;
using mapping_detail::RigStructure;

namespace {

// Alias lists, best first. The limbs are found from their middle joint (knee, elbow), whose names are the
// least ambiguous: "LeftShoulder" is the shoulder ball joint in CMU 131 but the clavicle in Mixamo, and
// "LeftHip" is a thigh in CMU but "Hips" is the pelvis everywhere. The joints above and below the middle
// joint are then searched along its chain only.
constexpr std::string_view kKnee[] = {"Knee", "Leg", "LowerLeg", "LowLeg", "Shin", "Calf", "Crus", "Tibia"};
constexpr std::string_view kThigh[] = {"UpLeg", "UpperLeg", "Thigh", "Hip", "Femur"};
constexpr std::string_view kAnkle[] = {"Ankle", "Foot", "Tarsus"};
constexpr std::string_view kToe[] = {"ToeBase", "Toe", "Toes", "Toe0", "Ball", "ForeFoot"};
constexpr std::string_view kElbow[] = {"Elbow", "ForeArm", "LowerArm", "LowArm", "Radius"};
constexpr std::string_view kUpperArm[] = {"UpperArm", "UpArm", "Arm", "Humerus", "Shoulder"};
constexpr std::string_view kWrist[] = {"Wrist", "Hand", "Carpus"};
constexpr std::string_view kHandEnd[] = {"HandEnd", "HandTip", "HandSite", "FingerTip", "FingerTips"};
constexpr std::string_view kHead[] = {"Head", "Skull"};

std::string sideWord(BodySide side) { return side == BodySide::Left ? "left" : "right"; }

std::string aliasList(Aliases aliases) {
  std::string list;
  for (size_t i = 0; i < aliases.size(); ++i) {
    if (i > 0) list += i + 1 == aliases.size() ? " or " : ", ";
    list += aliases[i];
  }
  return list;
}

std::string name(CanonicalJoint joint) { return std::string(canonicalJointName(joint)); }

CanonicalJoint sided(BodySide side, CanonicalJoint left) { return side == BodySide::Left ? left : mirrorJoint(left); }

// The automatic search: a rig joint per canonical joint, or -1 and why not.
class Finder {
 public:
  explicit Finder(const Skeleton& skeleton) : rig_(skeleton) { found_.fill(-1); }

  void run() {
    for (BodySide side : {BodySide::Left, BodySide::Right}) {
      findLeg(side);
      findArm(side);
    }
    findHipsAndSpine();
    dropInconsistentChains();
  }

  const std::array<int, kCanonicalJointCount>& found() const { return found_; }
  const std::string& why(CanonicalJoint joint) const { return why_[static_cast<size_t>(index(joint))]; }

 private:
  int get(CanonicalJoint joint) const { return found_[static_cast<size_t>(index(joint))]; }
  void set(CanonicalJoint joint, int rig_joint) { found_[static_cast<size_t>(index(joint))] = rig_joint; }
  void fail(CanonicalJoint joint, std::string reason) { why_[static_cast<size_t>(index(joint))] = std::move(reason); }
  void failFrom(std::initializer_list<CanonicalJoint> joints, CanonicalJoint missing) {
    for (CanonicalJoint joint : joints) fail(joint, "found from " + name(missing) + ", which is missing");
  }
  std::string quoted(int rig_joint) const { return "'" + rig_.name(rig_joint) + "'"; }

  // Knee by name; the thigh is the nearest thigh-named ancestor (else the knee's parent); ankle and toe
  // are the nearest named descendants (else the main chain; the toe tip End Site only as a last resort).
  void findLeg(BodySide side) {
    const CanonicalJoint hip = sided(side, CanonicalJoint::LeftHip), knee = sided(side, CanonicalJoint::LeftKnee);
    const CanonicalJoint ankle = sided(side, CanonicalJoint::LeftAnkle), toe = sided(side, CanonicalJoint::LeftToe);
    const int knee_joint = rig_.findByName(side, kKnee);
    if (knee_joint < 0) {
      fail(knee, "no " + sideWord(side) + "-side joint named like " + aliasList(kKnee));
      failFrom({hip, ankle, toe}, knee);
      return;
    }
    set(knee, knee_joint);
    int hip_joint = rig_.nearestNamedAncestor(knee_joint, side, kThigh);
    if (hip_joint < 0) hip_joint = rig_.parent(knee_joint);
    if (hip_joint >= 0) set(hip, hip_joint);
    else fail(hip, name(knee) + " " + quoted(knee_joint) + " is the rig's root");

    int ankle_joint = rig_.nearestNamedDescendant(knee_joint, side, kAnkle, false);
    if (ankle_joint < 0) ankle_joint = rig_.mainChild(knee_joint);
    if (ankle_joint < 0) {
      fail(ankle, "no joint below " + name(knee) + " " + quoted(knee_joint));
      failFrom({toe}, ankle);
      return;
    }
    set(ankle, ankle_joint);
    int toe_joint = rig_.nearestNamedDescendant(ankle_joint, side, kToe, false);
    if (toe_joint < 0) toe_joint = rig_.mainChild(ankle_joint);
    if (toe_joint < 0) toe_joint = rig_.endSiteChild(ankle_joint);
    if (toe_joint >= 0) set(toe, toe_joint);
    else fail(toe, "no joint or End Site below " + name(ankle) + " " + quoted(ankle_joint));
  }

  void findArm(BodySide side) {
    const CanonicalJoint upper = sided(side, CanonicalJoint::LeftUpperArm);
    const CanonicalJoint elbow = sided(side, CanonicalJoint::LeftElbow);
    const CanonicalJoint wrist = sided(side, CanonicalJoint::LeftWrist);
    const CanonicalJoint hand_end = sided(side, CanonicalJoint::LeftHandEnd);
    const int elbow_joint = rig_.findByName(side, kElbow);
    if (elbow_joint < 0) {
      fail(elbow, "no " + sideWord(side) + "-side joint named like " + aliasList(kElbow));
      failFrom({upper, wrist, hand_end}, elbow);
      return;
    }
    set(elbow, elbow_joint);
    int upper_joint = rig_.nearestNamedAncestor(elbow_joint, side, kUpperArm);
    if (upper_joint < 0) upper_joint = rig_.parent(elbow_joint);
    if (upper_joint >= 0) set(upper, upper_joint);
    else fail(upper, name(elbow) + " " + quoted(elbow_joint) + " is the rig's root");

    int wrist_joint = rig_.nearestNamedDescendant(elbow_joint, side, kWrist, false);
    if (wrist_joint < 0) wrist_joint = rig_.mainChild(elbow_joint);
    if (wrist_joint < 0) {
      fail(wrist, "no joint below " + name(elbow) + " " + quoted(elbow_joint));
      failFrom({hand_end}, wrist);
      return;
    }
    set(wrist, wrist_joint);
    const int end_joint = findHandEnd(wrist_joint, side);
    if (end_joint >= 0) set(hand_end, end_joint);
    else fail(hand_end, name(wrist) + " " + quoted(wrist_joint) + " has no child joint or End Site");
  }

  // A joint named like a hand end, else the deepest joint of the hand's main chain (index finger, else
  // middle finger, else the longest chain, never the thumb, ring or little finger while another chain
  // exists) when it lies away from the wrist, else that chain's End Site.
  int findHandEnd(int wrist, BodySide side) const {
    const int named = rig_.nearestNamedDescendant(wrist, side, kHandEnd, true);
    if (named >= 0) return named;
    auto fingerRank = [&](int joint) {
      const std::string& flat = rig_.flatName(joint);
      auto has = [&](std::string_view word) { return flat.find(word) != std::string::npos; };
      if (has("index")) return 0;
      if (has("middle")) return 1;
      if (has("thumb") || has("pinky") || has("ring") || has("little")) return 3;
      return 2;
    };
    int tip = wrist;
    for (;;) {
      int next = -1;
      for (int child : rig_.children(tip)) {
        if (rig_.isEndSite(child)) continue;
        if (next < 0 || fingerRank(child) < fingerRank(next) ||
            (fingerRank(child) == fingerRank(next) && rig_.subtreeHeight(child) > rig_.subtreeHeight(next)))
          next = child;
      }
      if (next < 0) break;
      tip = next;
    }
    if (tip != wrist && !rig_.samePlace(tip, wrist)) return tip;
    const int end_site = rig_.endSiteChild(tip);
    if (end_site >= 0) return end_site;
    return tip != wrist ? tip : -1;
  }

  // Hips: the lowest common ancestor of the thighs and the head (or the upper arms without a head).
  // Spine column: the joints between the hips and the head. Chest: the deepest column joint both arms
  // hang below (unless that is the last one). Spine: the first column joint below the chest away from the
  // hips. Neck: the first column joint above the chest away from it.
  void findHipsAndSpine() {
    std::vector<int> anchors;
    for (CanonicalJoint thigh : {CanonicalJoint::LeftHip, CanonicalJoint::RightHip})
      if (get(thigh) >= 0) anchors.push_back(get(thigh));
    const int head = rig_.findByName(BodySide::Center, kHead);
    std::vector<int> arms;
    for (CanonicalJoint arm : {CanonicalJoint::LeftUpperArm, CanonicalJoint::RightUpperArm})
      if (get(arm) >= 0) arms.push_back(get(arm));
    if (head >= 0) {
      set(CanonicalJoint::Head, head);
      anchors.push_back(head);
    } else {
      fail(CanonicalJoint::Head, "no joint named like " + aliasList(kHead));
      anchors.insert(anchors.end(), arms.begin(), arms.end());
    }

    const int hips = anchors.size() >= 2 ? rig_.commonAncestor(anchors) : -1;
    bool hips_above_all = hips >= 0;
    for (int anchor : anchors) hips_above_all = hips_above_all && rig_.isAncestor(hips, anchor);
    const std::initializer_list<CanonicalJoint> column_joints = {CanonicalJoint::Spine, CanonicalJoint::Chest,
                                                                 CanonicalJoint::Neck};
    if (!hips_above_all) {
      fail(CanonicalJoint::Hips, "no joint that both legs and the head (or arms) hang below");
      failFrom(column_joints, CanonicalJoint::Hips);
      return;
    }
    set(CanonicalJoint::Hips, hips);
    if (head < 0) {
      failFrom(column_joints, CanonicalJoint::Head);
      return;
    }

    const std::vector<int> column = rig_.pathBetween(hips, head);
    size_t chest_at = column.size();
    for (size_t i = column.size(); i-- > 0 && !arms.empty();) {
      bool above_arms = true;
      for (int arm : arms) above_arms = above_arms && rig_.isAncestor(column[i], arm);
      if (above_arms) {
        chest_at = i;
        break;
      }
    }
    if (chest_at == column.size()) {
      const std::string reason = arms.empty() ? "found where the arms branch off the spine, and no arm was found"
                                              : "the arms do not branch off the spine between the hips and the head";
      fail(CanonicalJoint::Chest, reason);
      failFrom({CanonicalJoint::Spine, CanonicalJoint::Neck}, CanonicalJoint::Chest);
      return;
    }
    // 3ds Max Biped hangs the clavicles off its neck joint, the last one below the head: then the chest
    // is the joint below it, so that the neck is still found.
    if (chest_at + 1 == column.size() && chest_at > 0) --chest_at;
    const int chest = column[chest_at];
    set(CanonicalJoint::Chest, chest);

    auto firstAwayFrom = [&](size_t begin, size_t end, int from) {
      for (size_t i = begin; i < end; ++i)
        if (!rig_.samePlace(column[i], from)) return column[i];
      return begin < end ? column[begin] : -1;
    };
    const int spine = firstAwayFrom(0, chest_at, hips);
    if (spine >= 0) set(CanonicalJoint::Spine, spine);
    else fail(CanonicalJoint::Spine, "no joint between the Hips " + quoted(hips) + " and the Chest " + quoted(chest));
    const int neck = firstAwayFrom(chest_at + 1, column.size(), chest);
    if (neck >= 0) set(CanonicalJoint::Neck, neck);
    else fail(CanonicalJoint::Neck, "no joint between the Chest " + quoted(chest) + " and the Head " + quoted(head));
  }

  // Each joint must hang below its canonical parent's joint, and no rig joint may serve twice.
  void dropInconsistentChains() {
    for (CanonicalJoint joint : kAllCanonicalJoints) {
      const int rig_joint = get(joint);
      if (rig_joint < 0) continue;
      const std::optional<CanonicalJoint> parent = canonicalParent(joint);
      if (parent && get(*parent) >= 0 && !rig_.isAncestor(get(*parent), rig_joint)) {
        set(joint, -1);
        fail(joint, quoted(rig_joint) + " does not hang below " + name(*parent) + " " + quoted(get(*parent)));
        continue;
      }
      for (CanonicalJoint earlier : kAllCanonicalJoints) {
        if (earlier == joint) break;
        if (get(earlier) == rig_joint) {
          set(joint, -1);
          fail(joint, quoted(rig_joint) + " is already " + name(earlier));
          break;
        }
      }
    }
  }

  RigStructure rig_;
  std::array<int, kCanonicalJointCount> found_{};
  std::array<std::string, kCanonicalJointCount> why_;
};

// `finder` must have been built on the validated `skeleton`.
JointMapping guess(const Skeleton& skeleton, Finder& finder) {
  finder.run();
  JointMapping mapping;
  mapping.joints = finder.found();
  mapping.convention = detectConvention(skeleton);
  return mapping;
}

}  // namespace

std::vector<CanonicalJoint> JointMapping::missing() const {
  std::vector<CanonicalJoint> result;
  for (CanonicalJoint joint : kAllCanonicalJoints)
    if ((*this)[joint] < 0) result.push_back(joint);
  return result;
}

std::string JointMapping::missingNames() const {
  std::string names;
  for (CanonicalJoint joint : missing()) names += (names.empty() ? "" : ", ") + name(joint);
  return names;
}

void JointMapping::validate(const Skeleton& skeleton) const {
  if (const std::optional<std::string> problem = describeMappingProblem(*this, skeleton))
    throw std::invalid_argument(*problem);
}

std::optional<std::string> describeMappingProblem(const JointMapping& mapping, const Skeleton& skeleton) {
  if (const std::string missing = mapping.missingNames(); !missing.empty()) return "missing " + missing;
  const int count = skeleton.jointCount();
  for (CanonicalJoint joint : kAllCanonicalJoints)
    if (mapping[joint] >= count)
      return name(joint) + " refers to joint " + std::to_string(mapping[joint]) + " but the skeleton has " +
             std::to_string(count) + " joints";
  auto label = [&](CanonicalJoint joint) {
    return name(joint) + " '" + skeleton.joints[static_cast<size_t>(mapping[joint])].name + "'";
  };
  for (CanonicalJoint joint : kAllCanonicalJoints) {
    for (CanonicalJoint earlier : kAllCanonicalJoints) {
      if (earlier == joint) break;
      if (mapping[earlier] == mapping[joint]) return label(joint) + " is already used for " + name(earlier);
    }
    const std::optional<CanonicalJoint> parent = canonicalParent(joint);
    if (!parent) continue;
    // Bounded by the joint count, so even a cyclic (invalid) parent table cannot hang this loop.
    bool below = false;
    int steps = 0;
    for (int j = skeleton.joints[static_cast<size_t>(mapping[joint])].parent; j >= 0 && j < count && !below &&
                                                                             steps <= count;
         j = skeleton.joints[static_cast<size_t>(j)].parent, ++steps)
      below = j == mapping[*parent];
    if (!below) return label(joint) + " does not hang below " + label(*parent);
  }
  return std::nullopt;
}

JointMapping guessJointMapping(const Skeleton& skeleton) {
  skeleton.validate();
  Finder finder(skeleton);
  return guess(skeleton, finder);
}

JointMapping mapJoints(const Skeleton& skeleton, const std::string& source) {
  skeleton.validate();
  Finder finder(skeleton);
  JointMapping mapping = guess(skeleton, finder);
  const std::vector<CanonicalJoint> missing = mapping.missing();
  if (missing.empty()) return mapping;

  // "missing A, B (A: why; B: why)", joints sharing a reason grouped together.
  std::vector<std::pair<std::string, std::string>> reasons;  // (reason, joints)
  for (CanonicalJoint joint : missing) {
    auto group = std::find_if(reasons.begin(), reasons.end(), [&](const auto& r) { return r.first == finder.why(joint); });
    if (group == reasons.end()) reasons.emplace_back(finder.why(joint), name(joint));
    else group->second += ", " + name(joint);
  }
  std::string explanation;
  for (const auto& [reason, joints] : reasons) explanation += (explanation.empty() ? "" : "; ") + joints + ": " + reason;
  throw InputError(source, 0,
                   "cannot map the rig to the canonical skeleton: missing " + mapping.missingNames() + " (" + explanation +
                       "); provide a joint mapping file (motionstyle-cli info CLIP --write-mapping MAP.json writes one "
                       "to complete)");
}

std::string detectConvention(const Skeleton& skeleton) {
  auto has = [&](std::string_view joint_name) { return skeleton.find(joint_name) >= 0; };
  for (const Joint& joint : skeleton.joints)
    if (joint.name.find("mixamorig") != std::string::npos)
      return "mixamo";
  if (has("LHipJoint") || has("RHipJoint") || has("lowerback") || has("LowerBack")) return "cmu";
  if (has("joint_Root") || has("UpperArm_L") || has("LowerLeg_L")) return "bandai";
  if (has("LeftHandEnd") || has("RightHandEnd")) return "animated-drawings";
  if (has("LeftUpLeg") && has("LeftForeArm") && has("LeftToeBase")) return "mixamo";
  return "generic";
}

}  // namespace motionstyle
