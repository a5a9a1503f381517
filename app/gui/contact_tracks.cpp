#include "contact_tracks.h"

#include <QFileInfo>
#include <QMenu>

#include <algorithm>
#include <cmath>
#include <exception>

#include "common/errors.h"
#include "features/proportions.h"
#include "ik/contact_file.h"
#include "motion/resample.h"
#include "style/familiarity.h"
#include "style/stylized_cleanup.h"
#include "track_view.h"

namespace motionstyle {
namespace {

// ContactLabel columns of a foot: heel then toe.
std::array<int, 2> footLabels(int foot) {
  return foot == 0 ? std::array<int, 2>{static_cast<int>(ContactLabel::LeftHeel), static_cast<int>(ContactLabel::LeftToe)}
                   : std::array<int, 2>{static_cast<int>(ContactLabel::RightHeel), static_cast<int>(ContactLabel::RightToe)};
}

}  // namespace

std::vector<bool> footTrack(const ContactLabels& labels, int foot, int frames) {
  std::vector<bool> track(static_cast<size_t>(std::max(frames, 0)), false);
  const auto [heel, toe] = footLabels(foot);
  for (Eigen::Index f = 0; f < labels.rows() && f < frames; ++f)
    track[static_cast<size_t>(f)] = labels(f, heel) != 0 || labels(f, toe) != 0;
  return track;
}

ContactLabels locksAtRate(const Eigen::MatrixXi& locks, double locks_fps, double fps, int frames) {
  if (locks.rows() == 0 || locks_fps <= 0.0 || fps <= 0.0 || frames <= 0) return {};
  const Eigen::MatrixXi at_rate = resampleRowsNearest(locks, 1.0 / locks_fps, fps);
  ContactLabels labels(frames, kContactCount);
  for (int f = 0; f < frames; ++f) labels.row(f) = at_rate.row(std::min<Eigen::Index>(f, at_rate.rows() - 1));
  return labels;
}

std::vector<bool> unheldFootTrack(const ContactLabels& contacts, const ContactLabels& held, int foot, int frames) {
  if (held.rows() == 0) return {};
  std::vector<bool> unheld(static_cast<size_t>(std::max(frames, 0)), false);
  for (Eigen::Index f = 0; f < frames && f < contacts.rows() && f < held.rows(); ++f)
    for (int label : footLabels(foot))
      if (contacts(f, label) != 0 && held(f, label) == 0) unheld[static_cast<size_t>(f)] = true;
  return unheld;
}

std::vector<bool> liftedFootTrack(const ContactLabels& contacts, const ContactLabels& held, const ContactLabels& lifted,
                                  int foot, int frames) {
  if (lifted.rows() == 0) return {};
  std::vector<bool> raised(static_cast<size_t>(std::max(frames, 0)), false);
  for (Eigen::Index f = 0; f < frames && f < contacts.rows() && f < held.rows() && f < lifted.rows(); ++f) {
    bool on = false, up = false, down = false;
    for (int label : footLabels(foot)) {
      on = on || contacts(f, label) != 0;
      up = up || lifted(f, label) != 0;
      down = down || (held(f, label) != 0 && lifted(f, label) == 0);
    }
    raised[static_cast<size_t>(f)] = on && up && !down;
  }
  return raised;
}

ContactTrackController::ContactTrackController(TrackView* tracks, ContentProvider content, ErrorReporter reporter,
                                               QObject* parent)
    : QObject(parent), tracks_(tracks), content_(std::move(content)), reporter_(std::move(reporter)) {
  connect(tracks_, &TrackView::trackEdited, this, [this](int track, int first, int last, bool value) {
    if (track == kLeftFootTrack || track == kRightFootTrack) overrideFoot(track, first, last, value);
  });
  // The rows are always there (flat without a result), so the timeline dock keeps one height.
  if (tracks_->floatTrackCount() == 0) {
    tracks_->addFloatTrack(tr("Skate cm/s"), QColor(120, 170, 230));
    tracks_->addFloatTrack(tr("Raw bone cm"), QColor(170, 170, 175));
    tracks_->addFloatTrack(tr("Unfamiliar"), QColor(214, 150, 70));
  }
  setQualityTracks({});
}

void ContactTrackController::refresh() {
  const LoadedClip* clip = content_();
  const ContactLabels labels = clip != nullptr ? clip->effectiveContacts() : ContactLabels();
  for (int foot : {kLeftFootTrack, kRightFootTrack}) tracks_->setBoolValues(foot, footTrack(labels, foot, tracks_->frameCount()));
}

void ContactTrackController::setQualityTracks(const QualityTracks& tracks) {
  // Scales: at least 5 cm/s and 2 cm full height, so that a clean result reads as flat, not as noise
  // blown up.
  const auto top = [](const std::vector<float>& values, float floor) {
    return values.empty() ? floor : std::max(floor, *std::max_element(values.begin(), values.end()));
  };
  tracks_->setFloatValues(kSkateTrack, tracks.skate_cm_s, 0.0f, top(tracks.skate_cm_s, 5.0f));
  // A contact the clean-up did not hold is hatched on its foot's track, a click there holds it; a foot
  // it lifts with the style is drawn raised.
  const LoadedClip* clip = content_();
  const ContactLabels contacts = clip != nullptr ? clip->effectiveContacts() : ContactLabels();
  for (int foot : {kLeftFootTrack, kRightFootTrack}) {
    tracks_->setUnheldFrames(foot, unheldFootTrack(contacts, tracks.held_contacts, foot, tracks_->frameCount()),
                             tr("Not held by the clean-up: the style moved this step more than %1 cm, so the foot "
                                "follows the network here.\nClick or drag over it to hold the foot planted.")
                                 .arg(kLockableSpreadCm));
    tracks_->setLiftedFrames(foot,
                             liftedFootTrack(contacts, tracks.held_contacts, tracks.lifted_contacts, foot,
                                             tracks_->frameCount()),
                             tr("Lifted with the style: the style raises this foot before its contact ends (or "
                                "lands it after it starts), and the clean-up lets it rise, still over its place.\n"
                                "Click or drag over it to end the contact and let the foot move freely."));
  }
  tracks_->setFloatValues(kRawBoneErrorTrack, tracks.raw_bone_error_cm, 0.0f, top(tracks.raw_bone_error_cm, 2.0f));
  // Full height at the "far" threshold, so the row reads against the reading's scale.
  tracks_->setFloatValues(kFamiliarityTrack, tracks.familiarity_cm, 0.0f,
                          top(tracks.familiarity_cm, static_cast<float>(style::kUnusualMaxCm)));
}

void ContactTrackController::overrideFoot(int foot, int first_frame, int last_frame, bool in_contact) {
  LoadedClip* clip = content_();
  if (clip == nullptr || clip->contact_overrides.size() == 0) {
    refresh();  // nothing to edit (no content, or unmapped): undo the painted cells
    return;
  }
  const int last = std::min(last_frame, clip->frameCount() - 1);
  for (int f = std::max(first_frame, 0); f <= last; ++f)
    for (int label : footLabels(foot)) clip->contact_overrides(f, label) = in_contact ? 1 : 0;
  refresh();
  emit overridesChanged(clip->contact_overrides);
}

void ContactTrackController::endFootContact(int contact, int first_frame, int last_frame) {
  for (int foot : {kLeftFootTrack, kRightFootTrack}) {
    const std::array<int, 2> labels = footLabels(foot);
    if (std::find(labels.begin(), labels.end(), contact) != labels.end()) overrideFoot(foot, first_frame, last_frame, false);
  }
}

void ContactTrackController::resetOverrides() {
  LoadedClip* clip = content_();
  if (clip == nullptr || clip->contact_overrides.size() == 0) return;
  clip->contact_overrides.setConstant(-1);
  refresh();
  emit overridesChanged(clip->contact_overrides);
}

bool ContactTrackController::saveTracks() {
  LoadedClip* clip = content_();
  if (clip == nullptr || !clip->isMapped()) {
    reporter_(tr("Could not save the contact tracks"), tr("There is no mapped content clip."));
    return false;
  }
  try {
    saveContactTracksBeside(*clip);
  } catch (const std::exception& error) {
    reporter_(tr("Could not save the contact tracks"), QString::fromStdString(error.what()));
    return false;
  }
  return true;
}

bool ContactTrackController::loadTracks() {
  LoadedClip* clip = content_();
  const QString title = tr("Could not load the contact tracks");
  if (clip == nullptr || !clip->isMapped()) {
    reporter_(title, tr("There is no mapped content clip."));
    return false;
  }
  try {
    loadContactTracksBeside(*clip);
  } catch (const std::exception& error) {
    reporter_(title, QString::fromStdString(error.what()));
    return false;
  }
  refresh();
  emit overridesChanged(clip->contact_overrides);
  return true;
}

void ContactTrackController::addActions(QMenu* menu) {
  menu->addAction(tr("&Save Contact Tracks"), this, &ContactTrackController::saveTracks)
      ->setStatusTip(tr("Save the content clip's foot contacts beside it (.contacts.json)"));
  menu->addAction(tr("&Load Contact Tracks"), this, &ContactTrackController::loadTracks)
      ->setStatusTip(tr("Load the foot contacts saved beside the content clip"));
  menu->addAction(tr("&Reset Contact Edits"), this, &ContactTrackController::resetOverrides);
}

}  // namespace motionstyle
