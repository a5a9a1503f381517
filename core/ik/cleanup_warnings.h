#pragma once
// Private to core/ik: the clean-up report's residual figures and warnings (unreachable targets,
// joints left far from their targets), computed from the result's world positions.

#include <Eigen/Core>
#include <string>

#include "ik/cleanup.h"
#include "motion/kinematics.h"

namespace motionstyle::ik_detail {

// Fills report.mean/max_position_residual_cm and appends warnings such as
// "targets unreachable: left arm stretched by 12.0 cm at frames 40-60".
// result_world: frames x 3J world positions of the cleaned clip, file units.
void addCleanupWarnings(const CleanupInput& input, const CleanupOptions& options, const LocalPoses& content_poses,
                        const Eigen::MatrixXd& result_world, CleanupReport& report);

// "12.3" (fixed, `decimals` digits).
std::string formatFixed(double value, int decimals);

}  // namespace motionstyle::ik_detail
