#pragma once
// Whose root path and timing a stylized clip follows.
//
//   Content (the default): the content's. The output's root velocities (sideways, forward, turning;
//     feature_layout.h) are replaced by the content's, so the character covers the same ground, turns
//     the same way and arrives at the same time: what an animator placing a character in a scene needs.
//     Style networks are trained with the trajectory term (eq. 9) so that their steps fit that pace.
//   Style: the style network's own root motion: the style may change the pace (an elderly walk
//     covers less ground) and, a little, the path.
// Applied to the stylized features before they are turned into world positions (stylizer.h) and to the
// optimisation method's output (optimization_transfer.h).

#include <Eigen/Core>
#include <optional>
#include <string>

namespace motionstyle::style {

enum class PathMode { Content, Style };

// "content", "style"
const char* pathModeName(PathMode mode);
std::optional<PathMode> parsePathMode(const std::string& name);

// output and content: 66 x frames each (same count). PathMode::Content copies the content's three root
// velocity rows into output; Style leaves it. Throws std::invalid_argument on a shape mismatch.
void applyPathMode(Eigen::MatrixXd& output, const Eigen::MatrixXd& content, PathMode mode);

}  // namespace motionstyle::style
