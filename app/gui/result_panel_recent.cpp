// The Result panel's remembered results (recent_results.h): a style shown before with the same inputs
// is shown again without a job.
#include "app_log.h"
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
  app_log::write(QStringLiteral("live: %1 -> cleaned result on screen %2 ms after the change (job 0 ms, figures %3 ms, "
                                "strength %4, %5 frames, clean-up solved 0 of %6 chunks, remembered: made earlier for "
                                "these inputs)")
                     .arg(last_change_)
                     .arg(on_screen - last_change_ms_)
                     .arg(on_screen - figures_start)
                     .arg(strength(), 0, 'f', 2)
                     .arg(result_->report.frames)
                     .arg(result_->report.chunks));
  last_change_ms_ = -1;
  scheduleLookAhead();
  return true;
}

}  // namespace motionstyle
