#pragma once
// A clip as the desktop app holds it: the editable Motion (file units) with its joint mapping and
// contact overrides, plus what is computed from them once (display positions, detected contacts).
// Loading goes through the core (readBvh, mapJoints, worldPositions, detectSpaceConvention,
// detectContacts).

#include <QString>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>

#include "display_space.h"
#include "features/foot_contacts.h"
#include "features/representation.h"
#include "figure_data.h"
#include "ik/contacts.h"
#include "mapping/joint_mapping.h"
#include "motion/motion.h"

namespace motionstyle {

struct LoadedClip {
  // Identity of this clip's current content and mapping: a new id on every load or re-mapping, so
  // that views derived from it (a stylized result) know when they are stale.
  std::uint64_t id = 0;
  QString path;                       // absolute path of the file
  QString name;                       // file name without folder, for lists and the legend
  Motion motion;                      // as read: file units and axes, rotations in degrees
  std::optional<JointMapping> mapping;  // nullopt: the rig could not be mapped (see mapping_problem)
  QString mapping_problem;            // why not, e.g. "missing LeftToe, RightToe"; empty when mapped
  DisplaySpace display_space;         // file -> display (cm, Y-up, floor at 0)
  Eigen::MatrixXd display_positions;  // frames x 3*joints at the clip's own rate, display space
  // Foot contacts at the clip's own rate, frames x 4 (ContactLabel order), 0/1, detected from height
  // and speed; empty when unmapped. Overrides: same shape, -1 automatic / 0 off / 1 on (user edits).
  ContactLabels detected_contacts;
  Eigen::MatrixXi contact_overrides;
  // The overrides as the file beside the clip holds them (ik/contact_file.h; all automatic when there
  // is none): what differs is the user's unsaved work. contacts_note: what loadClip did with that file
  // ("contacts from walk.bvh.contacts.json", or why it was not used); empty when there is none.
  Eigen::MatrixXi saved_contact_overrides;
  QString contacts_note;
  // Leading frames that are the rig's rest pose, not motion (a CMU file's T-pose frame 0): the features,
  // the contacts and the clean-up see the motion continued over them (features/rest_pose_frames.h).
  int rest_pose_frames = 0;

  int frameCount() const { return motion.frameCount(); }
  double fps() const { return motion.fps(); }
  int animatedJointCount() const;  // joints excluding End Sites
  bool isMapped() const { return mapping.has_value(); }
  // For the clips list: "cmu rig, cmu (guessed), +Y up" (convention, length unit, file's up axis; and
  // ", frame 0 rest pose" for a clip that opens with one) or "unmapped: missing LeftToe, RightToe".
  QString mappingStatus() const;
  // Detected contacts with the overrides applied (frames x 4); empty when unmapped.
  ContactLabels effectiveContacts() const;
  // True when the contact overrides differ from those saved beside the clip.
  bool hasUnsavedContactEdits() const;
};

// Reads the contact tracks saved beside `clip` (contactTracksPath) as its overrides, which are then
// saved. Throws InputError naming the file (unreadable, malformed, or of another clip: frames, rate)
// or when the clip is not mapped; the clip is unchanged then.
void loadContactTracksBeside(LoadedClip& clip);
// Writes the clip's effective contacts and overrides beside it, atomically; they are saved then.
// Throws WriteError (the old file stays intact) or InputError when the clip is not mapped.
void saveContactTracksBeside(LoadedClip& clip);

// Reads and prepares a BVH file. A rig that cannot be mapped still loads (unmapped, shown with a best
// -effort display space). Contact tracks saved beside it are its overrides (a file that does not fit
// is left alone and named in contacts_note). Throws InputError (bad or unreadable file) and
// std::bad_alloc; never leaves a partial clip.
LoadedClip loadClip(const std::filesystem::path& file);

// The clip's features (extractFeatures with the default options, as a stylize job reads it), null when
// it is unmapped or cannot be featurised (too short, say: Stylize then says why). For what the GUI
// thread reads from a clip once, when it becomes the content: its familiarity and its locomotion kind.
std::shared_ptr<const MotionFeatures> clipFeatures(const LoadedClip& clip);

// Maps `clip` with a mapping file (mapping/mapping_file.h) and recomputes its display space and
// contacts; the overrides are those saved beside it (or automatic). Throws InputError naming the mapping file; the clip is unchanged then.
void remapClip(LoadedClip& clip, const std::filesystem::path& mapping_file);

// The viewport's view of a clip in a role, resampled to `display_fps` (the timeline's rate, so that
// clips of any rate play in sync by time; <= 0 keeps the clip's own rate), with its effective foot
// contacts when mapped.
FigureData figureFromClip(const LoadedClip& clip, FigureRole role, double display_fps = 0.0);

// Figure data from display positions (frames x 3*joints, one row per frame) and a topology.
FigureData figureFromPositions(const QString& name, FigureRole role, const std::vector<int>& parents,
                               const Eigen::MatrixXd& display_positions);

// The joints of the subtree of `body_root` (the mapped hips) in order, and each joint's index among them
// (-1 outside it); every joint when body_root <= 0 (a rig rooted at its hips). What a figure draws:
// rigs such as Bandai's have a reference root that stays at the world origin while the hips carry the
// motion, and drawing it would put a bone from the origin to the body and place, follow and trace the
// figure by a point that never moves.
struct BodySubtree {
  std::vector<int> kept;
  std::vector<int> new_index;
};
BodySubtree bodySubtree(const std::vector<int>& parents, int body_root);
// The figure of `body`'s joints from FILE positions (frames x 3*joints of the rig whose joints have
// `parents`), in display space (DisplaySpace::toDisplay), in one pass over the clip: no whole-clip
// intermediate copies (a live result of a long clip, once per result). Without contacts. Throws
// std::invalid_argument when the positions, the parents and the body do not match.
FigureData figureInDisplaySpace(const QString& name, FigureRole role, const std::vector<int>& parents,
                                const BodySubtree& body, const Eigen::MatrixXd& file_positions, const DisplaySpace& space);
// setFigureContacts for a figure of `body`'s joints, `joints` numbered in the whole rig (none when a
// contact joint is outside the body).
void setBodyContacts(FigureData& figure, const BodySubtree& body, std::array<int, kContactCount> joints,
                     const Eigen::MatrixXi& labels);

// Gives `figure` its foot-contact markers: `labels` is frames x 4 (at the figure's rate, nonzero = in
// contact) for the figure's joints `joints` (foot_contacts.h order); frames past the labels get none.
void setFigureContacts(FigureData& figure, const std::array<int, kContactCount>& joints, const Eigen::MatrixXi& labels);

}  // namespace motionstyle
