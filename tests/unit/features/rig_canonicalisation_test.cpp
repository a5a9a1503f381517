// Rig canonicalisation (features/rig_canonicalisation.h): invalid input first, then the properties the
// representation relies on: girdle bones take the reference's mean direction, every other bone keeps
// its own, the inverse restores the clip exactly, the reference clip is (nearly) unchanged, and the
// clip's own placement comes back through the representation's inverse.
#include <gtest/gtest.h>

#include <cmath>

#include "bvh/bvh_reader.h"
#include "features/representation.h"
#include "features/rig_canonicalisation.h"
#include "mapping/joint_mapping.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

Eigen::Vector3d meanDirection(const Eigen::MatrixXd& features, int c) {
  const int parent = kCanonicalParent[static_cast<std::size_t>(c)];
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Eigen::Index f = 0; f < features.cols(); ++f)
    sum += (features.col(f).segment<3>(3 * c) - features.col(f).segment<3>(3 * parent)).normalized();
  return sum.normalized();
}

MotionFeatures featuresOf(const std::string& fixture, bool canonical_rig) {
  const Motion motion = readBvh(test::fixture(fixture));
  FeatureOptions options;
  options.canonical_rig = canonical_rig;
  return extractFeatures(motion, mapJoints(motion.skeleton, fixture), options);
}

TEST(RigCanonicalisationInvalid, RejectsBadShapes) {
  EXPECT_THROW(measureRigCorrection(Eigen::MatrixXd::Zero(65, 4)), std::invalid_argument);
  EXPECT_THROW(measureRigCorrection(Eigen::MatrixXd::Zero(kFeatureCount, 0)), std::invalid_argument);
  Eigen::MatrixXd wrong = Eigen::MatrixXd::Zero(65, 4);
  EXPECT_THROW(applyRigCorrection(wrong, RigCorrection()), std::invalid_argument);
  // Bones without a direction (all joints at one point) are left alone.
  EXPECT_TRUE(measureRigCorrection(Eigen::MatrixXd::Zero(kFeatureCount, 5)).isIdentity());
}

TEST(RigCanonicalisation, TheReferenceIsSymmetricAndUnitLength) {
  const auto& reference = referenceGirdleDirections();
  for (CanonicalJoint bone : kGirdleBones)
    EXPECT_NEAR(reference[static_cast<std::size_t>(index(bone))].norm(), 1.0, 1e-12);
  const auto mirrored = [](Eigen::Vector3d v) { v.x() = -v.x(); return v; };
  EXPECT_TRUE(reference[static_cast<std::size_t>(index(CanonicalJoint::RightHip))].isApprox(
      mirrored(reference[static_cast<std::size_t>(index(CanonicalJoint::LeftHip))])));
  EXPECT_TRUE(reference[static_cast<std::size_t>(index(CanonicalJoint::RightUpperArm))].isApprox(
      mirrored(reference[static_cast<std::size_t>(index(CanonicalJoint::LeftUpperArm))])));
}

TEST(RigCanonicalisation, GirdleBonesTakeTheReferencePlacementAndTheInverseRestoresTheClip) {
  for (const std::string fixture : {"cmu_131_01.bvh", "zombie.bvh"}) {
    const Eigen::MatrixXd captured = featuresOf(fixture, false).values;
    const RigCorrection correction = measureRigCorrection(captured);
    EXPECT_FALSE(correction.isIdentity());
    Eigen::MatrixXd canonical = captured;
    applyRigCorrection(canonical, correction);
    for (int c = 1; c < kCanonicalJointCount; ++c) {
      bool girdle = false;
      for (CanonicalJoint bone : kGirdleBones) girdle = girdle || index(bone) == c;
      if (girdle) {
        EXPECT_GT(meanDirection(canonical, c).dot(referenceGirdleDirections()[static_cast<std::size_t>(c)]), 1.0 - 1e-9)
            << fixture << " bone " << c;
      } else {  // every other bone keeps its direction and length, frame by frame
        const int parent = kCanonicalParent[static_cast<std::size_t>(c)];
        const Eigen::MatrixXd a = captured.middleRows<3>(3 * c) - captured.middleRows<3>(3 * parent);
        const Eigen::MatrixXd b = canonical.middleRows<3>(3 * c) - canonical.middleRows<3>(3 * parent);
        EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-9) << fixture << " bone " << c;
      }
    }
    Eigen::MatrixXd back = canonical;
    applyRigCorrection(back, correction, /*inverse=*/true);
    EXPECT_LT((back - captured).cwiseAbs().maxCoeff(), 1e-9) << fixture;
  }
}

// The clip's own girdle placement comes back through the representation's inverse: world positions of
// content features equal forward kinematics whether the features were canonicalised or not.
TEST(RigCanonicalisation, TheRepresentationsInverseRestoresTheRigsPlacement) {
  const Motion motion = readBvh(test::fixture("cmu_131_01.bvh"));
  const JointMapping mapping = mapJoints(motion.skeleton, "cmu_131_01.bvh");
  const MotionFeatures canonical = featuresOf("cmu_131_01.bvh", true);
  const MotionFeatures captured = featuresOf("cmu_131_01.bvh", false);
  EXPECT_GT((canonical.values - captured.values).cwiseAbs().maxCoeff(), 1.0);  // it did change the features
  const Eigen::MatrixXd a = canonicalWorldPositions(canonical.values, canonical.anchor);
  const Eigen::MatrixXd b = canonicalWorldPositions(captured.values, captured.anchor);
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-6);
}

}  // namespace
}  // namespace motionstyle
