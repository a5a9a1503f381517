#include "focused_keys.h"

#include <QAbstractItemView>
#include <QAbstractSlider>
#include <QApplication>
#include <QComboBox>
#include <QKeyEvent>
#include <QTabBar>

namespace motionstyle {
namespace {

// A letter or digit typed without Ctrl, Alt or Meta (Shift and the keypad's flag allowed).
bool isTypedCharacter(const QKeyEvent& event) {
  if (event.modifiers() & (Qt::ControlModifier | Qt::AltModifier | Qt::MetaModifier)) return false;
  return event.text().size() == 1 && event.text().front().isLetterOrNumber();
}

// The keys each kind of control moves with. Left and Right only for sliders and tab bars: a combo
// box or a flat list has no use for them, and there they go on stepping the timeline.
bool keepsKey(const QWidget& widget, const QKeyEvent& event) {
  const bool slides = qobject_cast<const QAbstractSlider*>(&widget) || qobject_cast<const QTabBar*>(&widget);
  const bool lists = qobject_cast<const QComboBox*>(&widget) || qobject_cast<const QAbstractItemView*>(&widget);
  if (lists && isTypedCharacter(event)) return true;  // it jumps to the entry that starts with it
  if ((event.modifiers() & ~(Qt::KeypadModifier | Qt::ShiftModifier)) != 0) return false;
  switch (event.key()) {
    case Qt::Key_Left:
    case Qt::Key_Right:
      return slides;
    case Qt::Key_Up:
    case Qt::Key_Down:
    case Qt::Key_Home:
    case Qt::Key_End:
    case Qt::Key_PageUp:
    case Qt::Key_PageDown:
      return slides || lists;
    default:
      return false;
  }
}

class FocusedKeys : public QObject {
 public:
  using QObject::QObject;

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override {
    if (event->type() != QEvent::ShortcutOverride) return false;
    const auto* widget = qobject_cast<const QWidget*>(watched);
    if (widget == nullptr || !widget->hasFocus() || !keepsKey(*widget, *static_cast<const QKeyEvent*>(event)))
      return false;
    event->accept();  // the key goes to the focused control, not to a shortcut
    return true;
  }
};

}  // namespace

void installFocusedKeys(QApplication& application) {
  static const char* const kInstalled = "motionstyle_focused_keys";
  if (application.property(kInstalled).toBool()) return;
  application.installEventFilter(new FocusedKeys(&application));
  application.setProperty(kInstalled, true);
}

}  // namespace motionstyle
