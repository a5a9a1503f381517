#pragma once
// Motion: a skeleton plus its animation channels, exactly as a BVH file holds them (editable data).
// Computed results (local rotations, world positions, features) are derived from it by the kinematics
// and features modules and never stored here.
//
// values(f, c): frame f, channel c in file order (Skeleton::channelOffsets()). Positions are in the
// file's length unit; rotations are Euler angles in DEGREES, composed in the joint's channel order.

#include <Eigen/Core>
#include <string>

#include "motion/skeleton.h"

namespace motionstyle {

using MatrixRowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Motion {
  Skeleton skeleton;
  double frame_time = 1.0 / 60.0;  // seconds per frame, > 0
  MatrixRowMajor values;           // frames x skeleton.channelCount()
  std::string source;              // where it came from (file path), for messages

  int frameCount() const { return static_cast<int>(values.rows()); }
  double fps() const { return 1.0 / frame_time; }
  double durationSeconds() const { return frameCount() * frame_time; }

  // Throws std::invalid_argument on an invalid skeleton, a non-positive or non-finite frame time,
  // a column count that differs from the skeleton's channels, or a non-finite value.
  void validate() const;
};

}  // namespace motionstyle
