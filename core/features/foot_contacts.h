#pragma once
// Foot-contact detection from height AND horizontal speed, in ANY space: the caller gives the up axis,
// the floor height and the character's body height in the positions' own unit, and every threshold is
// a fraction of that body height. The ONE detector of the project: the representation's contact labels
// (reference space, features/representation.cpp) and the clean-up's locks (the clip's file space,
// ik/cleanup.cpp, the CLI, the GUI) both come from it. It lives in `features` because the
// representation needs it and `ik` already builds on `features`, not the other way round.
//
// A joint (heel = ankle, toe = ball of the foot) is in contact at frame t when
//     height(t) - floor - rest_height < height_threshold      and
//     horizontal speed(t)             < speed_threshold,
// with hysteresis (a contact only ends once the height or the speed exceeds release_factor x its
// threshold) and no contact or gap shorter than min_segment_seconds (flicker).
// rest_height is the joint's own height above the sole, estimated per clip as a low percentile of its
// height above the floor (a planted foot is the lowest the joint gets), capped at max_rest_height.
//
// Defaults, from the 2016 reference code (notes-from-holden-2016-public-code.md): contact when the
// squared step is < 0.05 CMU units^2 per 60 fps frame and the height is < 3.0 (ankle) / 2.0 (toe) CMU
// units, with 1 CMU unit ~ 1/25 of the body height. That is a 3-D speed < 0.22 units/frame = 0.54 body
// heights/s, and heights of 0.12 / 0.08 body heights ABOVE THE FLOOR, i.e. ~0.05 body heights above the
// joints' rest heights (ankle ~0.05, toe ~0.01 body heights on the CMU fixture). We keep 0.05 body
// heights above rest (8.5 cm on a 170 cm character) but use the HORIZONTAL speed with a much tighter
// 0.15 body heights/s (25 cm/s): the clean-up pins a joint to one point for a whole segment, so a
// segment must hold only planted frames. Measured on tests/data/cmu_131_01.bvh (body 137 cm), heel
// strikes and toe-offs move at 10-25 cm/s while the clip's deliberate slides and pivots run at
// 30-60 cm/s; 0.3 body heights/s (41 cm/s) admitted those slides and the locks then pulled the feet
// up to 7 cm off the clip. The hysteresis (x1.5 to release) keeps a rolling foot in contact, and
// 0.05 s (3 frames at 60 fps, the 2016 code's flicker filter) is the shortest contact or gap kept.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>

#include "features/feature_layout.h"
#include "features/space_convention.h"
#include "mapping/joint_mapping.h"
#include "motion/motion.h"
#include "motion/skeleton.h"

namespace motionstyle {

struct ContactDetectionOptions {
  double height_threshold = 0.05;      // body heights above the joint's rest height
  double speed_threshold = 0.15;       // body heights per second, horizontal
  double release_factor = 1.5;         // hysteresis: leave contact above release_factor x thresholds
  double min_segment_seconds = 0.05;   // shorter contacts and gaps are flicker (3 frames at 60 fps)
  double rest_height_percentile = 0.05;  // of the joint's height above the floor over the clip
  double max_rest_height = 0.10;       // body heights; caps the rest height of a foot that never lands

  // Throws std::invalid_argument on a non-finite or non-positive threshold, release_factor < 1,
  // a negative segment length or a percentile outside [0, 1].
  void validate() const;
};

// Labels of the four contact joints (ContactLabel order), frames x 4, 0 or 1.
using ContactLabels = Eigen::MatrixXi;

// world_positions: frames x (3 * joint count), world positions in any consistent unit and axes.
// foot_joints: the joint (index into world_positions' joints) of each contact label, ContactLabel order.
// up: unit vector; floor_height: along up, positions' unit; fps > 0; body_height > 0, positions' unit.
// Throws std::invalid_argument on an index out of range, a non-unit up, non-finite positions or
// non-positive fps / body height.
ContactLabels detectContacts(const Eigen::MatrixXd& world_positions, const std::array<int, kContactCount>& foot_joints,
                             const Eigen::Vector3d& up, double floor_height, double fps, double body_height,
                             const ContactDetectionOptions& options = {});

// The rest height (height above the floor during contact, positions' unit) detectContacts assumes for
// each contact joint.
std::array<double, kContactCount> estimateRestHeights(const Eigen::MatrixXd& world_positions,
                                                      const std::array<int, kContactCount>& foot_joints,
                                                      const Eigen::Vector3d& up, double floor_height,
                                                      double body_height, const ContactDetectionOptions& options = {});

// The skeleton's joints for the four contact labels (LeftAnkle, LeftToe, RightAnkle, RightToe).
std::array<int, kContactCount> contactJoints(const JointMapping& mapping);
// The same for positions that hold just the 21 canonical joints (frames x 63): their canonical indices.
std::array<int, kContactCount> canonicalContactJoints();

// Body height of a skeleton in its rest pose (all rotations zero): the extent along `up`, file units,
// of the body's joints and End Sites, the body being the first joint that branches (the hips) and
// all below it; joints above it (a static root, a reference node) only place it, and their offsets
// hold where the clip starts, not the body. Falls back to the largest extent along any axis when the
// rest pose lies down (extent along up < 1/4 of that), as a few rigs are built (Bandai's).
double restPoseBodyHeight(const Skeleton& skeleton, const Eigen::Vector3d& up);

// The floor of a clip: a soft minimum (the 2nd percentile over frames) of the lowest contact joint's
// height along up, minus nothing: the caller adds the sole offset if it wants one. Positions' unit.
double estimateFloorHeight(const Eigen::MatrixXd& world_positions, const std::array<int, kContactCount>& foot_joints,
                           const Eigen::Vector3d& up);

// The ground of a clip in its own file space, in the order every clean-up front end needs it:
//   convention = detectSpaceConvention(skeleton, canonical_positions, mapping, unit), up = its fileUp(),
//   floor      = estimateFloorHeight over the contact joints along up,
//   contacts   = detectContacts on that floor with the rest pose's body height (restPoseBodyHeight).
// canonical_positions: frames x 63, the 21 canonical joints in file space (canonicalJointPositions).
// One sequence, so that the CLI, the app and the benchmarks lock the same feet on the same floor.
struct FileSpaceGround {
  SpaceConvention convention;
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  double floor_height = 0.0;  // file units along up
  ContactLabels contacts;     // frames x kContactCount
};
FileSpaceGround detectFileSpaceGround(const Motion& motion, const JointMapping& mapping,
                                      const Eigen::MatrixXd& canonical_positions,
                                      const std::optional<std::string>& unit = std::nullopt);

// The ground as the features and the clean-up see the clip: detectFileSpaceGround on a copy of
// `motion` whose first `rest_pose_frames` frames are replaced by the motion continued
// (rest_pose_frames.h), so a CMU T-pose frame 0 neither lowers the floor nor reads as a contact.
// Frames keep their times: the contacts index the clip's own frames. For callers that only read the
// ground (the app's loader, stylize's saved contact tracks); cleanup replaces the frames in place.
FileSpaceGround detectClipGround(const Motion& motion, const JointMapping& mapping, int rest_pose_frames,
                                 const std::optional<std::string>& unit = std::nullopt);

}  // namespace motionstyle
