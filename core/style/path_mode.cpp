#include "style/path_mode.h"

#include <stdexcept>

#include "features/feature_layout.h"

namespace motionstyle::style {

const char* pathModeName(PathMode mode) { return mode == PathMode::Content ? "content" : "style"; }

std::optional<PathMode> parsePathMode(const std::string& name) {
  if (name == "content") return PathMode::Content;
  if (name == "style") return PathMode::Style;
  return std::nullopt;
}

void applyPathMode(Eigen::MatrixXd& output, const Eigen::MatrixXd& content, PathMode mode) {
  if (output.rows() != kFeatureCount || content.rows() != kFeatureCount || output.cols() != content.cols())
    throw std::invalid_argument("applyPathMode: output and content must both be 66 x frames of the same length");
  if (mode == PathMode::Content) output.middleRows<3>(kSidewaysVelocity) = content.middleRows<3>(kSidewaysVelocity);
}

}  // namespace motionstyle::style
