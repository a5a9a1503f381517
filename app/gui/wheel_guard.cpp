#include "wheel_guard.h"

#include <QAbstractSlider>
#include <QAbstractSpinBox>
#include <QApplication>
#include <QComboBox>
#include <QEvent>
#include <QScrollBar>
#include <QWidget>

namespace motionstyle {
namespace {

// Scroll bars are sliders too, and always scroll: only widgets that hold a value are held back.
bool takesWheelForValue(const QObject* object) {
  if (qobject_cast<const QScrollBar*>(object)) return false;
  return qobject_cast<const QAbstractSpinBox*>(object) || qobject_cast<const QComboBox*>(object) ||
         qobject_cast<const QAbstractSlider*>(object);
}

class WheelGuard : public QObject {
 public:
  using QObject::QObject;

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override {
    if (event->type() == QEvent::Polish && takesWheelForValue(watched)) {
      auto* widget = static_cast<QWidget*>(watched);
      if (widget->focusPolicy() == Qt::WheelFocus) widget->setFocusPolicy(Qt::StrongFocus);
    } else if (event->type() == QEvent::Wheel && takesWheelForValue(watched) &&
               !static_cast<QWidget*>(watched)->hasFocus()) {
      event->ignore();  // Qt then offers the wheel to the parent (the scroll area)
      return true;
    }
    return false;
  }
};

}  // namespace

void installWheelGuard(QApplication& application) {
  static const char* const kInstalled = "motionstyle_wheel_guard";
  if (application.property(kInstalled).toBool()) return;
  application.installEventFilter(new WheelGuard(&application));
  application.setProperty(kInstalled, true);
}

}  // namespace motionstyle
