// Random rigs built from the names the mapper knows, and convention rigs with random renames and inserted
// joints: whatever the hierarchy, mapJoints either returns a mapping that passes describeMappingProblem
// or throws InputError naming exactly guessJointMapping's gaps.

#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <string>
#include <vector>

#include "common/errors.h"
#include "mapping/joint_mapping.h"
#include "mapping_test_rigs.h"

namespace motionstyle {
namespace {

Skeleton randomRig(std::mt19937& random) {
  static const std::vector<std::string> kSides = {"", "Left", "Right", "L_", "R_"};
  static const std::vector<std::string> kWords = {"Hips",  "Spine",   "Chest", "Neck",    "Head",   "UpLeg",
                                                  "Leg",   "Foot",    "Toe",   "Shoulder", "Arm",   "ForeArm",
                                                  "Hand",  "HandEnd", "Thumb", "Index1",  "Middle1", "Root"};
  std::uniform_int_distribution<int> count_of(1, 40);
  std::uniform_int_distribution<size_t> side_of(0, kSides.size() - 1), word_of(0, kWords.size() - 1);
  std::uniform_int_distribution<int> coin(0, 3);
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  Skeleton skeleton;
  const int count = count_of(random);
  for (int j = 0; j < count; ++j) {
    Joint joint;
    joint.name = kSides[side_of(random)] + kWords[word_of(random)];
    if (skeleton.find(joint.name) >= 0) joint.name = "extra" + std::to_string(j);
    if (j > 0) {
      // A random earlier joint that is not an End Site.
      std::vector<int> parents;
      for (int p = 0; p < j; ++p)
        if (!skeleton.joints[static_cast<size_t>(p)].end_site) parents.push_back(p);
      joint.parent = parents[std::uniform_int_distribution<size_t>(0, parents.size() - 1)(random)];
      joint.end_site = coin(random) == 0;
    }
    if (coin(random) != 0) joint.offset = {coordinate(random), coordinate(random), coordinate(random)};
    if (!joint.end_site) joint.channels = {ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
    skeleton.joints.push_back(joint);
  }
  skeleton.validate();
  return skeleton;
}

// A joint named `name` inserted between `joint` and its parent, `fraction` of the way along the bone.
Skeleton insertAbove(const Skeleton& skeleton, int joint, const std::string& name, double fraction) {
  Skeleton result = skeleton;
  const auto at = static_cast<size_t>(joint);
  Joint inserted = skeleton.joints[at];
  inserted.name = name;
  inserted.end_site = false;
  inserted.channels = {ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
  inserted.offset *= fraction;
  result.joints.insert(result.joints.begin() + joint, inserted);
  for (size_t j = at + 1; j < result.joints.size(); ++j)
    if (result.joints[j].parent >= joint) ++result.joints[j].parent;
  result.joints[at + 1].parent = joint;
  result.joints[at + 1].offset *= 1.0 - fraction;
  return result;
}

// One of the convention rigs with a few random renames and inserted joints: mostly still mappable.
Skeleton perturbedRig(std::mt19937& random) {
  static const std::vector<std::function<test::TestRig()>> kRigs = {
      test::bandaiRig, test::cgspeedRig, test::mixamoRig, test::animatedDrawingsRig, test::unrealRig, test::bipedRig};
  static const std::vector<std::string> kNames = {"Twist", "Roll", "Knee", "LeftKnee", "RightArm", "Head", "Neck2",
                                                  "Spine9", "LeftToe", "Hips2", "L_Hand", "extra", "RightHandEnd"};
  Skeleton skeleton = kRigs[std::uniform_int_distribution<size_t>(0, kRigs.size() - 1)(random)]().skeleton;
  const int edits = std::uniform_int_distribution<int>(0, 3)(random);
  for (int e = 0; e < edits; ++e) {
    const int joint = std::uniform_int_distribution<int>(1, skeleton.jointCount() - 1)(random);
    std::string name = kNames[std::uniform_int_distribution<size_t>(0, kNames.size() - 1)(random)];
    if (skeleton.find(name) >= 0) name += std::to_string(e);
    if (std::uniform_int_distribution<int>(0, 1)(random) == 0) {
      skeleton.joints[static_cast<size_t>(joint)].name = name;
    } else {
      const double fraction = std::uniform_int_distribution<int>(0, 1)(random) == 0 ? 0.0 : 0.5;
      skeleton = insertAbove(skeleton, joint, name, fraction);
    }
  }
  skeleton.validate();
  return skeleton;
}

TEST(RandomRigs, MappingIsValidOrTheErrorListsExactlyTheGaps) {
  std::mt19937 random(20170717);
  int mapped = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Skeleton skeleton = trial % 2 == 0 ? randomRig(random) : perturbedRig(random);
    const JointMapping guess = guessJointMapping(skeleton);
    std::string gaps;
    for (CanonicalJoint joint : guess.missing()) gaps += (gaps.empty() ? "" : ", ") + std::string(canonicalJointName(joint));
    try {
      const JointMapping mapping = mapJoints(skeleton, "random.bvh");
      ++mapped;
      EXPECT_EQ(describeMappingProblem(mapping, skeleton), std::nullopt) << "trial " << trial;
      EXPECT_TRUE(gaps.empty());
    } catch (const InputError& error) {
      ASSERT_FALSE(gaps.empty()) << "trial " << trial;
      EXPECT_NE(error.detail().find("missing " + gaps + " ("), std::string::npos) << error.detail();
    }
    // Whatever was found is consistent: each found joint hangs below its found canonical parent.
    for (CanonicalJoint joint : kAllCanonicalJoints) {
      const auto parent = canonicalParent(joint);
      if (!parent || guess[joint] < 0 || guess[*parent] < 0) continue;
      int j = skeleton.joints[static_cast<size_t>(guess[joint])].parent;
      while (j >= 0 && j != guess[*parent]) j = skeleton.joints[static_cast<size_t>(j)].parent;
      EXPECT_EQ(j, guess[*parent]) << "trial " << trial << ": " << canonicalJointName(joint);
    }
    if (::testing::Test::HasFailure()) return;
  }
  std::cout << "random rigs mapped completely: " << mapped << " of 3000\n";
}

TEST(RandomRigs, DefaultMappingIsEntirelyUnmapped) {
  EXPECT_EQ(JointMapping{}.missing().size(), static_cast<size_t>(kCanonicalJointCount));
}

}  // namespace
}  // namespace motionstyle
