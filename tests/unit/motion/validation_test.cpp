// Skeleton::validate and Motion::validate: every documented inconsistency is rejected, a well-formed
// rig passes.

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "motion/motion.h"
#include "motion/skeleton.h"
#include "motion_test_helpers.h"

namespace motionstyle {
namespace {

using test::C;
using test::makeEndSite;
using test::makeJoint;

Skeleton chain() {
  Skeleton s;
  s.joints.push_back(makeJoint("Hips", -1, {0, 0, 0}, {C::Xposition, C::Yposition, C::Zposition, C::Zrotation, C::Xrotation, C::Yrotation}));
  s.joints.push_back(makeJoint("Spine", 0, {0, 10, 0}, {C::Zrotation, C::Xrotation, C::Yrotation}));
  s.joints.push_back(makeEndSite("Spine_End", 1, {0, 5, 0}));
  return s;
}

Motion chainMotion(int frames) {
  Motion m;
  m.skeleton = chain();
  m.values = MatrixRowMajor::Zero(frames, m.skeleton.channelCount());
  return m;
}

TEST(SkeletonValidate, RejectsAnEmptySkeleton) { EXPECT_THROW(Skeleton{}.validate(), std::invalid_argument); }

TEST(SkeletonValidate, RejectsARootThatIsNotJointZero) {
  Skeleton s = chain();
  s.joints[0].parent = 1;
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

TEST(SkeletonValidate, RejectsAParentThatDoesNotPrecedeItsChild) {
  Skeleton s = chain();
  s.joints[1].parent = 2;
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s.joints[1].parent = 1;  // itself
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s.joints[1].parent = -1;  // a second root
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

TEST(SkeletonValidate, RejectsAChildOfAnEndSite) {
  Skeleton s = chain();
  s.joints.push_back(makeJoint("Beyond", 2, {0, 1, 0}, {C::Xrotation, C::Yrotation, C::Zrotation}));
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

TEST(SkeletonValidate, RejectsEmptyAndDuplicateNames) {
  Skeleton s = chain();
  s.joints[1].name.clear();
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s.joints[1].name = "Hips";
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

TEST(SkeletonValidate, RejectsNonFiniteOffsets) {
  Skeleton s = chain();
  s.joints[1].offset.y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s.joints[1].offset.y() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

TEST(SkeletonValidate, RejectsAnEndSiteWithChannels) {
  Skeleton s = chain();
  s.joints[2].channels = {C::Xrotation};
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

TEST(SkeletonValidate, RejectsRepeatedChannels) {
  Skeleton s = chain();
  s.joints[1].channels = {C::Zrotation, C::Xrotation, C::Zrotation};
  EXPECT_THROW(s.validate(), std::invalid_argument);
  s.joints[1].channels = {C::Xposition, C::Xposition};
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

TEST(SkeletonValidate, RejectsAnUnknownChannelValue) {
  Skeleton s = chain();
  s.joints[1].channels = {static_cast<ChannelType>(7)};
  EXPECT_THROW(s.validate(), std::invalid_argument);
}

TEST(SkeletonValidate, AcceptsWellFormedRigs) {
  EXPECT_NO_THROW(chain().validate());
  EXPECT_NO_THROW(test::mixedSkeleton().validate());
  EXPECT_EQ(chain().channelCount(), 9);
  EXPECT_EQ(chain().channelOffsets(), (std::vector<int>{0, 6, 9}));
}

TEST(MotionValidate, RejectsBadFrameTimes) {
  Motion m = chainMotion(2);
  for (double bad : {0.0, -1.0 / 30.0, std::numeric_limits<double>::quiet_NaN(),
                     std::numeric_limits<double>::infinity()}) {
    m.frame_time = bad;
    EXPECT_THROW(m.validate(), std::invalid_argument) << "frame time " << bad;
  }
}

TEST(MotionValidate, RejectsAColumnCountOtherThanTheSkeletons) {
  Motion m = chainMotion(2);
  m.values = MatrixRowMajor::Zero(2, 8);
  EXPECT_THROW(m.validate(), std::invalid_argument);
}

TEST(MotionValidate, RejectsNonFiniteValues) {
  Motion m = chainMotion(3);
  m.values(2, 4) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(m.validate(), std::invalid_argument);
  m.values(2, 4) = -std::numeric_limits<double>::infinity();
  EXPECT_THROW(m.validate(), std::invalid_argument);
}

TEST(MotionValidate, RejectsAnInvalidSkeleton) {
  Motion m = chainMotion(1);
  m.skeleton.joints[1].parent = 5;
  EXPECT_THROW(m.validate(), std::invalid_argument);
}

TEST(MotionValidate, AcceptsAWellFormedMotionIncludingZeroFrames) {
  EXPECT_NO_THROW(chainMotion(4).validate());
  EXPECT_NO_THROW(chainMotion(0).validate());
}

}  // namespace
}  // namespace motionstyle
