#pragma once
// ContactTrackController: the timeline's foot-contact tracks for the content clip, and its quality
// track.
//   - "Left foot" / "Right foot" (TrackView bool tracks 0 and 1) show the content clip's contacts:
//     detected from height and speed (ik/contacts.h) with the user's overrides applied; a foot is in
//     contact when its heel or its toe is.
//   - Painting a track (click-drag) forces heel and toe of that foot on or off over the painted frames:
//     overrides that the next clean-up applies (applyContactOverrides).
//   - Save / Load write and read them beside the clip (ik/contact_file.h: clip.bvh.contacts.json).
//   - Two float tracks (TrackView float tracks 0 and 1, added by the controller) show the result's
//     per-frame quality: the cleaned output's foot skate (cm/s) and the raw network output's bone
//     error (cm; where the IK has to hold bones the network stretched).
// Timeline frames are the content's own frames (MainWindow plays every clip at the content's rate).

#include <QObject>
#include <QString>

#include <Eigen/Core>

#include <functional>
#include <vector>

#include "clip_loader.h"

class QMenu;

namespace motionstyle {

class TrackView;

// Per-frame quality of a result, one value per frame of the content.
struct QualityTracks {
  std::vector<float> skate_cm_s;         // the cleaned output: mean foot speed over the contact tracks
  // The clean-up's locks per content frame (frames x 4, ContactLabel order); empty without a result.
  // A contact of the content's that is not held (the style moved that step) is hatched on its track.
  ContactLabels held_contacts;
  // Where the clean-up lifts a heel or toe off the floor with the style though its contact holds
  // (frames x 4; CleanupReport::lifted_contacts): a foot lifted with none of its joints held down is
  // drawn raised on its track (liftedFootTrack).
  ContactLabels lifted_contacts;
  std::vector<float> raw_bone_error_cm;  // the raw network output: its largest bone-length error (the
                                         // cleaned clip's is zero by construction)
  std::vector<float> familiarity_cm;     // the content: the style network's loss network's
                                         // reconstruction error (style/familiarity.h), before any result
};

class ContactTrackController : public QObject {
  Q_OBJECT

 public:
  using ContentProvider = std::function<LoadedClip*()>;  // the content clip, nullptr when none
  using ErrorReporter = std::function<void(const QString& title, const QString& message)>;
  static constexpr int kLeftFootTrack = 0;
  static constexpr int kRightFootTrack = 1;
  static constexpr int kSkateTrack = 0;  // float tracks
  static constexpr int kRawBoneErrorTrack = 1;
  static constexpr int kFamiliarityTrack = 2;

  // `tracks` must already hold the two foot tracks (indices above).
  ContactTrackController(TrackView* tracks, ContentProvider content, ErrorReporter reporter, QObject* parent = nullptr);

  // Redraws the foot tracks from the content clip (frames beyond it stay empty).
  void refresh();
  // The quality tracks (one value per content frame); empty ones show flat rows (no result yet).
  void setQualityTracks(const QualityTracks& tracks);
  // Adds Save / Load / Reset actions to `menu`.
  void addActions(QMenu* menu);

 public slots:
  // Force heel and toe of `foot` (0 left, 1 right) on or off over frames first..last of the content.
  void overrideFoot(int foot, int first_frame, int last_frame, bool in_contact);
  // Ends the contact of the foot that `contact` (a ContactLabel: a heel or toe) belongs to over frames
  // first..last, as a drag off its track does: the foot's track is what the user sees and edits, so
  // the fix of a held-down warning (CleanupWarning::contact) shows on it. Other values do nothing.
  void endFootContact(int contact, int first_frame, int last_frame);
  void resetOverrides();
  // Beside the clip (contactTracksPath). false and a report on failure.
  bool saveTracks();
  bool loadTracks();

 signals:
  // The content clip's overrides changed (frames x 4, -1/0/1 at the content's rate).
  void overridesChanged(const Eigen::MatrixXi& overrides);

 private:
  TrackView* tracks_;
  ContentProvider content_;
  ErrorReporter reporter_;
};

// Foot `foot` (0 left, 1 right) of contact labels (frames x 4) as a track of `frames` values.
std::vector<bool> footTrack(const ContactLabels& labels, int foot, int frames);

// A result's labels per solved frame (its locks, or its lifted joints: frames x 4 at `locks_fps`) at
// `fps` over `frames` frames (each frame takes the row nearest in time): QualityTracks' held_contacts
// and lifted_contacts.
ContactLabels locksAtRate(const Eigen::MatrixXi& locks, double locks_fps, double fps, int frames);

// Per frame of a foot's track: a contact of that foot (heel or toe, in `contacts`) that `held` does
// not lock. Empty when `held` is.
std::vector<bool> unheldFootTrack(const ContactLabels& contacts, const ContactLabels& held, int foot, int frames);

// Per frame of a foot's track: the foot is in contact in `contacts`, a joint of it is lifted in
// `lifted`, and none is held down (`held` and not lifted): the whole foot off the floor. A heel
// rolling on its held toe is not, nor a toe rolling on a held heel whose own contact has ended.
// Empty when `lifted` is.
std::vector<bool> liftedFootTrack(const ContactLabels& contacts, const ContactLabels& held, const ContactLabels& lifted,
                                  int foot, int frames);

}  // namespace motionstyle
