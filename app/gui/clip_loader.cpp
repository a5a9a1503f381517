#include "clip_loader.h"

#include <QFileInfo>
#include <QObject>
#include <QStringList>

#include <algorithm>
#include <atomic>
#include <exception>
#include <optional>
#include <stdexcept>

#include "bvh/bvh_reader.h"
#include "features/foot_contacts.h"
#include "ik/contact_file.h"
#include "features/representation.h"
#include "features/rest_pose_frames.h"
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
  const std::string names = guessJointMapping(skeleton).missingNames();
  return names.empty() ? QStringLiteral("inconsistent joint chains") : QStringLiteral("missing ") + QString::fromStdString(names);
}

// Fills the mapping-dependent parts of `clip` (display space, contacts) from clip.mapping.
// The contact tracks saved beside the clip, if any, as its overrides; contacts_note says what came of them.
void readContactsBeside(LoadedClip& clip) {
  clip.contacts_note.clear();
  const std::filesystem::path file = contactTracksPath(clip.path.toStdString());
  if (!clip.isMapped() || !std::filesystem::exists(file)) return;
  const QString name = QString::fromStdString(file.filename().string());
  try {
    loadContactTracksBeside(clip);
    clip.contacts_note = QObject::tr("contacts from %1").arg(name);
  } catch (const InputError& error) {
    clip.contacts_note = QObject::tr("%1 not used: %2").arg(name, QString::fromStdString(error.what()));
  }
}

void prepare(LoadedClip& clip) {
  const Eigen::MatrixXd world = worldPositions(clip.motion);
  clip.detected_contacts.resize(0, 0);
  clip.contact_overrides.resize(0, 0);
  clip.saved_contact_overrides.resize(0, 0);
  if (clip.mapping) {
    requireMeasurableRestPose(clip.motion, *clip.mapping);  // InputError: a flat skeleton is not loaded
    // The convention, floor and contacts as every clean-up front end finds them (foot_contacts.h), on
    // the motion continued over a leading rest pose, as the features and the clean-up see it.
    clip.rest_pose_frames = leadingRestPoseFrames(clip.motion, *clip.mapping);
    FileSpaceGround ground;
    if (clip.rest_pose_frames > 0) {
      ground = detectClipGround(clip.motion, *clip.mapping, clip.rest_pose_frames);
    } else {  // the canonical joints are columns of the world positions already computed
      Eigen::MatrixXd canonical(world.rows(), 3 * kCanonicalJointCount);
      for (int c = 0; c < kCanonicalJointCount; ++c)
        canonical.middleCols<3>(3 * c) = world.middleCols<3>(3 * clip.mapping->joints[static_cast<size_t>(c)]);
      ground = detectFileSpaceGround(clip.motion, *clip.mapping, canonical);
    }
    clip.display_space.convention = ground.convention;
    clip.display_space.floor_height = ground.floor_height;
    clip.detected_contacts = std::move(ground.contacts);
    clip.contact_overrides = Eigen::MatrixXi::Constant(clip.detected_contacts.rows(), kContactCount, -1);
    clip.saved_contact_overrides = clip.contact_overrides;
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
  return QStringLiteral("%1 rig, %2%3, %4 up%5")
      .arg(QString::fromStdString(mapping->convention), QString::fromStdString(c.unit),
           c.unit_guessed ? QStringLiteral(" (guessed)") : QString(), QString::fromStdString(c.up_axis),
           rest_pose_frames > 0 ? QStringLiteral(", frame 0 rest pose") : QString());
}

ContactLabels LoadedClip::effectiveContacts() const {
  if (detected_contacts.size() == 0) return detected_contacts;
  return applyContactOverrides(detected_contacts, contact_overrides);
}

LoadedClip loadClip(const std::filesystem::path& file) {
  LoadedClip clip;
  clip.motion = readBvh(file, /*minimum_frames=*/1);  // a skeleton without motion is not a clip to style
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
  readContactsBeside(clip);
  return clip;
}

bool LoadedClip::hasUnsavedContactEdits() const {
  return contact_overrides.size() > 0 && (contact_overrides.rows() != saved_contact_overrides.rows() ||
                                          contact_overrides.cols() != saved_contact_overrides.cols() ||
                                          contact_overrides != saved_contact_overrides);
}

void loadContactTracksBeside(LoadedClip& clip) {
  const std::filesystem::path file = contactTracksPath(clip.path.toStdString());
  if (!clip.isMapped()) throw InputError(file.string(), 0, "the clip's rig is not mapped: it has no foot contacts");
  Eigen::MatrixXi overrides = contactOverridesFromTracks(loadContactTracks(file), clip.detected_contacts, clip.fps(), file);
  clip.contact_overrides = overrides;
  clip.saved_contact_overrides = std::move(overrides);
}

void saveContactTracksBeside(LoadedClip& clip) {
  const std::filesystem::path file = contactTracksPath(clip.path.toStdString());
  if (!clip.isMapped()) throw InputError(file.string(), 0, "the clip's rig is not mapped: it has no foot contacts");
  ContactTracks tracks;
  tracks.fps = clip.fps();
  tracks.labels = clip.effectiveContacts();
  tracks.overrides = clip.contact_overrides;
  saveContactTracks(tracks, file);
  clip.saved_contact_overrides = clip.contact_overrides;
}

std::shared_ptr<const MotionFeatures> clipFeatures(const LoadedClip& clip) {
  if (!clip.mapping) return nullptr;
  try {
    return std::make_shared<const MotionFeatures>(extractFeatures(clip.motion, *clip.mapping));
  } catch (const std::exception&) {  // std::bad_alloc included: the clip stays open, Stylize reports
    return nullptr;
  }
}

void remapClip(LoadedClip& clip, const std::filesystem::path& mapping_file) {
  LoadedClip remapped = clip;
  remapped.mapping = loadJointMapping(mapping_file, clip.motion.skeleton);
  remapped.mapping_problem.clear();
  prepare(remapped);
  readContactsBeside(remapped);
  clip = std::move(remapped);
}

FigureData figureFromPositions(const QString& name, FigureRole role, const std::vector<int>& parents,
                               const Eigen::MatrixXd& display_positions) {
  FigureData figure;
  figure.name = name;
  figure.role = role;
  figure.parents = parents;
  figure.frame_count = static_cast<int>(display_positions.rows());
  // Eigen is column-major, FigureData frame-major: a transposed copy, by blocks of frames so that both
  // sides stay in the cache (a 36,000-frame clip's 27 MB, once per result).
  const Eigen::Index frames = display_positions.rows(), columns = display_positions.cols();
  figure.positions.resize(static_cast<size_t>(frames) * static_cast<size_t>(columns));
  constexpr Eigen::Index kBlock = 64;
  for (Eigen::Index first = 0; first < frames; first += kBlock) {
    const Eigen::Index last = std::min(frames, first + kBlock);
    for (Eigen::Index c = 0; c < columns; ++c)
      for (Eigen::Index f = first; f < last; ++f)
        figure.positions[static_cast<size_t>(f * columns + c)] = display_positions(f, c);
  }
  return figure;
}

void setFigureContacts(FigureData& figure, const std::array<int, kContactCount>& joints, const Eigen::MatrixXi& labels) {
  figure.contact_joints.assign(joints.begin(), joints.end());
  figure.contacts.assign(static_cast<size_t>(figure.frame_count) * joints.size(), 0);
  for (int f = 0; f < figure.frame_count && f < labels.rows(); ++f)
    for (Eigen::Index k = 0; k < labels.cols() && k < kContactCount; ++k)
      figure.contacts[static_cast<size_t>(f) * joints.size() + static_cast<size_t>(k)] =
          static_cast<std::uint8_t>(labels(f, k) != 0);
}

BodySubtree bodySubtree(const std::vector<int>& parents, int body_root) {
  const int count = static_cast<int>(parents.size());
  BodySubtree subtree;
  if (body_root <= 0 || body_root >= count) {  // the whole figure
    for (int j = 0; j < count; ++j) subtree.kept.push_back(j);
    subtree.new_index = subtree.kept;
    return subtree;
  }
  // Joints descend from their parents in order, so one pass finds the subtree.
  subtree.new_index.assign(static_cast<size_t>(count), -1);
  subtree.new_index[static_cast<size_t>(body_root)] = 0;
  subtree.kept.push_back(body_root);
  for (int j = body_root + 1; j < count; ++j) {
    const int parent = parents[static_cast<size_t>(j)];
    if (parent >= 0 && subtree.new_index[static_cast<size_t>(parent)] >= 0) {
      subtree.new_index[static_cast<size_t>(j)] = static_cast<int>(subtree.kept.size());
      subtree.kept.push_back(j);
    }
  }
  return subtree;
}

FigureData figureInDisplaySpace(const QString& name, FigureRole role, const std::vector<int>& parents,
                                const BodySubtree& body, const Eigen::MatrixXd& file_positions, const DisplaySpace& space) {
  const size_t kept = body.kept.size();
  if (file_positions.cols() != static_cast<Eigen::Index>(3 * parents.size()) || body.new_index.size() != parents.size())
    throw std::invalid_argument("figureInDisplaySpace: the positions, the joints and the body do not match");
  FigureData figure;
  figure.name = name;
  figure.role = role;
  figure.frame_count = static_cast<int>(file_positions.rows());
  figure.parents.assign(kept, -1);
  for (size_t k = 0; k < kept; ++k) {
    const int parent = parents[static_cast<size_t>(body.kept[k])];
    figure.parents[k] = parent >= 0 ? body.new_index[static_cast<size_t>(parent)] : -1;
  }
  // DisplaySpace::toDisplay, the body's joints picked and Eigen's columns turned into FigureData's
  // frames in one pass, by blocks of frames so that both sides stay in the cache.
  const Eigen::Matrix3d& axes = space.convention.axes;
  const double cm_per_unit = space.convention.cm_per_unit;
  const double floor_cm = cm_per_unit * space.floor_height;
  const Eigen::Index frames = file_positions.rows();
  figure.positions.resize(static_cast<size_t>(frames) * kept * 3);
  constexpr Eigen::Index kBlock = 64;
  for (Eigen::Index first = 0; first < frames; first += kBlock) {
    const Eigen::Index last = std::min(frames, first + kBlock);
    for (size_t k = 0; k < kept; ++k) {
      const Eigen::Index column = 3 * body.kept[k];
      for (Eigen::Index f = first; f < last; ++f) {
        Eigen::Vector3d p = cm_per_unit * (axes * file_positions.row(f).segment<3>(column).transpose());
        p.y() -= floor_cm;
        const size_t to = (static_cast<size_t>(f) * kept + k) * 3;
        figure.positions[to] = p.x();
        figure.positions[to + 1] = p.y();
        figure.positions[to + 2] = p.z();
      }
    }
  }
  return figure;
}

void setBodyContacts(FigureData& figure, const BodySubtree& body, std::array<int, kContactCount> joints,
                     const Eigen::MatrixXi& labels) {
  for (int& joint : joints) joint = body.new_index[static_cast<size_t>(joint)];
  // Outside the body (not possible for a mapped rig, whose feet descend from the hips) a marker would
  // point at another joint: none then.
  if (std::find(joints.begin(), joints.end(), -1) == joints.end()) setFigureContacts(figure, joints, labels);
}

FigureData figureFromClip(const LoadedClip& clip, FigureRole role, double display_fps) {
  if (!(display_fps > 0.0)) display_fps = clip.fps();
  std::vector<int> parents;
  parents.reserve(static_cast<size_t>(clip.motion.skeleton.jointCount()));
  for (const Joint& joint : clip.motion.skeleton.joints) parents.push_back(joint.parent);
  const bool same_rate = sameFrameRate(clip.fps(), display_fps);
  if (!clip.mapping)
    return same_rate ? figureFromPositions(clip.name, role, parents, clip.display_positions)
                     : figureFromPositions(clip.name, role, parents, rowsAtRate(clip.display_positions, clip.fps(), display_fps));
  const BodySubtree body = bodySubtree(parents, (*clip.mapping)[CanonicalJoint::Hips]);
  const DisplaySpace as_is;  // display_positions are in display space already
  FigureData figure =
      same_rate ? figureInDisplaySpace(clip.name, role, parents, body, clip.display_positions, as_is)
                : figureInDisplaySpace(clip.name, role, parents, body, rowsAtRate(clip.display_positions, clip.fps(), display_fps), as_is);
  setBodyContacts(figure, body, contactJoints(*clip.mapping),
                  resampleRowsNearest(clip.effectiveContacts(), 1.0 / clip.fps(), display_fps));
  return figure;
}

}  // namespace motionstyle
