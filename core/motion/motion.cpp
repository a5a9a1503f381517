#include "motion/motion.h"

#include <cmath>
#include <stdexcept>

namespace motionstyle {

void Motion::validate() const {
  skeleton.validate();
  if (!(std::isfinite(frame_time) && frame_time > 0.0))
    throw std::invalid_argument("frame time must be positive and finite, got " + std::to_string(frame_time));
  if (values.cols() != skeleton.channelCount())
    throw std::invalid_argument("motion has " + std::to_string(values.cols()) + " channels per frame, skeleton has " +
                                std::to_string(skeleton.channelCount()));
  if (!values.allFinite()) throw std::invalid_argument("motion contains a non-finite channel value");
}

}  // namespace motionstyle
