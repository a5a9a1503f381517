#pragma once
// Kinematics over a Motion (computed results, never stored in Motion).
//
// Conventions (BVH): column vectors; a joint's channels compose in file order, e.g.
// "Zrotation Xrotation Yrotation" gives R = Rz(a) * Rx(b) * Ry(c) (angles in degrees in the file,
// radians nowhere outside rotation.h). A joint's local transform is T(t) * R, where t is the joint's
// position channels when it has them (they REPLACE the offset, as Bandai-style files that carry 6
// channels on every joint expect) and its OFFSET otherwise. A joint with only some position channels
// (rare) replaces those components and keeps the offset's others. World = parent_world * local.
// Euler <-> quaternion conversions are those of rotation.h (also for joints with 1 or 2 rotation
// channels).
// Lengths stay in the file's unit and axes stay the file's: see features/space_convention.h for normalisation.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>
#include <vector>

#include "motion/motion.h"

namespace motionstyle {

// Local joint transforms of every frame. Index [frame * jointCount + joint].
struct LocalPoses {
  int frames = 0;
  int joints = 0;
  std::vector<Eigen::Quaterniond> rotations;  // unit quaternions
  std::vector<Eigen::Vector3d> translations;  // file units

  const Eigen::Quaterniond& rotation(int frame, int joint) const { return rotations[at(frame, joint)]; }
  const Eigen::Vector3d& translation(int frame, int joint) const { return translations[at(frame, joint)]; }
  Eigen::Quaterniond& rotation(int frame, int joint) { return rotations[at(frame, joint)]; }
  Eigen::Vector3d& translation(int frame, int joint) { return translations[at(frame, joint)]; }
  size_t at(int frame, int joint) const { return static_cast<size_t>(frame) * static_cast<size_t>(joints) + static_cast<size_t>(joint); }
};

// Channel values -> local transforms (End Sites: identity rotation, their offset). Validates the motion
// (std::invalid_argument from Motion::validate).
LocalPoses localPoses(const Motion& motion);

// The local transforms of frames first .. first + count - 1 only (frame 0 of the result is `first`).
// Validates the skeleton and those frames' values, not the others': a long clip is walked block by
// block in time and memory proportional to the block. std::invalid_argument for a range outside the clip.
LocalPoses localPoses(const Motion& motion, int first, int count);

// Local transforms -> channel values, written into motion.values (resized to poses.frames rows),
// decomposing each rotation into the joint's own Euler order and writing translations into its
// position channels. Joints without rotation channels must have identity rotations (to 1e-6 rad);
// translation components without a position channel must equal the offset's (to 1e-6 relative to
// max(1, |offset|)); std::invalid_argument otherwise, and for non-finite poses or a size mismatch
// (motion is then unchanged). Joints with 1 or 2 rotation channels receive the projection described in
// rotation.h. Continuity: every frame takes the Euler solution nearest the previous frame's angles;
// frame 0 takes the one nearest the motion's current frame 0 when it has one (so a round trip keeps
// the file's angle ranges), else the principal solution.
void setLocalPoses(const LocalPoses& poses, Motion& motion);

// The channel values (poses.frames x skeleton.channelCount()) setLocalPoses writes, with the same
// checks; frame 0 continues from `seed_row` (a channel row, e.g. the previous block's last frame) when
// it is not null. Why: a clip converted block by block gets the same Euler branches as in one piece.
MatrixRowMajor channelValues(const Skeleton& skeleton, const LocalPoses& poses, const double* seed_row);

// channelValues for the listed joints only, written into `values` (poses.frames x channelCount); every
// other column is left as it is. Why: the clean-up changes only the joints it solves; the others keep
// the content's own values exactly, without a round trip through quaternions. Same checks for the
// listed joints; std::invalid_argument also for a joint index outside the skeleton or values of
// another shape.
void writeChannelValues(const Skeleton& skeleton, const LocalPoses& poses, std::span<const int> joints,
                        const double* seed_row, MatrixRowMajor& values);

// World positions of every joint (file units, file axes), frames x (3 * jointCount):
// row f = x0 y0 z0 x1 y1 z1 ... Rotations must be unit quaternions. std::invalid_argument when the
// poses do not match the skeleton or a parent does not precede its child. Allocates only the result
// and per-joint scratch (the overload below with every joint wanted).
Eigen::MatrixXd worldPositions(const Skeleton& skeleton, const LocalPoses& poses);
inline Eigen::MatrixXd worldPositions(const Motion& motion) { return worldPositions(motion.skeleton, localPoses(motion)); }

// World positions (file units, file axes) of the `wanted` joints only (indices into skeleton.joints,
// repeats allowed), frames x (3 * wanted.size()): row f = x y z of wanted[0], then wanted[1], ...
// Forward kinematics visits only the wanted joints and their ancestors, a block of frames at a time
// (vectorised), so asking for a few joints costs a fraction of the full call. Rotations must be unit
// quaternions. std::invalid_argument as above, and for a wanted index outside the skeleton.
Eigen::MatrixXd worldPositions(const Skeleton& skeleton, const LocalPoses& poses, std::span<const int> wanted);

// The same for a whole motion, walked a block of frames at a time (kMotionBlockFrames), so the local
// transforms of a long clip (56 bytes per joint and frame) are never all held at once.
Eigen::MatrixXd worldPositions(const Motion& motion, std::span<const int> wanted);
inline constexpr int kMotionBlockFrames = 1024;

// World rotation of every joint (joint frame -> world), same indexing as LocalPoses.
std::vector<Eigen::Quaterniond> worldRotations(const Skeleton& skeleton, const LocalPoses& poses);

}  // namespace motionstyle
