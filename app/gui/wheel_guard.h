#pragma once
// Spin boxes, combo boxes and sliders take the mouse wheel only when they have keyboard focus (a click
// or Tab gives it). Without focus the wheel goes on to the scroll area around them, so scrolling a
// long form never silently changes a value under the pointer (a style weight of 100 became 99).
// Installed once on the application: every such widget, now and later, follows the rule.

class QApplication;

namespace motionstyle {

// Idempotent. Sets those widgets' focus policy to Qt::StrongFocus as they are polished (so the wheel
// does not give them focus either) and passes their unfocused wheel events to their parents.
void installWheelGuard(QApplication& application);

}  // namespace motionstyle
