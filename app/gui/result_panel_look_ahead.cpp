// The Result panel's look-ahead: while the user looks at a result, the styles near it in the chooser
// (+1, -1, +2, -2, ...: the nearest first) are computed for the same inputs on a second worker and
// remembered (recent_results.h), so that a switch to any of them is shown at once. Before the first
// result too (a clip just opened, a style just chosen), the chosen style first: Stylize then shows it
// at once. After a result that came with the hand away from the controls (a click, a key pressed and
// let go) it starts at once; while a drag or a key held down brings results, only once the inputs
// have rested for a moment or the hand lets go (a drag's steps never start it). One style at a time;
// any change drops it, and so does a job of the Style networks panel
// (holdLookAhead) until it ends. How many: lookAheadStyles(), every shipped style for a clip up to
// 2,000 frames, two for a very long one (each costs a job on both cores and keeps its result and
// prepared network). Before any clip is open it reads and prepares the shipped networks instead.
#include <QComboBox>
#include <QFileInfo>
#include <QScopedValueRollback>
#include <QTimer>

#include <algorithm>
#include <utility>

#include "app_log.h"
#include "result_panel.h"

namespace motionstyle {

static_assert(StylizerCache::kCapacity >= RecentResults::kCapacity &&
                  RecentResults::kCapacity >= 2 + ResultPanel::kLookAheadMaxStyles,
              "a style computed ahead must stay remembered and prepared until it is chosen");

void ResultPanel::setLookAheadDelay(int milliseconds) {
  look_ahead_delay_ms_ = milliseconds;
  if (milliseconds < 0) stopLookAhead();
}

void ResultPanel::holdLookAhead(bool held) {
  look_ahead_held_ = held;
  if (held) stopLookAhead();
  else scheduleLookAhead();
}

void ResultPanel::setHandOnControl(std::function<bool()> hand_on_control) {
  hand_on_control_ = std::move(hand_on_control);
}

void ResultPanel::handReleased() {
  // The last result is in: at once. Else its result, with the hand away, starts it.
  if (look_ahead_timer_->isActive()) scheduleLookAhead(true);
}

void ResultPanel::scheduleLookAhead(bool at_once) {
  const int delay = at_once ? 0 : look_ahead_delay_ms_;
  if (look_ahead_delay_ms_ >= 0 && !look_ahead_held_) look_ahead_timer_->start(delay);
}

void ResultPanel::stopLookAhead() {
  look_ahead_timer_->stop();
  // A read is kept (it depends on no input, and a new job would wait for it on the thread anyway), and
  // so is a job the panel waits for (dropAdoptedLookAhead and cancel drop it).
  if (look_ahead_->isBusy() && !look_ahead_reads_ && !look_ahead_adopted_) {
    look_ahead_->abandon();
    look_ahead_inputs_ = {};  // (its network and contacts are not kept alive by it)
  }
}

int ResultPanel::lookAheadStyles() const {
  const int frames = content_ ? std::max(1, content_->motion.frameCount()) : 1;
  return std::clamp(kLookAheadFrames / frames, kLookAheadMinStyles, kLookAheadMaxStyles);
}

void ResultPanel::lookAhead() {
  if (look_ahead_->isBusy()) return;  // its completion looks for the next
  if (!content_ || !content_->mapping) {
    readAhead();
    return;
  }
  if (busy_ || resultIsStale() || given_stylized_ || !reading_file_.isEmpty()) return;
  const int current = network_choice_->currentIndex(), count = network_choice_->count();
  const int styles = 1 + lookAheadStyles();  // the chosen one (shown, or not yet: it comes first) and its neighbours
  int candidates = 0;
  for (int step = 0; step < 2 * count + 1 && candidates < styles; ++step) {
    const int index = current + (step % 2 == 1 ? (step + 1) / 2 : -(step / 2));  // 0, +1, -1, +2, -2, ...
    if (index < 0 || index >= count) continue;
    const QString file = network_choice_->itemData(index).toString();
    const bool chosen = index == current && hasNetwork();
    if (file.isEmpty() && !chosen) continue;  // a network without a file: nothing to read ahead
    ResultInputs inputs = currentInputs();
    if (!chosen) inputs.stylizer = stylizers_.find(file);  // prepared already, or read on the worker
    if (!inputs.stylizer && unreadable_files_.contains(file)) continue;  // the user hears of it on picking it
    ++candidates;
    if (inputs.stylizer && recent_.contains(inputs)) continue;  // already there
    startLookAhead(std::move(inputs), file, network_choice_->itemText(index));
    return;  // one at a time: its completion looks for the next
  }
}

void ResultPanel::readAhead() {
  for (int index = 0; index < network_choice_->count(); ++index) {
    const QString file = network_choice_->itemData(index).toString();
    if (file.isEmpty() || file == reading_file_ || unreadable_files_.contains(file) || stylizers_.find(file)) continue;
    look_ahead_reads_ = true;
    const qint64 started = clock_.elapsed();
    look_ahead_->restart(QString(), [this, file, started](const JobRunner::Context&) -> JobRunner::Completion {
      std::shared_ptr<const style::Stylizer> stylizer;
      try {
        stylizer = readNetworkFile(file);
      } catch (...) {  // reported if the user picks it (chooseNetwork reads it again)
      }
      return [this, stylizer, file, started] { onReadAhead(stylizer, file, clock_.elapsed() - started); };
    });
    return;
  }
}

void ResultPanel::onReadAhead(std::shared_ptr<const style::Stylizer> stylizer, const QString& file,
                              qint64 milliseconds) {
  look_ahead_reads_ = false;
  app_log::write(QStringLiteral("look-ahead: %1 %2 in %3 ms")
                     .arg(QFileInfo(file).fileName(), stylizer ? QStringLiteral("read and prepared") : QStringLiteral("not readable"))
                     .arg(milliseconds));
  if (!stylizer) unreadable_files_ << file;
  else if (!stylizers_.find(file)) stylizers_.store(file, std::move(stylizer));
  scheduleLookAhead(true);  // the next, or the clip's styles
}

void ResultPanel::startLookAhead(ResultInputs inputs, const QString& file, const QString& name) {
  style::StylizeCleanupJob job;
  job.world_positions = true;  // the figure of its result is drawn from them (result_figures.h)
  job.content = content_->motion;
  job.mapping = *content_->mapping;
  job.strength = inputs.strength;
  job.path = inputs.path;
  job.kind = inputs.kind;
  job.contact_overrides = inputs.contact_overrides;
  job.memory = std::make_shared<style::StylizeCleanupMemory>();  // the shown style's is in use: its own
  // This style's network output on the clip, when a result of it is remembered (the strength or
  // contacts changed since; for another path or aim the job runs the network again): copied here, on the GUI
  // thread, while no job writes it (lookAhead runs only while the panel is idle), so that only the
  // clean-up runs (20-30 ms for 500 frames, not 80).
  if (inputs.stylizer)
    if (auto kept = recent_.memoryFor(content_->id, inputs.stylizer)) job.memory->copyFrom(*kept);
  const qint64 started = clock_.elapsed();
  look_ahead_reads_ = false;
  look_ahead_inputs_ = inputs;
  const bool chosen = inputs.stylizer && inputs.stylizer == stylizer_;  // its next job reuses the scratch
  look_ahead_->restart(tr("Could not compute a neighbouring style"),
                       [this, job = std::move(job), inputs = std::move(inputs), file, name, started,
                        chosen](const JobRunner::Context& context) mutable -> JobRunner::Completion {
                         if (!inputs.stylizer) {
                           try {
                             inputs.stylizer = readNetworkFile(file);
                           } catch (...) {  // skipped from now on, and the next style computed
                             return [this, file] { onReadAhead(nullptr, file, 0); };
                           }
                         }
                         job.stylizer = inputs.stylizer;
                         auto result = std::make_shared<const style::StylizeCleanupResult>(job.run(context.cancelFlag()));
                         if (!chosen) inputs.stylizer->releaseIdleNetworks();  // its scratch: it may never be chosen
                         return [this, result, inputs, memory = job.memory, file, name, started] {
                           onLookedAhead({inputs, result, name, memory}, file, clock_.elapsed() - started);
                         };
                       });
}

void ResultPanel::onLookedAhead(RecentResults::Entry entry, const QString& file, qint64 milliseconds) {
  look_ahead_inputs_ = {};
  ResultInputs now = currentInputs();
  const bool adopted = std::exchange(look_ahead_adopted_, false);
  if (adopted && !(now == entry.inputs)) {  // not what the panel waited for (never expected): a job of its own
    setBusy(false, status_label_->text());
    runStylize();
    return;
  }
  now.stylizer = entry.inputs.stylizer;
  if (!(now == entry.inputs)) return;  // the inputs moved on while it ran
  if (!file.isEmpty() && !stylizers_.find(file)) stylizers_.store(file, entry.inputs.stylizer);
  app_log::write(QStringLiteral("look-ahead: %1 computed for the current inputs in %2 ms").arg(entry.network_name).arg(milliseconds));
  entry.computed_ahead = true;
  recent_.remember(std::move(entry));
  if (adopted) {  // shown as one computed ahead, the panel's job done
    setBusy(false, status_label_->text());
    showRememberedResult(std::exchange(adopted_for_stylize_, false), clock_.elapsed() - job_start_ms_);
    emit jobEnded(true);
    return;
  }
  // The inputs still rest: the next nearest at once. A change drops it within a few ms (a job checks
  // its cancel flag before every refinement step and clean-up frame), so it never holds an edit back.
  scheduleLookAhead(true);
}

bool ResultPanel::lookAheadComputes(const ResultInputs& inputs) const {
  return look_ahead_->isBusy() && !look_ahead_reads_ && look_ahead_inputs_.stylizer && look_ahead_inputs_ == inputs;
}

bool ResultPanel::adoptLookAhead() {
  if (given_stylized_ || !lookAheadComputes(currentInputs())) return false;
  look_ahead_timer_->stop();
  if (busy_) {  // a job for older inputs: dropped, as startJob drops it
    const QScopedValueRollback dropping(abandoning_, true);
    runner_->abandon();
  }
  pending_ = false;
  look_ahead_adopted_ = true;
  adopted_for_stylize_ = !result_;
  job_network_name_ = network_name_;
  job_start_ms_ = clock_.elapsed();
  const QString step = tr("Stylizing and cleaning up...");
  setBusy(true, resultIsStale() ? tr("Out of date: %1. Updating: %2").arg(stale_reason_, step) : step);
  return true;  // last_change_ms_ stays: showRememberedResult logs the latency from it
}

void ResultPanel::dropAdoptedLookAhead() {
  if (!std::exchange(look_ahead_adopted_, false)) return;
  stopLookAhead();
  setBusy(false, status_label_->text());
}

}  // namespace motionstyle
