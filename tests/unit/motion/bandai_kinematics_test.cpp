// Forward kinematics on the licensed Bandai dataset (label "data"; skips when it is absent).
// Bandai files carry 6 channels on every joint; below the root motion (joint_Root -> Hips) the
// position channels restate the offsets, so every bone must keep its length in every frame.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <vector>

#include "bvh/bvh_reader.h"
#include "motion/kinematics.h"
#include "motion/resample.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

// A deterministic spread of files over both datasets: every `stride`-th of the sorted list.
std::vector<std::filesystem::path> sampledFiles(const std::filesystem::path& dir, size_t stride) {
  std::vector<std::filesystem::path> all;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == ".bvh") all.push_back(entry.path());
  std::sort(all.begin(), all.end());
  std::vector<std::filesystem::path> sampled;
  for (size_t n = 0; n < all.size(); n += stride) sampled.push_back(all[n]);
  return sampled;
}

TEST(BandaiKinematics, BonesAreRigidInEveryFrame) {
  MOTIONSTYLE_REQUIRE_BANDAI(dir);
  const std::vector<std::filesystem::path> files = sampledFiles(dir, 97);
  ASSERT_GE(files.size(), 5u);
  double worst_fk = 0.0;
  double worst_data = 0.0;
  for (const std::filesystem::path& file : files) {
    SCOPED_TRACE(file.filename().string());
    const Motion motion = readBvh(file);
    const LocalPoses poses = localPoses(motion);
    const Eigen::MatrixXd world = worldPositions(motion.skeleton, poses);
    for (int j = 1; j < motion.skeleton.jointCount(); ++j) {
      const Joint& joint = motion.skeleton.joints[static_cast<size_t>(j)];
      if (joint.parent == 0) continue;  // Hips: its position channels are the root motion
      const double rest = joint.offset.norm();
      for (int f = 0; f < motion.frameCount(); ++f) {
        const double bone = (world.block<1, 3>(f, 3 * j) - world.block<1, 3>(f, 3 * joint.parent)).norm();
        // FK exactness: the bone is the joint's translation, rotated.
        const double translation = poses.translation(f, j).norm();
        worst_fk = std::max(worst_fk, std::abs(bone - translation) / std::max(translation, 1.0));
        // The data: position channels restate the offset (to the ~6 significant digits files print).
        worst_data = std::max(worst_data, std::abs(bone - rest) / std::max(rest, 1.0));
      }
    }
  }
  std::cout << "checked " << files.size() << " files; worst FK deviation " << worst_fk
            << " (relative), worst bone-length change " << worst_data << " (relative to max(1, |offset|))\n";
  EXPECT_LE(worst_fk, 1e-9);
  EXPECT_LE(worst_data, 1e-6);
}

TEST(BandaiKinematics, ResamplingTo60FpsAgreesAtSharedFrames) {
  MOTIONSTYLE_REQUIRE_BANDAI(dir);
  for (const std::filesystem::path& file : sampledFiles(dir, 241)) {
    SCOPED_TRACE(file.filename().string());
    const Motion motion = readBvh(file);
    const Motion up = resampleMotion(motion, 60.0);  // Bandai is 30 fps ("0.0333333")
    ASSERT_EQ(up.frameCount(), 2 * motion.frameCount() - 1);
    const Eigen::MatrixXd source = worldPositions(motion);
    const Eigen::MatrixXd target = worldPositions(up);
    const double scale = source.cwiseAbs().maxCoeff();
    for (int f = 0; f < motion.frameCount(); ++f)
      ASSERT_LT((target.row(2 * f) - source.row(f)).cwiseAbs().maxCoeff(), 1e-12 * scale) << "frame " << f;
  }
}

}  // namespace
}  // namespace motionstyle
