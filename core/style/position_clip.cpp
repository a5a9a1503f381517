#include "style/position_clip.h"

#include <stdexcept>

#include "features/feature_layout.h"
#include "mapping/canonical_joints.h"

namespace motionstyle::style {

Motion canonicalPositionsMotion(const Eigen::MatrixXd& world_positions, double fps, const std::string& source) {
  if (world_positions.cols() != 3 * kCanonicalJointCount || world_positions.rows() < 1 || !world_positions.allFinite())
    throw std::invalid_argument("canonicalPositionsMotion: need frames x 63 finite positions, frames >= 1");
  if (!(fps > 0.0)) throw std::invalid_argument("canonicalPositionsMotion: fps must be positive");
  Motion motion;
  motion.source = source;
  motion.frame_time = 1.0 / fps;
  const auto local = [&](Eigen::Index frame, int joint) -> Eigen::Vector3d {
    const Eigen::Vector3d world = world_positions.row(frame).segment<3>(3 * joint).transpose();
    const int parent = kCanonicalParent[static_cast<std::size_t>(joint)];
    if (parent < 0) return world;
    return world - world_positions.row(frame).segment<3>(3 * parent).transpose();
  };
  for (int c = 0; c < kCanonicalJointCount; ++c) {
    Joint joint;
    joint.name = std::string(canonicalJointName(static_cast<CanonicalJoint>(c)));
    joint.parent = kCanonicalParent[static_cast<std::size_t>(c)];
    joint.offset = local(0, c);
    joint.channels = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition};
    motion.skeleton.joints.push_back(joint);
  }
  motion.values.resize(world_positions.rows(), 3 * kCanonicalJointCount);
  for (Eigen::Index f = 0; f < world_positions.rows(); ++f)
    for (int c = 0; c < kCanonicalJointCount; ++c) motion.values.row(f).segment<3>(3 * c) = local(f, c).transpose();
  motion.validate();
  return motion;
}

}  // namespace motionstyle::style
