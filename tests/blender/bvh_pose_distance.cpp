// bvh_pose_distance A.bvh B.bvh: how far apart two BVH files' motions are, whatever axes, channel
// layout or rotation orders each file uses. For every frame and every pair of joints present in both
// (by name, end sites left out) it compares the distance between the two joints in A with the same
// distance in B; prints the largest difference in A's units and the frame counts, and exits 0. Why
// distances: Blender writes a file in its own axes (Z up) with position channels on every joint, so
// positions differ by a rotation while a misread rotation order or offset changes the distances.
// Exit 2 for a file that cannot be read or two files without three joints in common.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "bvh/bvh_reader.h"
#include "motion/kinematics.h"

using namespace motionstyle;

namespace {

// Indices (into each skeleton's joints) of the joints both files name, end sites left out.
std::vector<std::pair<int, int>> commonJoints(const Skeleton& a, const Skeleton& b) {
  std::vector<std::pair<int, int>> common;
  for (std::size_t i = 0; i < a.joints.size(); ++i) {
    if (a.joints[i].end_site) continue;
    for (std::size_t j = 0; j < b.joints.size(); ++j)
      if (!b.joints[j].end_site && b.joints[j].name == a.joints[i].name)
        common.emplace_back(static_cast<int>(i), static_cast<int>(j));
  }
  return common;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: bvh_pose_distance A.bvh B.bvh\n");
    return 2;
  }
  try {
    const Motion a = readBvh(argv[1]);
    const Motion b = readBvh(argv[2]);
    const auto common = commonJoints(a.skeleton, b.skeleton);
    if (common.size() < 3) {
      std::fprintf(stderr, "bvh_pose_distance: %zu joints in common\n", common.size());
      return 2;
    }
    const Eigen::MatrixXd world_a = worldPositions(a);  // frames x 3 * joints
    const Eigen::MatrixXd world_b = worldPositions(b);
    const Eigen::Index frames = std::min(world_a.rows(), world_b.rows());
    double worst = 0.0;
    int worst_frame = 0;
    for (Eigen::Index f = 0; f < frames; ++f)
      for (std::size_t p = 0; p < common.size(); ++p)
        for (std::size_t q = p + 1; q < common.size(); ++q) {
          const auto joint = [&](const Eigen::MatrixXd& world, int index) -> Eigen::Vector3d {
            return world.row(f).segment<3>(3 * index).transpose();
          };
          const double da = (joint(world_a, common[p].first) - joint(world_a, common[q].first)).norm();
          const double db = (joint(world_b, common[p].second) - joint(world_b, common[q].second)).norm();
          if (std::abs(da - db) > worst) {
            worst = std::abs(da - db);
            worst_frame = static_cast<int>(f);
          }
        }
    std::printf("frames %d %d joints %zu max_distance_difference %.6g at_frame %d\n", a.frameCount(), b.frameCount(),
                common.size(), worst, worst_frame);
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bvh_pose_distance: %s\n", error.what());
    return 2;
  }
}
