// The Result panel's remembered results (recent_results.h): a style shown before, or computed ahead,
// for the same inputs is shown without a job, and the status says which.
#include "result_panel.h"

#include <algorithm>
#include <utility>

namespace motionstyle {

ResultInputs ResultPanel::currentInputs() const {
  return {content_ ? content_->id : 0, stylizer_, strength(), pathMode(), aimKind(), overrides_};
}

bool ResultPanel::showRememberedResult(bool stylize_pressed, qint64 waited_ms) {
  if (given_stylized_ || !canStylize()) return false;
  RecentResults::Entry* remembered = recent_.find(currentInputs());
  if (remembered == nullptr) return false;
  const bool computed_ahead = std::exchange(remembered->computed_ahead, false);  // shown from now on
  if (busy_) cancel();  // the running job answers other inputs
  result_ = remembered->result;
  memory_ = remembered->memory;  // the next edit of this style starts from its solution
  result_network_name_ = remembered->network_name;
  stale_reason_.clear();
  const qint64 figures_start = clock_.elapsed();
  QString status = tr("Shown again: made earlier for the same clip, style, strength, path, aim and contacts.");
  if (computed_ahead)
    status = stylize_pressed ? tr("Stylized and cleaned up %1 frames (computed ahead while the clip was open).")
                                   .arg(result_->cleaned.frameCount())
                             : tr("Computed ahead while you looked, for the same clip, strength, path, aim and contacts.");
  const qint64 on_screen = showResult(status);
  const QString how = !computed_ahead ? QStringLiteral("remembered: made earlier for these inputs")
                      : waited_ms < 0 ? QStringLiteral("remembered: computed ahead for these inputs")
                                      : QStringLiteral("remembered: computed ahead for these inputs, its job waited for");
  logResultOnScreen(last_change_, on_screen - last_change_ms_, std::max<qint64>(waited_ms, 0), on_screen - figures_start,
                    strength(), 0, how);
  last_change_ms_ = -1;
  scheduleLookAhead(!hand_on_control_());
  return true;
}

}  // namespace motionstyle
