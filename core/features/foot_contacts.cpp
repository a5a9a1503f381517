#include "features/foot_contacts.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace motionstyle {

void removeShortRuns(Eigen::Ref<Eigen::RowVectorXd> labels, int min_frames) {
  const Eigen::Index n = labels.size();
  // Repeatedly flip the shortest interior run below the limit; each flip merges it with its
  // neighbours, so the loop ends after at most n iterations.
  for (Eigen::Index guard = 0; guard < n; ++guard) {
    Eigen::Index best_start = -1, best_length = min_frames;
    for (Eigen::Index start = 0; start < n;) {
      Eigen::Index end = start;
      while (end < n && labels[end] == labels[start]) ++end;
      const Eigen::Index length = end - start;
      if (start > 0 && end < n && length < best_length) {
        best_start = start;
        best_length = length;
      }
      start = end;
    }
    if (best_start < 0) return;
    const double flipped = labels[best_start] > 0.5 ? 0.0 : 1.0;
    labels.segment(best_start, best_length).setConstant(flipped);
  }
}

Eigen::MatrixXd detectFootContacts(const Eigen::MatrixXd& positions, double fps,
                                   const ContactThresholds& thresholds) {
  if (positions.cols() != 3 * kCanonicalJointCount)
    throw std::invalid_argument("detectFootContacts: expected 63 columns of canonical positions");
  if (!(fps > 0.0)) throw std::invalid_argument("detectFootContacts: fps must be positive");
  const Eigen::Index frames = positions.rows();
  Eigen::MatrixXd contacts = Eigen::MatrixXd::Zero(kContactCount, frames);
  for (int label = 0; label < kContactCount; ++label) {
    const int column = 3 * index(kContactJoint[static_cast<size_t>(label)]);
    const bool is_heel = label == static_cast<int>(ContactLabel::LeftHeel) || label == static_cast<int>(ContactLabel::RightHeel);
    const double max_height = is_heel ? thresholds.heel_height_cm : thresholds.toe_height_cm;
    for (Eigen::Index t = 0; t < frames; ++t) {
      // Central difference inside the clip, one-sided at its ends.
      const Eigen::Index before = t > 0 ? t - 1 : t;
      const Eigen::Index after = t + 1 < frames ? t + 1 : t;
      double speed = 0.0;
      if (after > before)
        speed = (positions.row(after).segment<3>(column) - positions.row(before).segment<3>(column)).norm() * fps /
                static_cast<double>(after - before);
      const double height = positions(t, column + 1);
      contacts(label, t) = (height < max_height && speed < thresholds.max_speed_cm_s) ? 1.0 : 0.0;
    }
    const int min_frames = std::max(1, static_cast<int>(std::lround(thresholds.min_segment_frames * fps / 60.0)));
    Eigen::RowVectorXd row = contacts.row(label);
    removeShortRuns(row, min_frames);
    contacts.row(label) = row;
  }
  return contacts;
}

}  // namespace motionstyle
