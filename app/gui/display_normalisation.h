#pragma once
// =====================================================================================================
// TEMPORARY display normalisation - to be REPLACED by the core's space convention
// (core/features/space_convention.h: detectSpaceConvention with the clip's JointMapping), which knows
// units and up axes properly. Until the app maps joints, this keeps raw files viewable.
// =====================================================================================================

#include <Eigen/Core>

namespace motionstyle {

// File-space world positions (frames x 3*joints, the file's unit and axes) -> display space (cm,
// Y-up, floor at y = 0 on frame 0), by a heuristic on the FIRST frame:
//   - up axis: the axis of largest extent (Y wins unless another is over 10% larger, since most
//     files are Y-up and arm spans rival heights); it is assumed to point along +axis,
//   - rotation of that axis onto +Y (Z-up: (x, y, z) -> (x, z, -y); X-up: (x, y, z) -> (-y, x, z)),
//   - uniform scale so the first frame is 170 cm tall, then a shift putting its lowest joint on y = 0.
// A degenerate first frame (no joints, zero height) is returned rotated but unscaled.
Eigen::MatrixXd normaliseForDisplay(const Eigen::MatrixXd& file_positions);

}  // namespace motionstyle
