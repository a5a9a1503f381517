#include "live_resolution.h"

#include <QEvent>
#include <QGuiApplication>

#include "skeleton_viewport.h"

namespace motionstyle {

LiveResolution::LiveResolution(SkeletonViewport* viewport, QObject* parent) : QObject(parent), viewport_(viewport) {}

void LiveResolution::resultShown() {
  const bool hand_on_control = QGuiApplication::mouseButtons() != Qt::NoButton;
  viewport_->setReducedResolution(hand_on_control);
  if (hand_on_control && !watching_) {
    QCoreApplication::instance()->installEventFilter(this);
    watching_ = true;
  }
}

bool LiveResolution::eventFilter(QObject* watched, QEvent* event) {
  if (watching_ && event->type() == QEvent::MouseButtonRelease &&
      QGuiApplication::mouseButtons() == Qt::NoButton) {
    QCoreApplication::instance()->removeEventFilter(this);
    watching_ = false;
    viewport_->setReducedResolution(false);  // the last result, sharp
    emit handReleased();
  }
  return QObject::eventFilter(watched, event);
}

}  // namespace motionstyle
