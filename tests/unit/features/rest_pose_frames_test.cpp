// A leading rest-pose frame (CMU's cmuconvert BVH files open with a T-pose): detected, replaced by the
// motion continued backward for the features and the clean-up, and written back as it was.
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "bvh/bvh_reader.h"
#include "features/foot_contacts.h"
#include "features/representation.h"
#include "features/rest_pose_frames.h"
#include "mapping/joint_mapping.h"
#include "motion/kinematics.h"
#include "motion/resample.h"
#include "style/stylized_cleanup.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

// The clip with its rig's rest pose put before frame 0, as CMU's files have it: the first frame's
// root position, every rotation zero.
Motion withRestPoseFrame(const Motion& motion) {
  Motion out = motion;
  out.values.resize(motion.values.rows() + 1, motion.values.cols());
  out.values.bottomRows(motion.values.rows()) = motion.values;
  out.values.row(0).setZero();
  int column = 0;
  for (const Joint& joint : motion.skeleton.joints)
    for (ChannelType channel : joint.channels) {
      if (!isRotation(channel)) out.values(0, column) = motion.values(0, column);
      ++column;
    }
  return out;
}

// Largest distance between matching canonical joints of two frames x 63 matrices, rows [first, end).
double maxJointDistance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, Eigen::Index first) {
  double worst = 0.0;
  for (Eigen::Index f = first; f < a.rows(); ++f)
    for (int c = 0; c < kCanonicalJointCount; ++c)
      worst = std::max(worst, (a.row(f).segment<3>(3 * c) - b.row(f).segment<3>(3 * c)).norm());
  return worst;
}

TEST(RestPoseFrames, RejectsWhatCannotBeReplacedOrRestored) {
  const Motion motion = readBvh(test::fixture("zombie.bvh"));
  Motion copy = motion;
  EXPECT_THROW(replaceRestPoseFrames(copy, -1), std::invalid_argument);
  EXPECT_THROW(replaceRestPoseFrames(copy, motion.frameCount() - 1), std::invalid_argument);  // two must follow
  Motion other = motion;
  other.values.conservativeResize(Eigen::NoChange, motion.values.cols() - 3);
  EXPECT_THROW(restoreRestPoseFrames(other, motion, 1), std::invalid_argument);
  replaceRestPoseFrames(copy, 0);
  EXPECT_EQ(copy.values, motion.values);
}

TEST(RestPoseFrames, ClipsThatOpenWithMotionHaveNone) {
  for (const char* name : {"zombie.bvh", "cmu_131_01.bvh"}) {
    Motion motion = readBvh(test::fixture(name));
    const JointMapping mapping = mapJoints(motion.skeleton, name);
    EXPECT_EQ(leadingRestPoseFrames(motion, mapping), 0) << name;
    // Fast motion is not a rest pose: every fourth frame (four times the speed).
    Motion fast = motion;
    fast.values.resize((motion.frameCount() + 3) / 4, motion.values.cols());
    for (Eigen::Index f = 0; f < fast.values.rows(); ++f) fast.values.row(f) = motion.values.row(4 * f);
    EXPECT_EQ(leadingRestPoseFrames(fast, mapping), 0) << name;
    // Too short to tell: the rest pose and one frame of motion.
    motion.values.conservativeResize(1, Eigen::NoChange);
    EXPECT_EQ(leadingRestPoseFrames(withRestPoseFrame(motion), mapping), 0) << name;
  }
}

TEST(RestPoseFrames, AFrameOfTheRigsRestPoseIsFoundAndReplacedForTheFeatures) {
  const Motion cmu = readBvh(test::fixture("cmu_131_01.bvh"));
  const std::vector<std::pair<std::string, Motion>> clips = {
      {"zombie.bvh", readBvh(test::fixture("zombie.bvh"))}, {"cmu_131_01.bvh", cmu}, {"at 24 fps", resampleMotion(cmu, 24.0)}};
  for (const auto& [name, motion] : clips) {
    const JointMapping mapping = mapJoints(motion.skeleton, name == "zombie.bvh" ? name : "cmu_131_01.bvh");
    const Motion with_rest = withRestPoseFrame(motion);
    ASSERT_EQ(leadingRestPoseFrames(with_rest, mapping), 1) << name;

    // The replacement continues the first step backward, angles through the shortest turn.
    Motion replaced = with_rest;
    replaceRestPoseFrames(replaced, 1);
    EXPECT_EQ(replaced.values.bottomRows(motion.frameCount()), motion.values) << name;
    const Eigen::MatrixXd world = worldPositions(replaced, mapping.joints);
    const double first_step = maxJointDistance(world.middleRows(0, 1), world.middleRows(1, 1), 0);
    const double next_step = maxJointDistance(world.middleRows(1, 1), world.middleRows(2, 1), 0);
    EXPECT_LT(first_step, 2.0 * next_step + 1e-9) << name;

    // The features see the replaced clip and say so.
    const MotionFeatures features = extractFeatures(with_rest, mapping);
    const MotionFeatures expected = extractFeatures(replaced, mapping);
    EXPECT_EQ(features.anchor.rest_pose_frames, 1) << name;
    EXPECT_EQ(expected.anchor.rest_pose_frames, 0) << name;
    EXPECT_EQ(features.values, expected.values) << name;
    EXPECT_EQ(features.contacts, expected.contacts) << name;
  }
}

// The ground the app's loader and stylize read: a T-pose frame 0 is seen through as the features see
// it (not a contact, not the floor), the caller's clip is not changed, and no rest pose means the clip.
TEST(RestPoseFrames, TheClipsGroundSeesThroughTheRestPose) {
  const Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton, "cmu_131_01.bvh");
  const Motion with_rest = withRestPoseFrame(motion);
  Motion replaced = with_rest;
  replaceRestPoseFrames(replaced, 1);
  const FileSpaceGround expected = detectFileSpaceGround(replaced, mapping, canonicalJointPositions(replaced, mapping));
  const FileSpaceGround ground = detectClipGround(with_rest, mapping, 1);
  EXPECT_EQ(ground.contacts, expected.contacts);
  EXPECT_DOUBLE_EQ(ground.floor_height, expected.floor_height);
  ASSERT_EQ(ground.contacts.rows(), with_rest.frameCount());
  EXPECT_EQ(ground.contacts.bottomRows(motion.frameCount() - 1), expected.contacts.bottomRows(motion.frameCount() - 1));
  // Read as motion, the T-pose's frame changes what is detected: the replacement is not a no-op here.
  const FileSpaceGround as_motion = detectClipGround(with_rest, mapping, 0);
  EXPECT_NE(as_motion.contacts, ground.contacts);
  EXPECT_EQ(detectClipGround(motion, mapping, 0).contacts,
            detectFileSpaceGround(motion, mapping, canonicalJointPositions(motion, mapping)).contacts);
}

// The clean-up of a clip with a rest-pose frame writes that frame back unchanged and cleans the
// motion as it cleans the same clip without it; at the content's rate and resampled.
TEST(RestPoseFrames, TheCleanUpWritesTheRestPoseBackAndCleansTheMotion) {
  const Motion motion = readBvh(test::fixture("zombie.bvh"));  // 30 fps: solved at its own rate
  const JointMapping mapping = mapJoints(motion.skeleton, "zombie.bvh");
  const Motion with_rest = withRestPoseFrame(motion);
  auto stylizedAsIs = [&](const Motion& clip) {  // the content's own features as the "stylized" clip
    const MotionFeatures features = extractFeatures(clip, mapping);
    style::StylizedClip stylized;
    stylized.features = features.values;
    stylized.contacts = features.contacts;
    stylized.world_positions = canonicalWorldPositions(features.values, features.anchor);
    stylized.anchor = features.anchor;
    stylized.fps = features.anchor.fps;
    return stylized;
  };
  const style::StylizedCleanup plain = style::cleanUpStylizedClip(motion, mapping, stylizedAsIs(motion));
  const style::StylizedCleanup cleaned = style::cleanUpStylizedClip(with_rest, mapping, stylizedAsIs(with_rest));
  ASSERT_EQ(cleaned.motion.frameCount(), with_rest.frameCount());
  EXPECT_EQ(cleaned.motion.values.row(0), with_rest.values.row(0));
  EXPECT_LT(cleaned.report.max_position_residual_cm, plain.report.max_position_residual_cm + 1.0);
  // Past the first half second the two clean-ups agree (one frame apart in time).
  const Eigen::MatrixXd a = worldPositions(cleaned.motion, mapping.joints).bottomRows(motion.frameCount());
  const Eigen::MatrixXd b = worldPositions(plain.motion, mapping.joints);
  const double cm_per_unit = stylizedAsIs(motion).anchor.convention.cm_per_unit;
  EXPECT_LT(maxJointDistance(a, b, 15) * cm_per_unit, 1.0);

  // Resampled to 60 fps: frame 0 still the rest pose, frame 1 the motion.
  const style::StylizedCleanup at60 = style::cleanUpStylizedClip(with_rest, mapping, stylizedAsIs(with_rest), {}, 60.0);
  EXPECT_EQ(at60.motion.values.row(0), with_rest.values.row(0));
  EXPECT_NE(at60.motion.values.row(1), with_rest.values.row(0));
}

}  // namespace
}  // namespace motionstyle
