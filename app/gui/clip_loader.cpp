#include "clip_loader.h"

#include <QFileInfo>

#include <algorithm>

#include "bvh/bvh_reader.h"
#include "display_normalisation.h"
#include "motion/kinematics.h"

namespace motionstyle {

int LoadedClip::animatedJointCount() const {
  const auto& joints = motion.skeleton.joints;
  return static_cast<int>(std::count_if(joints.begin(), joints.end(), [](const Joint& j) { return !j.end_site; }));
}

LoadedClip loadClip(const std::filesystem::path& file) {
  LoadedClip clip;
  clip.motion = readBvh(file);
  const QFileInfo info(QString::fromStdString(file.string()));
  clip.path = info.absoluteFilePath();
  clip.name = info.fileName();
  clip.display_positions = normaliseForDisplay(worldPositions(clip.motion));
  return clip;
}

FigureData figureFromClip(const LoadedClip& clip, FigureRole role) {
  FigureData figure;
  figure.name = clip.name;
  figure.role = role;
  const Skeleton& skeleton = clip.motion.skeleton;
  figure.parents.reserve(static_cast<size_t>(skeleton.jointCount()));
  for (const Joint& joint : skeleton.joints) figure.parents.push_back(joint.parent);
  figure.frame_count = clip.frameCount();
  // Eigen is column-major: copy row by row into FigureData's frame-major layout.
  const Eigen::Index columns = clip.display_positions.cols();
  figure.positions.resize(static_cast<size_t>(figure.frame_count) * static_cast<size_t>(columns));
  for (Eigen::Index f = 0; f < clip.display_positions.rows(); ++f)
    for (Eigen::Index c = 0; c < columns; ++c)
      figure.positions[static_cast<size_t>(f * columns + c)] = clip.display_positions(f, c);
  return figure;
}

}  // namespace motionstyle
