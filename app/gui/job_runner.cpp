#include "job_runner.h"

#include <QCoreApplication>
#include <QEventLoop>

#include <exception>

#include "common/errors.h"
#include "error_text.h"

namespace motionstyle {

void JobRunner::Context::post(std::function<void()> on_gui) const {
  JobRunner* runner = runner_;
  const quint64 id = id_;
  QMetaObject::invokeMethod(runner, [runner, id, on_gui = std::move(on_gui)] {
    if (id == runner->job_id_ && runner->busy_) on_gui();
  }, Qt::QueuedConnection);
}

void JobRunner::Context::postThrottled(std::function<void()> on_gui, bool always) const {
  const auto now = std::chrono::steady_clock::now();
  if (!always && std::chrono::duration<double>(now - *last_post_).count() < interval_) return;
  *last_post_ = now;
  post(std::move(on_gui));
}

style::TrainingCallbacks JobRunner::Context::trainingCallbacks(
    std::function<void(const style::TrainingProgress&)> on_progress, std::function<void(const QString&)> on_log) const {
  style::TrainingCallbacks callbacks;
  callbacks.cancel = cancelFlag();
  auto step_sent = std::make_shared<bool>(false);
  if (on_progress)
    callbacks.progress = [this, on_progress, step_sent](const style::TrainingProgress& p) {
      using Phase = style::TrainingProgress::Phase;
      const bool first_step = p.phase == Phase::Training && !*step_sent;
      const bool always = p.phase == Phase::Loading || first_step || (p.phase == Phase::EpochEnd && p.epoch == p.epochs);
      if (p.phase == Phase::Training) *step_sent = true;
      if (p.phase == Phase::Loading) post([on_progress, p] { on_progress(p); });
      else postThrottled([on_progress, p] { on_progress(p); }, always);
    };
  if (on_log)
    callbacks.log = [this, on_log](const std::string& text) {
      const QString line = QString::fromStdString(text);
      post([on_log, line] { on_log(line); });
    };
  return callbacks;
}

JobRunner::JobRunner(QObject* parent) : QObject(parent) {
  thread_.setObjectName(QStringLiteral("MotionStyleJob"));
  context_ = new QObject;
  context_->moveToThread(&thread_);
  connect(&thread_, &QThread::finished, context_, &QObject::deleteLater);
  thread_.start();
}

JobRunner::~JobRunner() {
  if (cancel_) cancel_->store(true);
  thread_.quit();
  thread_.wait();
}

bool JobRunner::start(const QString& title, Body body) {
  if (busy_) return false;
  cancel_ = std::make_shared<std::atomic<bool>>(false);
  const quint64 id = ++job_id_;
  busy_ = true;
  emit busyChanged(true);
  // The context is copied into the worker's closure: the callbacks it makes refer to that copy, which
  // lives as long as the body runs.
  auto context = std::make_shared<Context>();
  context->runner_ = this;
  context->id_ = id;
  context->cancel_ = cancel_;
  context->last_post_ = std::make_shared<std::chrono::steady_clock::time_point>();
  context->interval_ = progress_interval_;
  QMetaObject::invokeMethod(context_, [this, id, title, context, body = std::move(body)] {
    Completion completion;
    std::exception_ptr error;
    if (!context->cancelled()) {
      try {
        completion = body(*context);
      } catch (const OperationCancelled&) {
        completion = nullptr;
      } catch (...) {
        error = std::current_exception();
      }
    }
    const bool cancelled = context->cancelled();
    QMetaObject::invokeMethod(this, [this, id, title, error, cancelled, completion = std::move(completion)] {
      if (id != job_id_ || !busy_) return;  // abandoned, replaced or shut down: nothing stale arrives
      if (error) {
        const FailureText text = failureText(error, title);
        emit failed(text.title, text.message);
        end(id, false);
        return;
      }
      if (completion) completion();
      end(id, completion && !cancelled);
    }, Qt::QueuedConnection);
  }, Qt::QueuedConnection);
  return true;
}

void JobRunner::restart(const QString& title, Body body) {
  abandon();
  start(title, std::move(body));
}

void JobRunner::cancel() {
  if (busy_ && cancel_) cancel_->store(true);
}

void JobRunner::cancelAndWait() {
  cancel();
  while (busy_) QCoreApplication::processEvents(QEventLoop::ExcludeUserInputEvents | QEventLoop::WaitForMoreEvents, 50);
}

void JobRunner::abandon() {
  if (!busy_) return;
  if (cancel_) cancel_->store(true);
  ++job_id_;  // everything the old job still posts is stale
  busy_ = false;
  emit finished(false);
  emit busyChanged(false);
}

void JobRunner::end(quint64 id, bool completed) {
  if (id != job_id_ || !busy_) return;
  busy_ = false;
  emit finished(completed);
  emit busyChanged(false);
}

}  // namespace motionstyle
