#pragma once
// The path a clip's root travels, read from its features' root velocities (feature_layout.h):
//   root(0) = 0, heading(0) = 0;  root(t+1) = root(t) + R(heading(t)) (v_x(t), v_z(t));
//   heading(t+1) = heading(t) + w(t)
// in reference cm and radians, relative to the clip's first frame. Used to compare a stylized clip's
// path with its content's ("keep the path") and to enforce it.

#include <Eigen/Core>
#include <vector>

#include "features/space_convention.h"
#include "mapping/joint_mapping.h"
#include "motion/motion.h"

namespace motionstyle {

struct RootPathSummary {
  double distance_cm = 0.0;                               // sum of |(v_x, v_z)| over the frames
  Eigen::Vector2d displacement = Eigen::Vector2d::Zero();  // root(end) - root(0), start frame's axes
  double heading_change = 0.0;                             // heading(end) - heading(0), radians
};

// The root at the start of each frame t = 0..frames (the last: after the clip's last step), by the
// formula above from root(0) = start_place, heading(0) = start_heading. Frame t's root-frame point p
// lies on the floor at place + R(heading) (p_x, p_z), R(h) (x, z) = (cos h x + sin h z, -sin h x + cos h z).
struct RootFrame {
  Eigen::Vector2d place = Eigen::Vector2d::Zero();
  double heading = 0.0;
  Eigen::Vector2d toWorld(double x, double z) const;            // a root-frame point's place on the floor
  Eigen::Vector2d toRootFrame(const Eigen::Vector2d& q) const;  // the inverse: (x, z) of a place q
};

// features: 66 x frames. Throws std::invalid_argument for another row count.
std::vector<RootFrame> rootFrames(const Eigen::MatrixXd& features, const Eigen::Vector2d& start_place = Eigen::Vector2d::Zero(),
                                  double start_heading = 0.0);

// features: 66 x frames. Throws std::invalid_argument for another row count.
RootPathSummary summariseRootPath(const Eigen::MatrixXd& features);

// How far `output` strays from `content` (both summaries of clips of the same character):
//   distance_ratio      = output.distance / content.distance (1 when both are 0)
//   end_error_fraction  = |output.displacement - content.displacement| / content.distance
//   heading_error       = |output.heading_change - content.heading_change|, radians
struct RootPathComparison {
  double distance_ratio = 1.0;
  double end_error_fraction = 0.0;
  double heading_error = 0.0;
};
RootPathComparison compareRootPaths(const RootPathSummary& content, const RootPathSummary& output);

// The same from where a character actually goes: `ground` is frames x 2, the hips projected on the
// floor in cm (any fixed axes), smoothed over `smoothing_frames` (a Gaussian's sigma: the hips sway
// from step to step, the path does not) before the distance is summed. heading_change stays 0.
RootPathSummary summariseGroundPath(const Eigen::MatrixXd& ground, double smoothing_frames);

// How far a clip on the same skeleton (a stylized, cleaned output) strays from the content's path,
// from the mapped hips on the floor of each, smoothed like the representation's root (3 frames at
// 60 fps). Both clips must share the skeleton, mapping and space convention.
RootPathComparison compareClipPaths(const Motion& content, const Motion& output, const JointMapping& mapping,
                                    const SpaceConvention& convention);

}  // namespace motionstyle
