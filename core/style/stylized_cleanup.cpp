#include "style/stylized_cleanup.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "features/foot_contacts.h"
#include "features/proportions.h"
#include "features/rest_pose_frames.h"
#include "ik/contacts.h"
#include "motion/kinematics.h"
#include "motion/resample.h"

namespace motionstyle::style {
namespace {

Eigen::MatrixXi contactsPerFrame(const Eigen::MatrixXd& contacts) {
  return (contacts.transpose().array() > 0.5).cast<int>().matrix();
}

// Overrides at the content's rate -> `frames` frames at `fps` (nearest frame in time), "automatic"
// where the schedule comes out short.
Eigen::MatrixXi overridesAtRate(const Eigen::MatrixXi& overrides, double content_fps, double fps, Eigen::Index frames) {
  const Eigen::MatrixXi at_rate = resampleRowsNearest(overrides, 1.0 / content_fps, fps);
  Eigen::MatrixXi out = Eigen::MatrixXi::Constant(frames, kContactCount, -1);
  const Eigen::Index rows = std::min(frames, at_rate.rows());
  out.topRows(rows) = at_rate.topRows(rows);
  return out;
}

// The content's contact segments on which the stylized foot really rests: a segment is kept when the
// output's foot joint stays within kLockableSpreadCm of its median position over the segment
// (horizontally, the character's cm). A style that moves a step further than that puts the foot
// elsewhere for the stance; locking it there would drag the leg after a foot the network put 20+ cm
// away. The spread, not the path length: the network's feet jitter by 0.5-1.5 cm a frame, which summed
// over a stance reads as 30-100 cm/s of travel for a foot that stays put, and a rule on it (until the
// twentieth session) locked 0-14 % of the content's stances and left the rest sliding
// (docs/decisions.md, "Feet that slid where the tracks said planted").

Eigen::MatrixXi restingContacts(const Eigen::MatrixXi& content_contacts, const StylizedClip& stylized) {
  Eigen::MatrixXi kept = Eigen::MatrixXi::Zero(content_contacts.rows(), content_contacts.cols());
  const SpaceConvention& convention = stylized.anchor.convention;
  const Eigen::Vector3d up = convention.fileUp();
  const Eigen::Vector3d across = up.unitOrthogonal();  // two horizontal axes
  const Eigen::Vector3d ahead = up.cross(across);
  std::vector<Eigen::Vector2d> feet;
  std::vector<double> along;
  for (int label = 0; label < kContactCount; ++label) {
    const int column = 3 * index(kContactJoint[static_cast<std::size_t>(label)]);
    for (const ContactSegment& segment : contactSegments(content_contacts, label)) {
      feet.clear();
      for (int f = segment.first; f <= segment.last; ++f) {
        const Eigen::Vector3d p = stylized.world_positions.block<1, 3>(f, column).transpose();
        feet.emplace_back(across.dot(p), ahead.dot(p));
      }
      Eigen::Vector2d median;
      for (int axis = 0; axis < 2; ++axis) {
        along.clear();
        for (const Eigen::Vector2d& foot : feet) along.push_back(foot[axis]);
        std::nth_element(along.begin(), along.begin() + static_cast<std::ptrdiff_t>(along.size() / 2), along.end());
        median[axis] = along[along.size() / 2];
      }
      double spread = 0.0;
      for (const Eigen::Vector2d& foot : feet) spread = std::max(spread, (foot - median).norm());
      if (spread * convention.cm_per_unit <= kLockableSpreadCm)
        kept.block(segment.first, label, segment.last - segment.first + 1, 1).setOnes();
    }
  }
  return kept;
}

// `rows` cut or extended (holding the last row) to `frames` rows; empty rows stay empty. A clip taken
// to 60 fps and back at a rate that does not divide 60 (24, 25 fps), or solved at 60 fps and taken
// back to 120, can come back a frame short.
template <typename Matrix>
Matrix fitRows(Matrix rows, Eigen::Index frames) {
  const Eigen::Index had = rows.rows();
  if (had == frames || had == 0) return rows;
  rows.conservativeResize(frames, Eigen::NoChange);
  for (Eigen::Index f = had; f < frames; ++f) rows.row(f) = rows.row(had - 1);
  return rows;
}

}  // namespace

double fileFloorHeight(const FeatureAnchor& anchor) {
  // Reference cm -> canonical cm -> file units; the up axis is the same line in both spaces.
  return anchor.floor_height / anchor.scale / anchor.convention.cm_per_unit;
}

StylizedCleanup cleanUpStylizedClip(const Motion& clip, const JointMapping& mapping, const StylizedClip& stylized,
                                    const CleanupOptions& options, double output_fps,
                                    const Eigen::MatrixXi& contact_overrides,
                                    const CleanupControl& control) {
  // The features saw the motion continued backward over the clip's rest-pose frames: so does the
  // solve, and the output gets the clip's own back at the end.
  const int rest_pose_frames = stylized.anchor.rest_pose_frames;
  if (rest_pose_frames < 0 || rest_pose_frames >= clip.frameCount())
    throw std::invalid_argument("cleanUpStylizedClip: the stylized clip replaced " + std::to_string(rest_pose_frames) +
                                " rest-pose frames of a content of " + std::to_string(clip.frameCount()));
  std::optional<Motion> replaced;
  if (rest_pose_frames > 0) {
    replaced = clip;
    replaceRestPoseFrames(*replaced, rest_pose_frames);
  }
  const Motion& content = replaced ? *replaced : clip;
  if (contact_overrides.size() > 0 &&
      (contact_overrides.rows() != content.frameCount() || contact_overrides.cols() != kContactCount))
    throw std::invalid_argument("cleanUpStylizedClip: contact overrides are " + std::to_string(contact_overrides.rows()) +
                                " x " + std::to_string(contact_overrides.cols()) + ", expected " +
                                std::to_string(content.frameCount()) + " x 4 (the content's frames)");
  const bool same_rate = sameFrameRate(content.fps(), stylized.fps);
  const int content_frames_at_stylized_rate =
      same_rate ? content.frameCount()
                : static_cast<int>(resampleSchedule(content.frameCount(), content.frame_time, stylized.fps).size());
  if (content_frames_at_stylized_rate != stylized.frameCount())
    throw std::invalid_argument("cleanUpStylizedClip: the stylized clip has " + std::to_string(stylized.frameCount()) +
                                " frames, its content " + std::to_string(content_frames_at_stylized_rate) +
                                " at the same rate");
  // The solve runs at the content's rate when it is below the network's (what is exported: a 30 fps
  // clip is solved on its 500 frames, not on 999 at 60 fps), else at the network's (120 fps content:
  // the targets have no more to say between their frames).
  const bool solve_at_content_rate = same_rate || content.fps() < stylized.fps;
  const double solve_fps = solve_at_content_rate ? content.fps() : stylized.fps;
  const Motion at_rate = solve_at_content_rate ? content : resampleMotion(content, stylized.fps);
  const FeatureAnchor& anchor = stylized.anchor;
  const Eigen::Vector3d up = anchor.convention.fileUp();
  const double floor = fileFloorHeight(anchor);
  // Locks: the content's contacts OR those detected on the output. The content's labels are what the
  // network was trained to respect (the foot loss), frame for frame (the networks keep the clip's
  // timing), and they judge the raw output. Detection on the raw output alone misses most of them:
  // its feet slide at 70-100 cm/s where the content is planted, above any speed threshold (measured
  // on a held-back Bandai run with three style networks: 0-6 contact frames of 159, vs 15-35 per
  // foot joint in the content), so the clean-up locked almost nothing and the cleaned feet still slid
  // at 60-90 cm/s there. Contacts found on the output as well keep any stance a style lengthens. A
  // content contact on which the output's foot does not rest (restingContacts: the style moved the
  // step) is not locked. The user's overrides (edited tracks) come last and win.
  // The output's own stances are read without the detector's hysteresis: it keeps a rolling foot in
  // the content's contact, but on the output it held a stance while the style lifted the foot up to
  // 1.5x the height threshold, and the clean-up locked the rising foot down (elderly at free pace on a
  // feminine run: the heel 8-9 cm under its targets, the toe pushed 3.4 cm through the floor;
  // docs/decisions.md, "The output's own stances without hysteresis").
  ContactDetectionOptions output_stances;
  output_stances.release_factor = 1.0;
  const Eigen::MatrixXi content_contacts = contactsPerFrame(stylized.contacts);
  Eigen::MatrixXi contacts =
      restingContacts(content_contacts, stylized)
          .cwiseMax(detectContacts(stylized.world_positions, canonicalContactJoints(), up, floor, stylized.fps,
                                   restPoseBodyHeight(content.skeleton, up), output_stances));
  // The tracks the user sees and edits: the content's contacts under the user's overrides.
  Eigen::MatrixXi tracks = content_contacts;
  if (contact_overrides.size() > 0) {
    const Eigen::MatrixXi overrides = overridesAtRate(contact_overrides, content.fps(), stylized.fps, stylized.frameCount());
    contacts = applyContactOverrides(contacts, overrides);
    tracks = applyContactOverrides(tracks, overrides);
  }

  StylizedCleanup result;
  result.fps = solve_fps;
  result.contacts = fitRows(resampleRowsNearest(contacts, 1.0 / stylized.fps, solve_fps), at_rate.frameCount());
  const Eigen::MatrixXd targets =
      fitRows(resampleRowsLinear(stylized.world_positions, 1.0 / stylized.fps, solve_fps), at_rate.frameCount());
  const CleanupInput input(at_rate, mapping, targets, result.contacts, up, floor, anchor.convention.cm_per_unit);
  // The clean-up's own world positions serve the metrics below (computing them again from the channel
  // values cost a live edit 1-1.5 ms for a 500-frame clip).
  Eigen::MatrixXd cleaned_world;
  // Its warnings name the frames of the clip that comes out (a 120 fps clip is solved at 60 fps).
  const double target_fps = output_fps > 0.0 ? output_fps : content.fps();
  CleanupOptions named_options = options;
  if (named_options.warning_fps <= 0.0) named_options.warning_fps = target_fps;
  Motion cleaned = cleanupMotion(input, named_options, &result.report, control, &cleaned_world);

  // Raw output: canonical joints only, at the network's rate, judged against the content's own
  // canonical bone lengths.
  const Eigen::MatrixXd content_world = worldPositions(at_rate);
  MetricsInput raw(stylized.world_positions, identityCanonicalJoints(), canonicalBones(content_world, mapping));
  raw.contacts = content_contacts;
  raw.up = up;
  raw.floor_height = floor;
  raw.cm_per_unit = anchor.convention.cm_per_unit;
  raw.fps = stylized.fps;
  result.raw = computeMetrics(raw);

  MetricsInput after(cleaned_world, mapping.joints, skeletonBones(cleaned.skeleton));
  // Skate over the tracks the user sees: over the locks it is 0 by construction and says nothing. A
  // foot skates on the floor: the frames where the clean-up lifts a joint with the style are left out.
  after.contacts = fitRows(resampleRowsNearest(tracks, 1.0 / stylized.fps, solve_fps), at_rate.frameCount());
  after.contacts.array() *= 1 - result.report.lifted_contacts.array();
  after.targets = targets;
  after.up = up;
  after.floor_height = floor;
  after.cm_per_unit = anchor.convention.cm_per_unit;
  after.fps = solve_fps;
  result.cleaned = computeMetrics(after);

  result.motion = sameFrameRate(cleaned.fps(), target_fps) ? std::move(cleaned) : resampleMotion(cleaned, target_fps);
  // Back at the content's rate the clip can come out a frame or two short (720 frames at 120 fps are
  // 360 at 60 fps, which give 719 at 120 fps): the content's last frames lie past the last solved one.
  // They hold that pose, as resampling does past the end, so that the export has the content's count.
  if (sameFrameRate(target_fps, content.fps()) && result.motion.values.rows() < content.frameCount())
    result.motion.values = fitRows(std::move(result.motion.values), content.frameCount());
  restoreRestPoseFrames(result.motion, clip, rest_pose_frames);
  result.motion.source = content.source;
  return result;
}

}  // namespace motionstyle::style
