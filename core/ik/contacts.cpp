#include "ik/contacts.h"

#include <stdexcept>
#include <string>

namespace motionstyle {

ContactLabels applyContactOverrides(const ContactLabels& automatic, const Eigen::MatrixXi& overrides) {
  if (automatic.cols() != kContactCount || overrides.cols() != kContactCount || overrides.rows() != automatic.rows())
    throw std::invalid_argument("contacts: overrides are " + std::to_string(overrides.rows()) + " x " +
                                std::to_string(overrides.cols()) + ", labels " + std::to_string(automatic.rows()) +
                                " x " + std::to_string(automatic.cols()) + " (expected frames x 4 for both)");
  ContactLabels result = automatic;
  for (Eigen::Index f = 0; f < overrides.rows(); ++f) {
    for (Eigen::Index label = 0; label < kContactCount; ++label) {
      const int value = overrides(f, label);
      if (value < -1 || value > 1)
        throw std::invalid_argument("contacts: override " + std::to_string(value) + " at frame " + std::to_string(f) +
                                    " (expected -1 = auto, 0 = off or 1 = on)");
      if (value >= 0) result(f, label) = value;
    }
  }
  return result;
}

std::vector<ContactSegment> contactSegments(const ContactLabels& labels, int label) {
  std::vector<ContactSegment> segments;
  const Eigen::Index frames = labels.rows();
  for (Eigen::Index f = 0; f < frames;) {
    if (labels(f, label) == 0) {
      ++f;
      continue;
    }
    Eigen::Index end = f;
    while (end + 1 < frames && labels(end + 1, label) != 0) ++end;
    segments.push_back({static_cast<int>(f), static_cast<int>(end)});
    f = end + 1;
  }
  return segments;
}

}  // namespace motionstyle
