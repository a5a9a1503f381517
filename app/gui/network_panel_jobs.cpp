// NetworkPanel's jobs: training (new / retrain / resume) and the optimisation method on the panel's
// JobRunner, their progress, results and live preview, and the closing rules.
#include "network_panel.h"

#include <QCoreApplication>
#include <QDateTime>
#include <QDoubleSpinBox>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QProgressBar>
#include <QTabWidget>
#include <QTemporaryDir>

#include <cmath>
#include <exception>

#include "adapt_tab.h"
#include "features/feature_layout.h"
#include "loss_curve_widget.h"
#include "error_text.h"
#include "job_runner.h"
#include "style/optimization_transfer_job.h"

namespace motionstyle {
namespace {

// "0.4 s" under 10 s (a quick run read "0:00"), else "m:ss" or "h:mm:ss".
QString formatDuration(double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) return QStringLiteral("--:--");
  if (seconds < 9.95) return QStringLiteral("%1 s").arg(seconds, 0, 'f', 1);
  const long long total = std::llround(seconds);
  if (total >= 3600)
    return QStringLiteral("%1:%2:%3")
        .arg(total / 3600)
        .arg(total / 60 % 60, 2, 10, QLatin1Char('0'))
        .arg(total % 60, 2, 10, QLatin1Char('0'));
  return QStringLiteral("%1:%2").arg(total / 60).arg(total % 60, 2, 10, QLatin1Char('0'));
}

QString termsText(double total, const std::vector<style::NamedLoss>& terms) {
  QString text = QStringLiteral("total %1").arg(total, 0, 'g', 4);
  for (const style::NamedLoss& term : terms)
    text += QStringLiteral(", %1 %2").arg(QString::fromStdString(term.name)).arg(term.value, 0, 'g', 3);
  return text;
}

}  // namespace

std::filesystem::path NetworkPanel::scratchFile(const QString& name) {
  if (!scratch_) {
    scratch_ = std::make_unique<QTemporaryDir>(QDir(QDir::tempPath()).filePath(QStringLiteral("motionstyle-training-XXXXXX")));
    if (!scratch_->isValid()) {
      scratch_.reset();
      return {};
    }
  }
  return std::filesystem::path(scratch_->filePath(name).toStdString());
}

QString NetworkPanel::lastCheckpointFile() const { return last_checkpoint_; }

void NetworkPanel::capturePreviewTarget() {
  preview_target_ = {};
  const LoadedClip* content = roles_.content();
  if (content == nullptr || content->frameCount() < 1) return;
  const LoadedClip& clip = *content;
  // The output is in the content's file space: the content's display space puts it on the same floor at
  // the same size, and the timeline's rate keeps it in step with the other figures.
  preview_target_.valid = true;
  preview_target_.content_id = clip.id;
  preview_target_.name = clip.name;
  preview_target_.display_space = clip.display_space;
  const double display_fps = roles_.display_fps();
  preview_target_.display_fps = display_fps > 0 ? display_fps : clip.fps();
}

void NetworkPanel::onPreview(const std::shared_ptr<const style::StylizedClip>& clip) {
  if (!clip || !preview_target_.valid || clip->frameCount() < 1) return;
  // The run previews the content clip it started with; once the user picks another, stay quiet.
  const LoadedClip* content = roles_.content();
  if (content == nullptr || content->id != preview_target_.content_id) return;
  try {
    const Eigen::MatrixXd shown = rowsAtRate(preview_target_.display_space.toDisplay(clip->world_positions), clip->fps,
                                             preview_target_.display_fps);
    const std::vector<int> parents(kCanonicalParent.begin(), kCanonicalParent.end());
    preview_shown_ = true;
    preview_content_id_ = preview_target_.content_id;
    emit previewReady(figureFromPositions(tr("%1 (preview)").arg(preview_target_.name), FigureRole::Output, parents, shown));
  } catch (const std::exception& error) {
    status_label_->setText(tr("Could not show the preview: %1").arg(QString::fromStdString(error.what())));
  }
}

bool NetworkPanel::startTraining(bool retrain) {
  if (isBusy()) {
    report(tr("A job is running"), tr("Cancel the running job before starting another."));
    return false;
  }
  const TrainingForm form = trainingForm();
  style::StyleTrainingJob job;
  style::StyleTrainingConfig& config = job.config;
  for (const QString& file : roles_.training_paths()) config.content.emplace_back(file.toStdString());
  for (const QString& folder : trainingFolders()) config.content.emplace_back(folder.toStdString());
  if (config.content.empty())
    for (const QString& file : defaultTrainingPaths(roles_)) config.content.emplace_back(file.toStdString());
  if (config.content.empty()) {
    report(tr("No training set"), tr("Open the clips to train on (any clip but the Style clip is used), right-click "
                                          "clips and choose \"In the Training Set\", or add a folder of BVH files on the "
                                          "Train tab."));
    return false;
  }
  config.styles = styleSources();
  if (config.styles.empty()) {
    report(tr("No style clip"), tr("Give a clip the Style role, or add style clips on the Train tab."));
    return false;
  }
  config.weights = form.weights;
  config.settings.epochs = form.epochs;
  config.settings.learning_rate = form.learning_rate;
  config.settings.dataset.bad_files = style::BadFilePolicy::Skip;  // a bad file in a folder is logged, not fatal

  QString base_name = QString::fromStdString(config.styles.front().file.stem().string());
  if (retrain) {
    const std::shared_ptr<const nn::StyleModel> model = network_list_->currentNetwork();
    if (!model) {
      report(tr("No network selected"), tr("Select the network to retrain on the Networks tab."));
      return false;
    }
    // The warm start keeps the selected network's shape and the loss network it was trained against.
    config.loss_network_model = nn::embeddedLossNetwork(*model);
    config.shape = model->transformation.shape();
    const std::filesystem::path init = scratchFile(QStringLiteral("retrain-start.net"));
    try {
      if (init.empty()) throw std::runtime_error("no temporary folder");
      nn::saveStyleModel(*model, init);
    } catch (const std::exception& error) {
      report(tr("Could not start retraining"), QString::fromStdString(error.what()));
      return false;
    }
    config.settings.init = init;
    base_name = network_list_->currentNetworkName() + tr(" retrained");
  } else {
    const QString loss_file = lossNetworkFile();
    if (loss_file.isEmpty()) {
      report(tr("No loss network"), tr("Choose the loss network (.net file) on the Train tab."));
      return false;
    }
    config.loss_network = loss_file.toStdString();
    config.shape.hidden = form.hidden_units;
  }
  const std::filesystem::path checkpoint =
      scratchFile(QStringLiteral("run-%1.net.checkpoint").arg(QDateTime::currentDateTime().toString(QStringLiteral("yyyyMMdd-hhmmss-zzz"))));
  if (checkpoint.empty()) {
    report(tr("Could not start training"), tr("No temporary folder for the checkpoints in %1.").arg(QDir::tempPath()));
    return false;
  }
  config.settings.checkpoint = checkpoint;
  // The scratch folder goes with the session: a checkpoint that survives a power cut buys nothing, and
  // an fsync in flight would hold up Cancel and closing the window.
  config.settings.checkpoint_durability = FileDurability::Unsynced;
  last_checkpoint_ = QString::fromStdString(checkpoint.string());
  if (const LoadedClip* content = roles_.content()) job.preview_content = content->path.toStdString();
  capturePreviewTarget();

  // Named after the style and the start time, so that runs from one style clip tell apart at a glance;
  // no character a file name would refuse (it is the suggested file name when saving).
  training_name_ = tr("%1 %2").arg(base_name, QDateTime::currentDateTime().toString(QStringLiteral("yyyy-MM-dd HHmm")));
  return runTraining(std::move(job), retrain ? tr("Retraining from %1...").arg(base_name) : tr("Loading the training clips..."));
}

bool NetworkPanel::canResumeTraining() const {
  std::error_code ignored;
  return resumable_ && std::filesystem::exists(resumable_->config.settings.checkpointPath(), ignored);
}

bool NetworkPanel::resumeTraining() {
  if (isBusy()) {
    report(tr("A job is running"), tr("Cancel the running job before starting another."));
    return false;
  }
  if (!canResumeTraining()) {
    report(tr("Nothing to resume"), tr("Only a cancelled training that completed an epoch can be resumed."));
    return false;
  }
  style::StyleTrainingJob job = *resumable_;
  job.config.settings.resume = true;  // from the checkpoint: the warm start is already in it
  job.config.settings.init.clear();
  job.config.init_model.reset();
  training_name_ = resumable_name_;
  if (const LoadedClip* content = roles_.content()) job.preview_content = content->path.toStdString();
  capturePreviewTarget();
  return runTraining(std::move(job), tr("Resuming %1 from its checkpoint...").arg(training_name_));
}

bool NetworkPanel::runTraining(style::StyleTrainingJob job, const QString& status) {
  resumable_.reset();
  const style::StyleTrainingJob kept = job;  // resumable if cancelled
  const bool started = runner_->start(tr("Could not train the network"), [this, job = std::move(job)](
                                                                          const JobRunner::Context& context) {
    const style::TrainingCallbacks callbacks = context.trainingCallbacks(
        [this](const style::TrainingProgress& p) { onTrainingProgress(p); },
        [this](const QString& line) { status_label_->setText(line); });
    const auto preview = [this, &context](std::shared_ptr<const style::StylizedClip> clip, int) {
      context.post([this, clip] { onPreview(clip); });
    };
    auto result = std::make_shared<const style::StyleTrainingJob::Result>(job.run(callbacks, preview));
    return JobRunner::Completion([this, result] { onTrainingFinished(*result); });
  });
  if (!started) return false;
  running_ = Running::Training;
  resumable_ = kept;
  resumable_->preview_content.clear();
  resumable_name_ = training_name_;
  loss_curve_->clear();
  loss_curve_->setXAxisName(tr("epochs"));
  emit previewCleared();
  progress_bar_->setRange(0, 0);
  progress_bar_->setFormat(tr("Loading clips..."));
  status_label_->setText(status);
  updateButtons();
  // Show the panel (it may be a tab behind the result panel): the progress and curves are here.
  for (QWidget* ancestor = parentWidget(); ancestor != nullptr; ancestor = ancestor->parentWidget()) {
    if (ancestor->inherits("QDockWidget")) {
      ancestor->show();
      ancestor->raise();
      break;
    }
  }
  tabs_->setCurrentIndex(1);
  return true;
}

bool NetworkPanel::startTransfer(int iterations) {
  if (isBusy()) {
    report(tr("A job is running"), tr("Cancel the running job before starting another."));
    return false;
  }
  const LoadedClip* content = roles_.content();
  const LoadedClip* style = roles_.style();
  if (content == nullptr || style == nullptr) {
    report(tr("Content and style needed"), tr("The optimisation method needs a clip with the Content role and one with "
                                              "the Style role."));
    return false;
  }
  style::OptimizationTransferJob job;
  // The loss network: the file on the Train tab, else the one embedded in the selected style network.
  const QString loss_file = lossNetworkFile();
  try {
    if (!loss_file.isEmpty()) {
      job.loss_network = style::loadCompatibleLossNetwork(loss_file.toStdString());
    } else if (const auto model = network_list_->currentNetwork()) {
      job.loss_network = nn::embeddedLossNetwork(*model);
    } else {
      report(tr("No loss network"), tr("Choose the loss network (.net file) on the Train tab."));
      return false;
    }
  } catch (...) {
    report(tr("Could not load the loss network"), errorText(std::current_exception(), loss_file));
    return false;
  }
  job.content = content->path.toStdString();
  job.style = style->path.toStdString();
  job.options.setIterations(iterations);
  job.options.style_weight = optimise_tab_->styleWeight();
  const QString label = tr("optimised towards %1").arg(style->name);
  const int total = job.options.iterations + job.options.constraint_iterations;

  // The progress (throttled) and the result reach the GUI thread through the runner's context.
  const auto show_progress = [this, iterations, total](const style::OptimizationProgress& p) {
    const int done = (p.stage == "style" ? 0 : iterations) + p.iteration;
    progress_bar_->setRange(0, total);
    progress_bar_->setValue(done);
    const double eta = done > 0 ? p.elapsed_seconds / done * (total - done) : -1.0;
    progress_bar_->setFormat(tr("%1 %2/%3, ETA %4").arg(QString::fromStdString(p.stage)).arg(p.iteration).arg(p.iterations)
                                 .arg(formatDuration(eta)));
    // The plot follows this run's terms (unweighted), not the last training's.
    loss_curve_->addPoint(QStringLiteral("content"), done, p.content);
    loss_curve_->addPoint(QStringLiteral("style"), done, p.style);
    if (p.stage != "style")
      for (const auto& [term, value] : {std::pair{"foot", p.foot}, std::pair{"bone", p.bone}, std::pair{"trajectory", p.trajectory}})
        loss_curve_->addPoint(QString::fromLatin1(term), done, value);
  };
  const bool started = runner_->start(tr("Could not run the optimisation method"),
                                      [this, job = std::move(job), show_progress, label](const JobRunner::Context& context) {
    style::OptimizationCallbacks callbacks;
    callbacks.cancel = context.cancelFlag();
    callbacks.progress = [&context, show_progress](const style::OptimizationProgress& p) {
      context.postThrottled([show_progress, p] { show_progress(p); }, p.iteration == 1 || p.iteration == p.iterations);
    };
    auto result = std::make_shared<const style::OptimizationTransferJob::Result>(job.run(callbacks));
    return JobRunner::Completion([this, result, label] {
      showOutcome(result->cancelled ? tr("Optimisation cancelled") : tr("Optimised in %1").arg(formatDuration(result->seconds)));
      if (result->clip) emit stylizedClipReady(*result->clip, label);
    });
  });
  if (!started) return false;
  running_ = Running::Transfer;
  loss_curve_->clear();
  loss_curve_->setXAxisName(tr("iterations"));
  progress_bar_->setRange(0, 0);  // busy until the first iteration reports (not the last run's bar)
  progress_bar_->setFormat(tr("Starting..."));
  status_label_->setText(tr("Optimising %1 towards %2...").arg(content->name, style->name));
  updateButtons();
  return true;
}

void NetworkPanel::cancelJob() {
  if (running_ == Running::None) return;
  runner_->cancel();
  progress_bar_->setFormat(tr("Cancelling..."));
  status_label_->setText(running_ == Running::Training ? tr("Cancelling: the last completed epoch is kept.")
                                                       : tr("Cancelling..."));
}

void NetworkPanel::onJobDone(bool completed) {
  running_ = Running::None;
  // A run that reached its end leaves a full bar saying so; any other (cancelled, failed) an empty
  // one: a full bar once said "Idle" after every run. The status line says how it ended.
  progress_bar_->setRange(0, 1000);
  progress_bar_->setValue(completed ? progress_bar_->maximum() : progress_bar_->minimum());
  progress_bar_->setFormat(completed ? tr("Done") : tr("Idle"));
  updateButtons();
  emit jobFinished();
}

void NetworkPanel::onTrainingProgress(const style::TrainingProgress& p) {
  emit trainingProgress(p);
  if (p.phase == style::TrainingProgress::Phase::Loading) {
    progress_bar_->setRange(0, 0);
    progress_bar_->setFormat(QString::fromStdString(p.message));
    return;
  }
  if (runner_->isCancelling()) return;
  const double steps = std::max(1, p.steps_per_epoch);
  const double position = (p.epoch - 1) + std::min(1.0, p.step / steps);
  progress_bar_->setRange(0, 1000);
  progress_bar_->setValue(static_cast<int>(std::lround(1000.0 * position / std::max(1, p.epochs))));
  progress_bar_->setFormat(tr("Epoch %1/%2, ETA %3").arg(p.epoch).arg(p.epochs).arg(formatDuration(p.eta_seconds)));
  if (p.phase == style::TrainingProgress::Phase::Training) {
    for (const style::NamedLoss& term : p.terms) loss_curve_->addPoint(QString::fromStdString(term.name), position, term.value);
    status_label_->setText(tr("Epoch %1/%2, step %3/%4, %5 elapsed\n%6")
                               .arg(p.epoch).arg(p.epochs).arg(p.step).arg(p.steps_per_epoch)
                               .arg(formatDuration(p.elapsed_seconds), termsText(p.total, p.terms)));
  }
}

void NetworkPanel::onTrainingFinished(const style::StyleTrainingJob::Result& outcome) {
  const bool cancelled = outcome.status == style::TrainingStatus::Cancelled;
  if (!cancelled) resumable_.reset();
  if (outcome.model) {
    auto model = std::make_shared<nn::StyleModel>(*outcome.model);
    model->metadata.properties.emplace_back("created", QDateTime::currentDateTime().toString(Qt::ISODate).toStdString());
    network_list_->addNetwork(std::move(model), cancelled ? tr("%1 (epoch %2)").arg(training_name_).arg(outcome.epochs_completed)
                                                          : training_name_);
  }
  if (!cancelled) {
    progress_bar_->setValue(progress_bar_->maximum());
    showOutcome(tr("Trained %n epoch(s) in %1. Not saved yet: Save As... on the Networks tab.", nullptr,
                   outcome.epochs_completed).arg(formatDuration(outcome.seconds)));
  } else if (outcome.model) {
    showOutcome(tr("Training cancelled. Kept the network of epoch %1 (checkpoint %2); not saved yet. Resume continues it.")
                    .arg(outcome.epochs_completed).arg(QString::fromStdString(outcome.checkpoint.string())));
  } else {
    showOutcome(tr("Training cancelled before the first epoch ended: no network to keep."));
  }
  tabs_->setCurrentIndex(0);
}

bool NetworkPanel::prepareToClose() {
  if (adapt_tab_->isBusy()) {
    if (ask(tr("Stop and close?"), tr("Adapting the networks to your clips. Stop it and close?\n\nNothing is changed."),
            QMessageBox::Yes | QMessageBox::No) != QMessageBox::Yes)
      return false;
    adapt_tab_->cancel();
  }
  if (running_ != Running::None) {
    const QString what = running_ == Running::Training ? tr("A training run is in progress. Stop it and close?\n\nThe network of the last "
                                               "completed epoch is kept; no network file is left half-written.")
                                          : tr("The optimisation method is running. Stop it and close?");
    if (ask(tr("Stop and close?"), what, QMessageBox::Yes | QMessageBox::No) != QMessageBox::Yes) return false;
    // Wait for the job to stop and hand over what it kept (the cancelled run's network), so that the
    // network can be offered for saving below.
    runner_->cancelAndWait();
  }
  return network_list_->prepareToClose();
}

}  // namespace motionstyle
