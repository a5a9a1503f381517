#include "busy_indicator.h"

namespace motionstyle {

BusyIndicator::BusyIndicator(QWidget* parent, int delay_ms) : QProgressBar(parent) {
  setRange(0, 0);
  QSizePolicy policy = sizePolicy();
  policy.setRetainSizeWhenHidden(true);
  setSizePolicy(policy);
  setVisible(false);
  delay_.setSingleShot(true);
  delay_.setInterval(delay_ms);
  connect(&delay_, &QTimer::timeout, this, [this] { setVisible(busy_); });
}

void BusyIndicator::setBusy(bool busy) {
  if (busy == busy_) return;
  busy_ = busy;
  if (busy) {
    delay_.start();
  } else {
    delay_.stop();
    setVisible(false);
  }
}

}  // namespace motionstyle
