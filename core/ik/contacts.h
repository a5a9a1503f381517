#pragma once
// Editable contact data on top of the detector (features/foot_contacts.h): the user's per-frame
// overrides and the contact segments the clean-up locks.

#include <Eigen/Core>
#include <vector>

#include "features/foot_contacts.h"

namespace motionstyle {

// User overrides per contact label: -1 = automatic, 0 = forced off, 1 = forced on (frames x 4).
// Returns the labels with the overrides applied. Throws std::invalid_argument on a size mismatch or a
// value outside {-1, 0, 1}.
ContactLabels applyContactOverrides(const ContactLabels& automatic, const Eigen::MatrixXi& overrides);

// Contact segments of one label column: [first, last] frame pairs (inclusive) of consecutive 1s.
struct ContactSegment {
  int first = 0;
  int last = 0;
};
std::vector<ContactSegment> contactSegments(const ContactLabels& labels, int label);

}  // namespace motionstyle
