#include "clip_loader.h"

#include <QFileInfo>
#include <QStringList>

#include <algorithm>
#include <atomic>

#include "bvh/bvh_reader.h"
#include "common/errors.h"
#include "mapping/canonical_joints.h"
#include "mapping/mapping_file.h"
#include "motion/kinematics.h"
#include "motion/resample.h"

namespace motionstyle {
namespace {

std::uint64_t nextClipId() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

QString missingJoints(const Skeleton& skeleton) {
  QStringList names;
  for (const CanonicalJoint joint : guessJointMapping(skeleton).missing())
    names << QString::fromUtf8(canonicalJointName(joint).data(), static_cast<qsizetype>(canonicalJointName(joint).size()));
  return names.isEmpty() ? QStringLiteral("inconsistent joint chains") : QStringLiteral("missing ") + names.join(QStringLiteral(", "));
}

// Fills the mapping-dependent parts of `clip` (display space, contacts) from clip.mapping.
void prepare(LoadedClip& clip) {
  const Eigen::MatrixXd world = worldPositions(clip.motion);
  clip.detected_contacts.resize(0, 0);
  clip.contact_overrides.resize(0, 0);
  if (clip.mapping) {
    clip.display_space = mappedDisplaySpace(clip.motion, *clip.mapping, world);
    const Eigen::Vector3d up = clip.display_space.convention.fileUp();
    clip.detected_contacts = detectContacts(world, contactJoints(*clip.mapping), up, clip.display_space.floor_height,
                                            clip.fps(), restPoseBodyHeight(clip.motion.skeleton, up));
    clip.contact_overrides = Eigen::MatrixXi::Constant(clip.detected_contacts.rows(), kContactCount, -1);
  } else {
    clip.display_space = unmappedDisplaySpace(clip.motion, world);
  }
  clip.display_positions = clip.display_space.toDisplay(world);
  clip.id = nextClipId();
}

}  // namespace

int LoadedClip::animatedJointCount() const {
  const auto& joints = motion.skeleton.joints;
  return static_cast<int>(std::count_if(joints.begin(), joints.end(), [](const Joint& j) { return !j.end_site; }));
}

QString LoadedClip::mappingStatus() const {
  if (!mapping) return QStringLiteral("unmapped: ") + mapping_problem;
  const SpaceConvention& c = display_space.convention;
  return QStringLiteral("%1 rig, %2%3, %4 up")
      .arg(QString::fromStdString(mapping->convention), QString::fromStdString(c.unit),
           c.unit_guessed ? QStringLiteral(" (guessed)") : QString(), QString::fromStdString(c.up_axis));
}

ContactLabels LoadedClip::effectiveContacts() const {
  if (detected_contacts.size() == 0) return detected_contacts;
  return applyContactOverrides(detected_contacts, contact_overrides);
}

LoadedClip loadClip(const std::filesystem::path& file) {
  LoadedClip clip;
  clip.motion = readBvh(file);
  const QFileInfo info(QString::fromStdString(file.string()));
  clip.path = info.absoluteFilePath();
  clip.name = info.fileName();
  try {
    clip.mapping = mapJoints(clip.motion.skeleton, file.string());
  } catch (const InputError&) {
    // Still viewable; the clips list says what is missing and offers a mapping file.
    clip.mapping_problem = missingJoints(clip.motion.skeleton);
  }
  prepare(clip);
  return clip;
}

void remapClip(LoadedClip& clip, const std::filesystem::path& mapping_file) {
  LoadedClip remapped = clip;
  remapped.mapping = loadJointMapping(mapping_file, clip.motion.skeleton);
  remapped.mapping_problem.clear();
  prepare(remapped);
  clip = std::move(remapped);
}

FigureData figureFromPositions(const QString& name, FigureRole role, const std::vector<int>& parents,
                               const Eigen::MatrixXd& display_positions) {
  FigureData figure;
  figure.name = name;
  figure.role = role;
  figure.parents = parents;
  figure.frame_count = static_cast<int>(display_positions.rows());
  // Eigen is column-major: copy row by row into FigureData's frame-major layout.
  const Eigen::Index columns = display_positions.cols();
  figure.positions.resize(static_cast<size_t>(figure.frame_count) * static_cast<size_t>(columns));
  for (Eigen::Index f = 0; f < display_positions.rows(); ++f)
    for (Eigen::Index c = 0; c < columns; ++c)
      figure.positions[static_cast<size_t>(f * columns + c)] = display_positions(f, c);
  return figure;
}

FigureData figureFromClip(const LoadedClip& clip, FigureRole role, double display_fps) {
  if (!(display_fps > 0.0)) display_fps = clip.fps();
  std::vector<int> parents;
  parents.reserve(static_cast<size_t>(clip.motion.skeleton.jointCount()));
  for (const Joint& joint : clip.motion.skeleton.joints) parents.push_back(joint.parent);
  FigureData figure = figureFromPositions(clip.name, role, parents, rowsAtRate(clip.display_positions, clip.fps(), display_fps));
  if (clip.mapping) {
    const ContactLabels contacts = resampleRowsNearest(clip.effectiveContacts(), 1.0 / clip.fps(), display_fps);
    const auto joints = contactJoints(*clip.mapping);
    figure.contact_joints.assign(joints.begin(), joints.end());
    figure.contacts.resize(static_cast<size_t>(figure.frame_count) * joints.size(), 0);
    for (int f = 0; f < figure.frame_count && f < contacts.rows(); ++f)
      for (Eigen::Index k = 0; k < contacts.cols(); ++k)
        figure.contacts[static_cast<size_t>(f) * joints.size() + static_cast<size_t>(k)] =
            static_cast<std::uint8_t>(contacts(f, k) != 0);
  }
  return figure;
}

}  // namespace motionstyle
