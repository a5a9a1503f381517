#include "result_panel.h"

#include <QCheckBox>
#include <QComboBox>
#include <QGuiApplication>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QScopedValueRollback>
#include <QTimer>
#include <QPushButton>
#include <QSlider>
#include <QVBoxLayout>

#include <cmath>
#include <exception>
#include <utility>

#include "common/errors.h"
#include "common/resource_paths.h"
#include "aim_choice.h"
#include "app_log.h"
#include "busy_indicator.h"
#include "display_space.h"
#include "familiarity_label.h"
#include "result_figures.h"
#include "result_metrics_view.h"
#include "shipped_networks.h"
#include "style/locomotion_kind.h"
#include "style/training.h"

namespace motionstyle {

constexpr int kStrengthSteps = 100;  // slider steps over strength 0..1

ResultPanel::ResultPanel(QWidget* parent) : QWidget(parent), memory_(std::make_shared<style::StylizeCleanupMemory>()) {
  clock_.start();
  setObjectName(QStringLiteral("ResultPanel"));

  network_choice_ = new QComboBox(this);
  network_choice_->setObjectName(QStringLiteral("NetworkChoice"));
  network_choice_->setPlaceholderText(tr("Choose a style..."));
  network_choice_->setToolTip(tr("The style to apply: the styles shipped with MotionStyle, and networks you opened"));
  network_choice_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  listShippedNetworks();
  connect(network_choice_, &QComboBox::activated, this, &ResultPanel::chooseNetwork);
  auto* open_network = new QPushButton(tr("Open..."), this);
  open_network->setToolTip(tr("Load a style network file (.net)"));
  connect(open_network, &QPushButton::clicked, this, &ResultPanel::browseNetwork);
  auto* network_row = new QHBoxLayout;
  network_row->addWidget(network_choice_, 1);
  network_row->addWidget(open_network);
  content_label_ = new QLabel(this);
  content_label_->setWordWrap(true);
  content_label_->setTextFormat(Qt::RichText);  // the name is escaped; the mapping hint is coloured

  strength_slider_ = new QSlider(Qt::Horizontal, this);
  strength_slider_->setObjectName(QStringLiteral("StrengthSlider"));
  strength_slider_->setRange(0, kStrengthSteps);
  strength_slider_->setValue(kStrengthSteps);
  strength_slider_->setToolTip(tr("0 = the content as it is, 1 = fully in the style"));
  strength_label_ = new QLabel(this);
  strength_label_->setMinimumWidth(36);
  connect(strength_slider_, &QSlider::valueChanged, this,
          [this](int value) { strength_label_->setText(QString::number(value / double(kStrengthSteps), 'f', 2)); });
  // The result follows the slider while it moves (inputsChanged drops the steps a job cannot keep up with).
  connect(strength_slider_, &QSlider::valueChanged, this, [this] { inputsChanged(tr("the strength changed")); });
  keep_path_ = new QCheckBox(tr("Keep the content's path"), this);
  keep_path_->setObjectName(QStringLiteral("KeepPathCheck"));
  keep_path_->setChecked(true);
  keep_path_->setToolTip(tr("On: the output covers the same ground and turns the same way as the content, in the "
                            "same time.\nOff: the style may change the pace (an elderly walk covers less ground)."));
  connect(keep_path_, &QCheckBox::toggled, this, [this] { inputsChanged(tr("the path choice changed")); });
  aim_choice_ = new AimChoice(this);
  connect(aim_choice_, &AimChoice::kindChanged, this, [this] { inputsChanged(tr("the style clip aimed at changed")); });
  familiarity_label_ = new FamiliarityLabel(this);
  connect(familiarity_label_, &FamiliarityLabel::adaptRequested, this, &ResultPanel::adaptRequested);
  strength_label_->setText(QStringLiteral("1.00"));
  auto* strength_row = new QHBoxLayout;
  strength_row->addWidget(strength_slider_, 1);
  strength_row->addWidget(strength_label_);

  stylize_button_ = new QPushButton(tr("Stylize && Clean Up"), this);
  stylize_button_->setObjectName(QStringLiteral("StylizeButton"));
  stylize_button_->setDefault(true);
  cancel_button_ = new QPushButton(tr("Cancel"), this);
  connect(stylize_button_, &QPushButton::clicked, this, &ResultPanel::stylize);
  connect(cancel_button_, &QPushButton::clicked, this, &ResultPanel::cancel);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(stylize_button_, 1);
  buttons->addWidget(cancel_button_);
  progress_ = new BusyIndicator(this);
  status_label_ = new QLabel(this);
  status_label_->setWordWrap(true);

  metrics_ = new ResultMetricsView(this);
  connect(metrics_, &ResultMetricsView::frameRequested, this, &ResultPanel::frameRequested);
  connect(metrics_, &ResultMetricsView::contactEndRequested, this, &ResultPanel::contactEndRequested);

  export_button_ = new QPushButton(tr("Export BVH..."), this);
  export_button_->setObjectName(QStringLiteral("ExportButton"));
  export_button_->setToolTip(tr("Save the cleaned clip on the content's own skeleton"));
  connect(export_button_, &QPushButton::clicked, this, &ResultPanel::browseExport);

  auto* form = new QFormLayout;
  form->addRow(tr("Style:"), network_row);
  form->addRow(tr("Content:"), content_label_);
  form->addRow(tr("Familiarity:"), familiarity_label_);
  form->addRow(tr("Strength:"), strength_row);
  auto* path_row = new QHBoxLayout;  // one row for both: the panel fits a 700-pixel-high screen
  path_row->addWidget(keep_path_);
  path_row->addStretch(1);
  path_row->addWidget(new QLabel(tr("Aim at:"), this));
  path_row->addWidget(aim_choice_);
  form->addRow(QString(), path_row);
  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form);
  layout->addLayout(buttons);
  layout->addWidget(progress_);
  layout->addWidget(status_label_);
  layout->addWidget(metrics_);
  layout->addWidget(export_button_);
  layout->addStretch(1);

  runner_ = new JobRunner(this);
  look_ahead_ = new JobRunner(this);  // its failures are not the user's: not reported
  reader_ = new JobRunner(this);
  connect(reader_, &JobRunner::failed, this, &ResultPanel::onNetworkReadFailed);
  look_ahead_timer_ = new QTimer(this);
  look_ahead_timer_->setSingleShot(true);
  hand_on_control_ = [] { return QGuiApplication::mouseButtons() != Qt::NoButton; };
  connect(look_ahead_timer_, &QTimer::timeout, this, &ResultPanel::lookAhead);
  // A look-ahead job the panel waited for failed: a job of its own, which reports what went wrong.
  connect(look_ahead_, &JobRunner::failed, this, [this] {
    if (!std::exchange(look_ahead_adopted_, false)) return;
    setBusy(false, status_label_->text());
    runStylize();
  });
  connect(runner_, &JobRunner::failed, this, [this](const QString& title, const QString& message) {
    setBusy(false, tr("Failed."));
    report(title, message);
    emit jobEnded(false);
  });
  connect(runner_, &JobRunner::finished, this, [this](bool completed) {
    if (!completed && busy_ && !abandoning_) {  // a job that ended without a result (not one we dropped)
      setBusy(false, tr("Cancelled."));
      emit jobEnded(false);
    }
  });

  refreshMetrics();
  refreshControls();
  scheduleLookAhead();  // no clip yet: the shipped networks are read ahead
}

ResultPanel::~ResultPanel() = default;

void ResultPanel::report(const QString& title, const QString& message) {
  if (reporter_) reporter_(title, message);
}

void ResultPanel::setContentClip(const LoadedClip* clip) {
  if ((clip == nullptr && !content_) || (clip != nullptr && content_ && content_->id == clip->id)) return;
  // A result (or one on its way) of the clip that goes: the window's status line spoke of it.
  const QString dropped = content_ && (result_ || busy_) ? content_->name : QString();
  cancel();
  content_ = clip != nullptr ? std::make_shared<const LoadedClip>(*clip) : nullptr;
  memory_ = std::make_shared<style::StylizeCleanupMemory>();  // the last clip's solutions help no other
  stopLookAhead();
  recent_.clear();
  overrides_ = content_ ? content_->contact_overrides : Eigen::MatrixXi();
  content_features_ = content_ ? clipFeatures(*content_) : nullptr;
  aim_choice_->showChoiceFor(content_ ? content_->path : QString(),
                             content_features_ ? style::locomotionKind(content_features_->values, content_features_->contacts)
                                               : std::string());
  given_stylized_.reset();
  clearResult();
  refreshControls();
  refreshFamiliarity();
  if (!dropped.isEmpty())
    emit statusMessage(!content_                  ? tr("No content clip: the result of %1 was cleared.").arg(dropped)
                       : content_->name == dropped ? tr("%1 changed (mapped again): its result was cleared.").arg(dropped)
                                                   : tr("The content is %1 now: the result of %2 was cleared.")
                                                         .arg(content_->name, dropped));
  // The chosen style (if any) and its neighbours, before Stylize is pressed: at once, as nothing is
  // being dragged (the rest is for drags).
  scheduleLookAhead(true);
}

void ResultPanel::setContactOverrides(const Eigen::MatrixXi& overrides) {
  // Overrides as they were are no edit: a stroke's release repeats its last step, and each such
  // repeat once showed the last result again ("Shown again: made earlier ...").
  if (overrides.rows() == overrides_.rows() && overrides.cols() == overrides_.cols() && overrides == overrides_) return;
  overrides_ = overrides;
  inputsChanged(tr("the contacts were edited"));
}

void ResultPanel::setStylizedClip(style::StylizedClip clip, const QString& label) {
  if (!content_) {
    report(tr("Nothing to clean up"), tr("Choose a content clip first."));
    return;
  }
  given_stylized_ = std::move(clip);
  network_name_ = label;
  emit sourceChanged();
  stylize();
}

double ResultPanel::strength() const { return strength_slider_->value() / double(kStrengthSteps); }

style::PathMode ResultPanel::pathMode() const {
  return keep_path_->isChecked() ? style::PathMode::Content : style::PathMode::Style;
}

void ResultPanel::setPathMode(style::PathMode mode) { keep_path_->setChecked(mode == style::PathMode::Content); }

std::string ResultPanel::aimKind() const { return aim_choice_->kind(); }

const std::optional<style::Familiarity>& ResultPanel::familiarity() const { return familiarity_label_->familiarity(); }

bool ResultPanel::canStylize() const { return content_ && content_->mapping && (hasNetwork() || given_stylized_); }

void ResultPanel::inputsChanged(const QString& what, qint64 changed_ms) {
  const bool was_waiting = look_ahead_adopted_;
  dropAdoptedLookAhead();  // it computes the inputs before this change
  look_ahead_timer_->stop();
  if (!lookAheadComputes(currentInputs())) stopLookAhead();  // else runStylize waits for it
  if (!result_ && !busy_ && !was_waiting) {  // nothing shown or on its way: the next Stylize uses the new inputs
    scheduleLookAhead();      // ... computed ahead once they rest
    return;
  }
  const bool was_stale = resultIsStale();
  last_change_ms_ = changed_ms >= 0 ? changed_ms : clock_.elapsed();
  last_change_ = what;
  if (result_) stale_reason_ = what;
  if (!reading_file_.isEmpty()) {  // the chooser shows a style whose file is being read: its job follows the read
    if (busy_) cancel();
    if (result_) status_label_->setText(tr("Out of date: %1. Reading the chosen style...").arg(what));
    refreshControls();
    if (result_ && !was_stale) emit resultRenamed();
    return;
  }
  if (showRememberedResult()) return;
  const bool rerun = canStylize();
  if (busy_ && rerun) {
    if (!dropped_previous_ && clock_.elapsed() - job_start_ms_ < last_job_ms_ / 2) {
      dropped_previous_ = true;  // the running job has only just started: replaced (see the header)
      runStylize();
    } else {
      stopLookAhead();  // (computing the new inputs or not: the job after the running one does)
      pending_ = true;  // after the running job: one job for the latest inputs
    }
  } else {
    if (busy_) cancel();
    if (rerun) runStylize();
  }
  if (resultIsStale()) {
    status_label_->setText(tr("Out of date: %1. %2").arg(what, rerun ? tr("Updating...") : tr("Stylize again to update it.")));
    refreshControls();
    if (!was_stale) emit resultRenamed();  // once, not at every step of a drag
  }
}

void ResultPanel::refreshFamiliarity() {
  familiarity_label_->measure(content_ ? content_->id : 0, content_features_.get(), stylizer_);
  emit familiarityChanged();
}

void ResultPanel::setStrength(double strength) {
  strength_slider_->setValue(static_cast<int>(std::lround(std::clamp(strength, 0.0, 1.0) * kStrengthSteps)));
}

void ResultPanel::stylize() {
  if (busy_) return;
  if (!reading_file_.isEmpty()) {  // the chosen style's file is being read: Stylize follows the read
    stylize_when_read_ = true;
    status_label_->setText(tr("Reading the chosen style..."));
    return;
  }
  last_change_ms_ = clock_.elapsed();
  last_change_ = tr("Stylize");
  if (!result_ && showRememberedResult(true)) return;  // computed ahead since the clip opened
  runStylize();
}

void ResultPanel::runStylize() {
  if (!content_) {
    report(tr("Nothing to stylize"), tr("Open a BVH clip and use it as the content."));
    return;
  }
  if (!content_->mapping) {
    report(tr("The content clip is not mapped"),
           tr("%1 cannot be stylized: %2.\nLoad a mapping file from the clip's context menu.")
               .arg(content_->name, content_->mapping_problem));
    return;
  }
  if (!given_stylized_ && !stylizer_) {
    report(tr("No style network"), tr("Open a style network file (.net) first, or train one."));
    return;
  }
  if (adoptLookAhead()) return;
  std::shared_ptr<const style::StylizeCleanupMemory> seed;
  if (stylizer_ && !given_stylized_) {
    // This style's own job memory when a result of it on this clip is remembered (its network output
    // serves any strength and contacts: a switch back after such an edit runs only the clean-up; the
    // job runs the network again for another path, whose root the contacts are planted under);
    // else, rather than another style's remembered one (which keeps its network output), a new one
    // seeded from it on the worker (its features and clean-up solutions).
    if (auto kept = recent_.memoryFor(content_->id, stylizer_)) {
      memory_ = std::move(kept);
    } else if (recent_.holds(memory_)) {
      seed = memory_;
      memory_ = std::make_shared<style::StylizeCleanupMemory>();
    }
  }
  style::StylizeCleanupJob job;
  job.world_positions = true;  // the figure of its result is drawn from them (result_figures.h)
  job_network_name_ = network_name_;
  job.content = content_->motion;
  job.mapping = *content_->mapping;
  job.stylizer = stylizer_;
  job.strength = strength();
  job.path = pathMode();
  job.kind = aimKind();
  job.stylized = given_stylized_;
  job.contact_overrides = overrides_;
  job.memory = memory_;
  job.seed = std::move(seed);
  job_change_ms_ = last_change_ms_ >= 0 ? last_change_ms_ : clock_.elapsed();
  job_change_ = last_change_ms_ >= 0 ? last_change_ : tr("Stylize");
  job_strength_ = job.strength;
  last_change_ms_ = -1;
  startJob(std::move(job));
}

void ResultPanel::startJob(style::StylizeCleanupJob job) {
  stopLookAhead();  // the cores are the edit's
  const QString step = job.stylized ? tr("Cleaning up...") : tr("Stylizing and cleaning up...");
  job_start_ms_ = clock_.elapsed();
  // A job for older inputs may still be running: it is dropped (its answer never arrives) and this one
  // runs as soon as the worker is free.
  {
    const QScopedValueRollback dropping(abandoning_, true);
    runner_->restart(tr("Could not stylize the clip"), [this, job = std::move(job)](const JobRunner::Context& context) {
      auto result = std::make_shared<const style::StylizeCleanupResult>(job.run(context.cancelFlag()));
      return [this, result] { onFinished(result); };
    });
  }
  setBusy(true, resultIsStale() ? tr("Out of date: %1. Updating: %2").arg(stale_reason_, step) : step);
}

void ResultPanel::cancel() {
  pending_ = false;
  stylize_when_read_ = false;
  if (!busy_) return;
  if (look_ahead_adopted_) {
    look_ahead_adopted_ = false;
    stopLookAhead();
  } else {  // the job stops at its next check; anything it still sends is dropped
    const QScopedValueRollback dropping(abandoning_, true);
    runner_->abandon();
  }
  setBusy(false, tr("Cancelled."));
  emit jobEnded(false);
}

void ResultPanel::onFinished(std::shared_ptr<const style::StylizeCleanupResult> result) {
  result_ = std::move(result);
  last_job_ms_ = std::lround(result_->seconds * 1000.0);
  dropped_previous_ = false;
  result_network_name_ = job_network_name_;
  // What the finished job was for, for its log line: the next job's start takes these fields.
  const QString change = job_change_;
  const qint64 change_ms = job_change_ms_;
  const double job_strength = job_strength_;
  const bool inputs_moved_on = pending_;
  if (inputs_moved_on) {
    // The job for the latest inputs starts first: the worker solves it while this result, out of
    // date, is painted (the paint no longer delays the next result).
    pending_ = false;
    runStylize();
  } else {
    stale_reason_.clear();
    if (!given_stylized_) recent_.remember({currentInputs(), result_, result_network_name_, memory_});
  }
  const qint64 figures_start = clock_.elapsed();
  const qint64 on_screen = showResult(tr("Stylized and cleaned up %1 frames in %2 s.")
                                          .arg(result_->cleaned.frameCount())
                                          .arg(result_->seconds, 0, 'f', 2),
                                      inputs_moved_on);
  const CleanupReport& report = result_->report;
  logResultOnScreen(change, on_screen - change_ms, std::lround(result_->seconds * 1000.0), on_screen - figures_start,
                    job_strength, report.chunks - report.chunks_reused,
                    QStringLiteral("%1 from the last solution, %2")
                        .arg(report.chunks_warm)
                        .arg(result_->network_output_kept ? QStringLiteral("network output kept")
                                                          : QStringLiteral("network run")));
  emit jobEnded(true);
  if (!inputs_moved_on) scheduleLookAhead(!hand_on_control_());
}

qint64 ResultPanel::showResult(const QString& status, bool next_job_running) {
  // The figures first, painted at once and alone (MainWindow::rebuildFigures); the rows, status and
  // buttons set below follow at the event loop's next pass (painted with the figures: 3-5 ms more).
  emit resultChanged();
  const qint64 on_screen = clock_.elapsed();
  if (!next_job_running) {  // else that job's "Updating" stays up
    const QString shown = status + aim_choice_->statusSentence(result_->stylized.kind);
    setBusy(false, shown);
    emit statusMessage(shown);
  }
  refreshMetrics();
  refreshControls();
  return on_screen;
}

void ResultPanel::logResultOnScreen(const QString& change, qint64 latency_ms, qint64 job_ms, qint64 figures_ms,
                                    double strength, int chunks_solved, const QString& how) const {
  app_log::write(QStringLiteral("live: %1 -> cleaned result on screen %2 ms after the change (job %3 ms, figures %4 ms, "
                                "strength %5, %6 frames, clean-up solved %7 of %8 chunks, %9)")
                     .arg(change)
                     .arg(latency_ms)
                     .arg(job_ms)
                     .arg(figures_ms)
                     .arg(strength, 0, 'f', 2)
                     .arg(result_->cleaned.frameCount())  // the content's frames, as in the status
                     .arg(chunks_solved)
                     .arg(result_->report.chunks)
                     .arg(how));
}

void ResultPanel::setBusy(bool busy, const QString& status) {
  const bool changed = busy != busy_;
  busy_ = busy;
  progress_->setBusy(busy);
  status_label_->setText(status);
  refreshControls();
  if (changed) emit busyChanged(busy);
}

void ResultPanel::clearResult() {
  const bool had = result_ != nullptr;
  result_.reset();
  stale_reason_.clear();
  status_label_->clear();
  refreshMetrics();
  if (had) emit resultChanged();
}

void ResultPanel::refreshControls() {
  if (given_stylized_)
    showNetworkInChoice(tr("%1 (stylized clip)").arg(network_name_), QString());
  else if (!hasNetwork())
    network_choice_->setCurrentIndex(-1);
  // A disabled Stylize says why, and how to fix it, beside the content and on the button.
  QString missing;
  if (!content_) missing = tr("Choose a content clip first: right-click a clip in the Clips table.");
  else if (!content_->mapping)
    missing = tr("%1 cannot be stylized: %2. Load a mapping file from the clip's context menu (right-click it in the "
                 "Clips table).").arg(content_->name, content_->mapping_problem);
  else if (!canStylize()) missing = tr("Choose a style first.");
  if (content_ && !content_->mapping)
    content_label_->setText(tr("%1<br><span style=\"color:#d08a2a\">Not mapped: load a mapping file from the clip's "
                               "context menu.</span>").arg(content_->name.toHtmlEscaped()));
  else
    content_label_->setText(content_ ? content_->name.toHtmlEscaped() : tr("<i>none</i>"));
  content_label_->setToolTip(content_ && !content_->mapping ? missing : QString());
  stylize_button_->setEnabled(canStylize() && !busy_);
  stylize_button_->setToolTip(missing.isEmpty() ? tr("Stylize the content and clean up the result") : missing);
  strength_slider_->setEnabled(!given_stylized_);
  keep_path_->setEnabled(!given_stylized_);
  // A network without stored style targets (files before format 3) has no refinement to aim.
  aim_choice_->setEnabled(!given_stylized_ && (!stylizer_ || stylizer_->refinementSteps() > 0));
  cancel_button_->setEnabled(busy_);
  export_button_->setEnabled(result_ != nullptr && !busy_);
  metrics_->setEnabled(!resultIsStale());  // greyed: the figures of an out-of-date result
}

void ResultPanel::refreshMetrics() { metrics_->showResult(result_.get()); }

}  // namespace motionstyle
