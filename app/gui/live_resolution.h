#pragma once
// LiveResolution: the viewport renders at reduced resolution while the user's hand is on a control.
//
// Contract: call resultShown() just before a new result is painted. If a mouse button is held then (a
// strength drag, a contact stroke: every step brings a new result), the viewport renders at half the
// pixels across and down (SkeletonViewport::setReducedResolution) until the button is released, when
// it renders the result at full resolution and emits handReleased(). Why: under a software OpenGL the
// render of each result competes with the next result's job for the same cores (docs/decisions.md,
// "The viewport as an image").

#include <QObject>

namespace motionstyle {

class SkeletonViewport;

class LiveResolution : public QObject {
  Q_OBJECT

 public:
  explicit LiveResolution(SkeletonViewport* viewport, QObject* parent = nullptr);

  void resultShown();

 signals:
  // The button held while results arrived was let go: the live drag is over.
  void handReleased();

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  SkeletonViewport* viewport_;
  bool watching_ = false;  // an application-wide filter waits for the button's release
};

}  // namespace motionstyle
