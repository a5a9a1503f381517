#pragma once
// A stylized clip whose foot does not rest on a content contact, for tests of what the clean-up does
// with a stance the style moved (restingContacts: more than kLockableSpreadCm is not locked).

#include <Eigen/Core>
#include <algorithm>

#include "features/feature_layout.h"
#include "style/stylizer.h"

namespace motionstyle::test {

// Moves the left ankle and toe of `clip`'s world positions (its targets) through the first left-heel
// contact of at least 20 frames: linearly from 0 to `cm` horizontally (canonical +X, in the file's
// axes and units) over the stance, and back to 0 over as many frames after it. False when the clip has
// no such stance.
inline bool slideTheLeftFootThroughAStance(style::StylizedClip& clip, double cm) {
  const int heel = static_cast<int>(ContactLabel::LeftHeel), frames = clip.frameCount();
  int stance = -1;
  for (int t = 0, run = 0; t < frames && stance < 0; ++t) {
    run = clip.contacts(heel, t) > 0.5 ? run + 1 : 0;
    if (run == 20) stance = t - 19;
  }
  if (stance < 0) return false;
  int end = stance;
  while (end < frames && clip.contacts(heel, end) > 0.5) ++end;
  const int back = std::min(frames, end + (end - stance));
  const SpaceConvention& convention = clip.anchor.convention;
  const Eigen::Vector3d slide = convention.toFile(Eigen::Vector3d(cm, 0.0, 0.0)) - convention.toFile(Eigen::Vector3d::Zero());
  for (int t = stance; t < back; ++t) {
    const double along = t < end ? double(t - stance) / (end - 1 - stance) : 1.0 - double(t - end + 1) / (back - end);
    for (CanonicalJoint joint : {CanonicalJoint::LeftAnkle, CanonicalJoint::LeftToe})
      clip.world_positions.row(t).segment<3>(3 * index(joint)) += along * slide.transpose();
  }
  return true;
}

}  // namespace motionstyle::test
