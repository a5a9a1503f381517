#pragma once
// A busy bar (no fraction: the work reports none) that appears only when the work outlasts a delay.
// Why: a live edit answers in tens of milliseconds; a bar shown and hidden at every step of a drag
// re-laid out and repainted the panel while the job ran, taking the GUI thread and a core from it.
// Hidden, the bar keeps its space, so showing it moves nothing in the panel.

#include <QProgressBar>
#include <QTimer>

namespace motionstyle {

class BusyIndicator : public QProgressBar {
  Q_OBJECT

 public:
  static constexpr int kDefaultDelayMs = 400;  // shorter work never shows the bar

  explicit BusyIndicator(QWidget* parent = nullptr, int delay_ms = kDefaultDelayMs);

  // Busy: the bar appears once the delay has passed and the work still goes on; not busy: it hides.
  void setBusy(bool busy);

 private:
  QTimer delay_;
  bool busy_ = false;
};

}  // namespace motionstyle
