#include "live_resolution.h"

#include <QCoreApplication>
#include <QEvent>
#include <QGuiApplication>
#include <QKeyEvent>

#include "skeleton_viewport.h"

namespace motionstyle {

LiveResolution::LiveResolution(SkeletonViewport* viewport, QObject* parent) : QObject(parent), viewport_(viewport) {
  QCoreApplication::instance()->installEventFilter(this);
}

LiveResolution::~LiveResolution() {
  if (QCoreApplication* application = QCoreApplication::instance()) application->removeEventFilter(this);
}

bool LiveResolution::handOnControl() const {
  return QGuiApplication::mouseButtons() != Qt::NoButton || !keys_held_.isEmpty();
}

void LiveResolution::resultShown() {
  const bool hand_on_control = handOnControl();
  viewport_->setReducedResolution(hand_on_control);
  if (hand_on_control) watching_ = true;
}

void LiveResolution::letGoIfAway() {
  if (!watching_ || handOnControl()) return;
  watching_ = false;
  viewport_->setReducedResolution(false);  // the last result, sharp
  emit handReleased();
}

bool LiveResolution::eventFilter(QObject* watched, QEvent* event) {
  switch (event->type()) {
    case QEvent::KeyPress: {
      const auto* key = static_cast<const QKeyEvent*>(event);
      if (!key->isAutoRepeat()) keys_held_.insert(key->key());
      break;
    }
    case QEvent::KeyRelease: {
      const auto* key = static_cast<const QKeyEvent*>(event);
      // An event passed on to the parent widgets reaches the filter once per widget: the first counts.
      if (!key->isAutoRepeat() && keys_held_.remove(key->key())) letGoIfAway();
      break;
    }
    case QEvent::MouseButtonRelease:
      letGoIfAway();
      break;
    case QEvent::ApplicationDeactivate:
      keys_held_.clear();
      letGoIfAway();
      break;
    default:
      break;
  }
  return QObject::eventFilter(watched, event);
}

}  // namespace motionstyle
