#pragma once
// Foot-contact labels from height AND velocity (velocity alone misfires on slow swings and shuffles).
//
// Works in REFERENCE space (Y-up, floor at y = 0, the character scaled to kReferenceSkeletalHeightCm),
// so one set of thresholds fits every character: they scale with its size by construction.
// Defaults follow Holden et al. 2016 (height < 3.0 / 2.0 CMU units for ankle / toe, squared step
// < 0.05 units^2 per 60 fps frame), converted at 1 CMU unit = 127 / 21.4 = 5.9 reference cm.

#include <Eigen/Core>

#include "features/feature_layout.h"

namespace motionstyle {

struct ContactThresholds {
  double heel_height_cm = 17.8;   // ankle joint above the floor, reference cm
  double toe_height_cm = 11.9;    // toe joint above the floor, reference cm
  double max_speed_cm_s = 80.0;   // 3-D speed of the joint, reference cm per second
  int min_segment_frames = 3;     // shorter contacts or gaps (at 60 fps) are flicker and get merged away
};

// positions: frames x 63, reference-space world positions of the canonical joints.
// Returns kContactCount x frames of 0/1 (rows in ContactLabel order). fps > 0.
Eigen::MatrixXd detectFootContacts(const Eigen::MatrixXd& positions, double fps,
                                   const ContactThresholds& thresholds = {});

// Removes runs (of either value) shorter than min_frames from a 0/1 row, longest-first, so that the
// result has no flicker. Runs touching the clip's ends are kept.
void removeShortRuns(Eigen::Ref<Eigen::RowVectorXd> labels, int min_frames);

}  // namespace motionstyle
