#pragma once
// JobRunner: runs one long core job at a time on its own worker thread, the Qt threading examples'
// pattern in one place:
//   - the job's body runs on the worker thread with style::TrainingCallbacks whose progress goes out as
//     the progress() signal (queued, throttled) and whose cancel flag is the runner's (an atomic the
//     core polls; cancel() returns at once);
//   - the body returns a completion, run on the GUI thread, that hands the typed result over; a job
//     that was cancelled runs none, and every signal of a job that is no longer the current one is
//     dropped (stale results never arrive);
//   - failures are turned into one user message by errorText() and reported by failed();
//   - the destructor cancels the job in flight, quits the thread and waits for it.

#include <QObject>
#include <QString>
#include <QThread>

#include <atomic>
#include <chrono>
#include <exception>
#include <functional>
#include <memory>

#include "style/training.h"

namespace motionstyle {

// The message for a failure of a job or an action (one translation of the core's errors for the app):
// bad input names the file and line, an unwritable file its path, memory and internal errors say so.
QString errorText(const std::exception_ptr& error);

class JobRunner : public QObject {
  Q_OBJECT

 public:
  // The completion the body returns: runs on the GUI thread when the job finished (not cancelled).
  using Completion = std::function<void()>;
  using Body = std::function<Completion(const style::TrainingCallbacks& callbacks)>;

  explicit JobRunner(QObject* parent = nullptr);
  ~JobRunner() override;  // cancels, quits and waits

  // Starts `body` unless a job is running (false then). `title` heads a failure report.
  bool start(const QString& title, Body body);
  void cancel();
  bool isBusy() const { return busy_; }
  // At most one step progress per this many seconds goes out (loading and epoch ends always do).
  void setProgressInterval(double seconds) { progress_interval_ = seconds; }

 signals:
  void progress(const motionstyle::style::TrainingProgress& progress);
  void logMessage(const QString& text);
  void failed(const QString& title, const QString& message);
  void finished(bool completed);  // after the completion (completed) or a cancellation / failure
  void busyChanged(bool busy);

 private:
  void end(quint64 id, bool completed);

  QThread thread_;
  QObject* context_ = nullptr;  // lives in thread_: queued work runs there
  std::shared_ptr<std::atomic<bool>> cancel_;
  quint64 job_id_ = 0;
  bool busy_ = false;
  double progress_interval_ = 0.05;
};

}  // namespace motionstyle
