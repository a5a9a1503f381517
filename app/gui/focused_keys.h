#pragma once
// A focused control keeps the keys it works with. The window's single-key shortcuts (the timeline's
// Left/Right/Home/End, the View menu's letters and digits) are tried by Qt before the focused widget
// sees the key, so without this the strength slider's Left stepped the timeline and typing "f" in the
// style chooser reset the camera instead of picking Feminine. A focused slider or tab bar now takes
// its arrows, Home, End and Page Up/Down; a combo box or list the same but Left and Right (it has no
// use for them: they still step the timeline), and plain letters and digits (it jumps to the entry
// that starts with them). Text fields and spin boxes claim their keys themselves. Space stays the
// window's: play and pause from anywhere.
// Installed once on the application, like the wheel guard (wheel_guard.h).

class QApplication;

namespace motionstyle {

// Idempotent.
void installFocusedKeys(QApplication& application);

}  // namespace motionstyle
