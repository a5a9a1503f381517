#pragma once
// LiveResolution: what the user's hand is doing on the controls, for the live results.
//
// Contract: call resultShown() just before a new result is painted. If the hand is on a control then
// (a mouse button held: a strength drag, a contact stroke; or a key held down: the slider's arrow key
// repeating), every step brings a new result: the viewport renders at half the pixels across and down
// (SkeletonViewport::setReducedResolution) until the hand lets go, when it renders the result at full
// resolution and emits handReleased(). Why: under a software OpenGL the render of each result competes
// with the next result's job for the same cores (docs/decisions.md, "The viewport as an image").
// handOnControl() says whether a button or a key is held now: a result that comes with the hand away
// (a click, a key pressed and let go) ends the edit, and work that waits for the end need not wait.
// Keys are followed by an application-wide event filter from construction; a key released in another
// application is forgotten when the application loses the focus.

#include <QObject>
#include <QSet>

namespace motionstyle {

class SkeletonViewport;

class LiveResolution : public QObject {
  Q_OBJECT

 public:
  explicit LiveResolution(SkeletonViewport* viewport, QObject* parent = nullptr);
  ~LiveResolution() override;

  void resultShown();
  bool handOnControl() const;

 signals:
  // The button or key held while results arrived was let go: the live edit is over.
  void handReleased();

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  void letGoIfAway();

  SkeletonViewport* viewport_;
  QSet<int> keys_held_;    // pressed, not auto-repeated, not yet released
  bool watching_ = false;  // results arrived with the hand on a control: its release is awaited
};

}  // namespace motionstyle
