#include "training_worker.h"

#include <QCoreApplication>

#include <chrono>
#include <exception>
#include <new>
#include <stdexcept>
#include <utility>

#include "common/errors.h"

namespace motionstyle {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Runs `job`; any exception becomes (title, message) for failed(). Returns false on failure.
template <typename Job, typename Fail>
bool runReportingErrors(const QString& what, Job&& job, Fail&& fail) {
  try {
    job();
    return true;
  } catch (const style::TrainingDiverged& error) {
    fail(QCoreApplication::translate("TrainingWorker", "Training diverged"),
         QCoreApplication::translate("TrainingWorker",
                                     "%1\n\nThe loss became NaN or infinite. Try a lower learning rate or smaller "
                                     "loss weights. The last good checkpoint is kept.")
             .arg(QString::fromStdString(error.what())));
  } catch (const InputError& error) {
    fail(QCoreApplication::translate("TrainingWorker", "Could not %1").arg(what), QString::fromStdString(error.what()));
  } catch (const WriteError& error) {
    fail(QCoreApplication::translate("TrainingWorker", "Could not write a file"),
         QCoreApplication::translate("TrainingWorker", "%1\n\nEarlier files were left intact.")
             .arg(QString::fromStdString(error.what())));
  } catch (const std::invalid_argument& error) {
    fail(QCoreApplication::translate("TrainingWorker", "Invalid settings"), QString::fromStdString(error.what()));
  } catch (const std::bad_alloc&) {
    fail(QCoreApplication::translate("TrainingWorker", "Out of memory"),
         QCoreApplication::translate("TrainingWorker", "Not enough memory to %1.").arg(what));
  } catch (const std::exception& error) {
    fail(QCoreApplication::translate("TrainingWorker", "Could not %1").arg(what),
         QCoreApplication::translate("TrainingWorker", "Internal error: %1").arg(QString::fromStdString(error.what())));
  }
  return false;
}

}  // namespace

void registerWorkerMetaTypes() {
  qRegisterMetaType<style::TrainingProgress>();
  qRegisterMetaType<style::OptimizationProgress>();
  qRegisterMetaType<TrainingOutcome>();
  qRegisterMetaType<std::shared_ptr<const nn::StyleModel>>();
  qRegisterMetaType<std::shared_ptr<const style::StylizedClip>>();
}

// ---- TrainingWorker -----------------------------------------------------------------------------

TrainingWorker::TrainingWorker(TrainingJob job, QObject* parent) : QObject(parent), job_(std::move(job)) {
  registerWorkerMetaTypes();
}

void TrainingWorker::makePreview(const nn::StyleModel& model, int epoch) {
  // Runs on the training thread between epochs: the compute pool is free and the stylize takes a few
  // milliseconds per thousand frames, so the preview costs the run almost nothing.
  const style::Stylizer stylizer(model);
  auto clip = std::make_shared<const style::StylizedClip>(stylizer.stylize(preview_clip_->features, 1.0));
  emit previewReady(std::move(clip), epoch);
}

void TrainingWorker::run() {
  const auto started = Clock::now();
  TrainingOutcome outcome;
  outcome.checkpoint = job_.config.settings.checkpointPath();
  std::shared_ptr<const nn::StyleModel> last_snapshot;
  // Name the checkpoint the user can go back to (it lives in the app's scratch folder).
  const auto fail = [this, &outcome](const QString& title, const QString& message) {
    std::error_code ignored;
    if (std::filesystem::exists(outcome.checkpoint, ignored))
      emit failed(title, message + tr("\n\nLast good checkpoint: %1").arg(QString::fromStdString(outcome.checkpoint.string())));
    else
      emit failed(title, message);
  };

  // The preview clip is optional: a content clip that cannot be featurised only loses the preview.
  if (!job_.preview_content.empty()) {
    try {
      preview_clip_ = style::loadMotionClip(job_.preview_content, job_.config.settings.dataset);
    } catch (const std::exception& error) {
      emit logMessage(tr("no live preview: %1").arg(QString::fromStdString(error.what())));
    }
  }

  double last_progress = -1e9;
  bool step_sent = false;
  style::TrainingCallbacks callbacks;
  callbacks.cancel = &cancel_;
  callbacks.progress = [&](const style::TrainingProgress& p) {
    // Loading messages, the first step and the run's last epoch end always go out; other steps and
    // epoch ends are throttled (tiny networks close hundreds of epochs a second).
    using Phase = style::TrainingProgress::Phase;
    const bool loading = p.phase == Phase::Loading;
    const bool always = loading || (p.phase == Phase::Training && !step_sent) ||
                        (p.phase == Phase::EpochEnd && p.epoch == p.epochs);
    const double now = secondsSince(started);
    if (!always && now - last_progress < job_.progress_interval_seconds) return;
    if (!loading) {
      last_progress = now;
      step_sent = step_sent || p.phase == Phase::Training;
    }
    emit progress(p);
  };
  callbacks.log = [this](const std::string& text) { emit logMessage(QString::fromStdString(text)); };
  callbacks.style_snapshot = [&](const nn::StyleModel& model) {
    const int epoch = model.metadata.training.epochs;
    last_snapshot = std::make_shared<const nn::StyleModel>(model);
    emit snapshotReady(last_snapshot, epoch);
    const double now = secondsSince(started);
    if (preview_clip_ && now - last_preview_seconds_ >= job_.preview_interval_seconds && !cancel_.load()) {
      last_preview_seconds_ = now;
      try {
        makePreview(model, epoch);
      } catch (const std::exception& error) {
        emit logMessage(tr("live preview failed: %1").arg(QString::fromStdString(error.what())));
        preview_clip_.reset();
      }
    }
  };

  const bool ok = runReportingErrors(tr("train the network"), [&] {
    style::StyleTrainingResult result = style::trainStyleNetwork(job_.config, callbacks);
    outcome.cancelled = result.status == style::TrainingStatus::Cancelled;
    outcome.epochs_completed = result.epochs_completed;
    outcome.history = std::move(result.history);
    if (!outcome.cancelled) outcome.model = std::make_shared<const nn::StyleModel>(std::move(result.model));
    else outcome.model = last_snapshot;  // the weights after the last completed epoch = the checkpoint
  }, fail);
  if (ok) {
    outcome.seconds = secondsSince(started);
    emit finished(outcome);
  }
  emit done();
}

// ---- TransferWorker -----------------------------------------------------------------------------

TransferWorker::TransferWorker(TransferJob job, QObject* parent) : QObject(parent), job_(std::move(job)) {
  registerWorkerMetaTypes();
}

void TransferWorker::run() {
  const auto started = Clock::now();
  const auto fail = [this](const QString& title, const QString& message) { emit failed(title, message); };
  double last_progress = -1e9;
  style::OptimizationCallbacks callbacks;
  callbacks.cancel = &cancel_;
  callbacks.progress = [&](const style::OptimizationProgress& p) {
    const double now = secondsSince(started);
    if (p.iteration != p.iterations && p.iteration != 1 && now - last_progress < job_.progress_interval_seconds) return;
    last_progress = now;
    emit progress(p);
  };
  runReportingErrors(tr("run the optimisation method"), [&] {
    const style::MotionClip content = style::loadMotionClip(job_.content);
    const style::MotionClip style_clip =
        style::loadMotionClip(job_.style, style::styleClipOptions({}, job_.autoencoder.network.shape().width));
    if (cancel_.load()) {
      emit finished(nullptr, true, secondsSince(started));
      return;
    }
    style::OptimizationResult result = style::optimizeStyleTransfer(
        job_.autoencoder, content.features, style_clip.features, job_.style.filename().string(), job_.options, callbacks);
    if (result.cancelled) emit finished(nullptr, true, secondsSince(started));
    else emit finished(std::make_shared<const style::StylizedClip>(std::move(result.clip)), false, secondsSince(started));
  }, fail);
  emit done();
}

}  // namespace motionstyle
