// The Result panel's remembered results (recent_results.h): a style shown before with the same inputs
// is shown again without a job.
#include "result_panel.h"

namespace motionstyle {

ResultInputs ResultPanel::currentInputs() const {
  return {content_ ? content_->id : 0, stylizer_, strength(), pathMode(), overrides_};
}

bool ResultPanel::showRememberedResult() {
  if (given_stylized_ || !canStylize()) return false;
  const RecentResults::Entry* remembered = recent_.find(currentInputs());
  if (remembered == nullptr) return false;
  if (busy_) cancel();  // the running job answers other inputs
  result_ = remembered->result;
  memory_ = remembered->memory;  // the next edit of this style starts from its solution
  result_network_name_ = remembered->network_name;
  stale_reason_.clear();
  const qint64 figures_start = clock_.elapsed();
  const qint64 on_screen =
      showResult(tr("Shown again: made earlier for the same clip, style, strength, path and contacts."));
  logResultOnScreen(last_change_, on_screen - last_change_ms_, 0, on_screen - figures_start, strength(), 0,
                    QStringLiteral("remembered: made earlier for these inputs"));
  last_change_ms_ = -1;
  scheduleLookAhead();
  return true;
}

}  // namespace motionstyle
