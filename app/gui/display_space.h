#pragma once
// The viewport's space for a clip: MotionStyle's canonical space (features/space_convention.h: Y-up,
// right-handed, centimetres) with the clip's floor moved to y = 0, found from the clip's joint mapping
// as the core finds it: the up axis from the feet-to-head direction over the whole clip, the unit given
// or guessed from skeletal height.
//
// A clip and everything derived from it in its FILE space (the cleaned output on its skeleton, the
// raw network output's canonical joints) share one DisplaySpace, so they stand on the same floor.

#include <Eigen/Core>

#include <array>
#include <vector>

#include "features/space_convention.h"
#include "motion/motion.h"

namespace motionstyle {

struct DisplaySpace {
  SpaceConvention convention;  // file -> canonical (Y-up cm)
  double floor_height = 0.0;   // file units along convention.fileUp()

  // file_positions: frames x 3*joints, file units and axes. Returns the same shape in cm, Y-up, with
  // the floor at y = 0.
  Eigen::MatrixXd toDisplay(const Eigen::MatrixXd& file_positions) const;
};

// A best effort for a clip that cannot be mapped (no feet or head to find the up axis): +Y up, scaled
// so that the rest pose is 170 cm tall, floor at the lowest joint over the clip. Shown only so that
// the user can see the rig while fixing its mapping.
DisplaySpace unmappedDisplaySpace(const Motion& motion, const Eigen::MatrixXd& file_positions);

// Per-frame rows (positions, one frame per row) from `source_fps` to `target_fps` by linear
// interpolation (resampleRowsLinear), so that clips of any rate play in sync by time on one timeline.
// At the same rate `rows` come back as they are (moved: a long clip's positions are not copied).
Eigen::MatrixXd rowsAtRate(Eigen::MatrixXd rows, double source_fps, double target_fps);

// A per-frame track (one value per frame at track_fps, e.g. a metric) -> one value per frame at fps,
// as rowsAtRate does it: for the timeline's quality tracks.
std::vector<float> trackAtRate(const std::vector<double>& track, double track_fps, double fps);

}  // namespace motionstyle
