// Invalid input first: every validate step of the clean-up names the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "ik/cleanup.h"
#include "ik_test_support.h"

namespace motionstyle {
namespace {

class CleanupInvalidInput : public ::testing::Test {
 protected:
  Motion clip = test::makeHumanoidClip(12, 60.0);
  JointMapping mapping = test::humanoidMapping(clip.skeleton);
  Eigen::MatrixXd targets = test::canonicalPositions(worldPositions(clip), mapping);
  Eigen::MatrixXi contacts = Eigen::MatrixXi::Zero(12, kContactCount);

  // Runs the clean-up and returns the std::invalid_argument message ("" if it did not throw).
  std::string failure(const JointMapping& map, const Eigen::MatrixXd& t, const Eigen::MatrixXi& c,
                      const Eigen::Vector3d& up = Eigen::Vector3d::UnitY(), double cm_per_unit = 1.0,
                      const CleanupOptions& options = {}) {
    try {
      cleanupMotion(CleanupInput{clip, map, t, c, up, 0.0, cm_per_unit}, options, nullptr);
    } catch (const std::invalid_argument& error) {
      return error.what();
    }
    return "";
  }
};

TEST_F(CleanupInvalidInput, RejectsTargetsWithAnotherFrameCount) {
  const Eigen::MatrixXd shorter = targets.topRows(10);
  EXPECT_NE(failure(mapping, shorter, contacts).find("targets are 10 x 63, expected 12 frames"), std::string::npos);
}

TEST_F(CleanupInvalidInput, RejectsContactsWithAnotherFrameCountOrWidth) {
  EXPECT_NE(failure(mapping, targets, Eigen::MatrixXi::Zero(11, 4)).find("contacts are 11 x 4"), std::string::npos);
  EXPECT_NE(failure(mapping, targets, Eigen::MatrixXi::Zero(12, 2)).find("contacts are 12 x 2"), std::string::npos);
}

TEST_F(CleanupInvalidInput, RejectsTargetsWithoutThreeColumnsPerCanonicalJoint) {
  const Eigen::MatrixXd narrow = targets.leftCols(60);
  EXPECT_NE(failure(mapping, narrow, contacts).find("x 60"), std::string::npos);
}

TEST_F(CleanupInvalidInput, RejectsMappingIndexOutsideTheSkeleton) {
  JointMapping bad = mapping;
  bad.joints[index(CanonicalJoint::LeftWrist)] = clip.skeleton.jointCount();
  EXPECT_NE(failure(bad, targets, contacts).find("outside the skeleton"), std::string::npos);
  bad.joints[index(CanonicalJoint::LeftWrist)] = -1;
  EXPECT_NE(failure(bad, targets, contacts).find("is -1"), std::string::npos);
}

TEST_F(CleanupInvalidInput, RejectsNonFiniteTargets) {
  Eigen::MatrixXd bad = targets;
  bad(7, 20) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(failure(mapping, bad, contacts).find("frame 7 are not finite"), std::string::npos);
  bad(7, 20) = std::numeric_limits<double>::infinity();
  EXPECT_NE(failure(mapping, bad, contacts).find("frame 7"), std::string::npos);
}

TEST_F(CleanupInvalidInput, RejectsContactLabelsOtherThanZeroOrOne) {
  Eigen::MatrixXi bad = contacts;
  bad(3, 1) = 2;
  EXPECT_NE(failure(mapping, targets, bad).find("contact label 2 at frame 3"), std::string::npos);
  bad(3, 1) = -1;
  EXPECT_NE(failure(mapping, targets, bad).find("contact label -1"), std::string::npos);
}

TEST_F(CleanupInvalidInput, RejectsBadSpace) {
  EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d(0, 2, 0)).find("unit vector"), std::string::npos);
  EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), 0.0).find("cm_per_unit"), std::string::npos);
  EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), std::nan("")).find("cm_per_unit"),
            std::string::npos);
}

TEST_F(CleanupInvalidInput, RejectsBadOptions) {
  CleanupOptions options;
  options.contact_weight = -1.0;
  EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), 1.0, options).find("contact_weight"),
            std::string::npos);
  options = {};
  options.solver = CleanupSolver::Ceres;
  options.window_frames = 4;
  options.window_overlap = 4;
  EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), 1.0, options).find("window_overlap"),
            std::string::npos);
  options = {};
  options.max_iterations = 0;
  EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), 1.0, options).find("max_iterations"),
            std::string::npos);
  options = {};
  options.max_total_seconds = 0.0;
  EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), 1.0, options).find("max_total_seconds"),
            std::string::npos);
  options.max_total_seconds = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), 1.0, options).find("max_total_seconds"),
            std::string::npos);
  options = {};
  options.block_frames = 0;
  EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), 1.0, options).find("block_frames"),
            std::string::npos);
  for (const double fps : {-30.0, std::numeric_limits<double>::infinity()}) {
    options = {};
    options.warning_fps = fps;
    EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), 1.0, options).find("warning_fps"),
              std::string::npos);
  }
  for (const double held : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
    options = {};
    options.held_down_warning_cm = held;
    EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), 1.0, options).find("held_down_warning_cm"),
              std::string::npos);
  }
  for (const double shift : {-1.0, std::numeric_limits<double>::quiet_NaN()}) {
    options = {};
    options.lock_shift_cm = shift;
    EXPECT_NE(failure(mapping, targets, contacts, Eigen::Vector3d::UnitY(), 1.0, options).find("lock_shift_cm"),
              std::string::npos);
  }
}

TEST_F(CleanupInvalidInput, RejectsAnEmptyClip) {
  clip.values.resize(0, clip.values.cols());
  EXPECT_NE(failure(mapping, Eigen::MatrixXd(0, 63), Eigen::MatrixXi(0, 4)).find("no frames"), std::string::npos);
}

TEST_F(CleanupInvalidInput, TheSolversLogNeverReachesStderr) {
  // A root 1e308 units away overflows the costs: Ceres 2.1 then logs every failed evaluation through
  // glog (kilobytes per frame) whatever its logging_type. The clean-up must keep stderr quiet.
  clip.values.col(0).setConstant(1e308);
  const Eigen::MatrixXd far_targets = test::canonicalPositions(worldPositions(clip), mapping);
  testing::internal::CaptureStderr();
  try {
    cleanupMotion(CleanupInput{clip, mapping, far_targets, contacts, Eigen::Vector3d::UnitY(), 0.0, 1.0}, {}, nullptr);
  } catch (const std::exception&) {
    // failing is allowed; talking is not
  }
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_LT(log.size(), 200u) << log.substr(0, 2000);
}

TEST_F(CleanupInvalidInput, AcceptsTheValidInput) {
  EXPECT_EQ(failure(mapping, targets, contacts), "");
}

}  // namespace
}  // namespace motionstyle
