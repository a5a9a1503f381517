#pragma once
// JobRunner: runs the core's long jobs (style/*_job.h, adaptation.h) one at a time on a worker thread
// it owns, the Qt threading examples' pattern in one place for every panel:
//   - the body runs on the worker thread; it gets a Context with the cancel flag (an atomic the core
//     polls) and post(), the one way to reach the GUI thread: queued, and dropped once the job is no
//     longer the current one (stale progress and results never arrive);
//   - the body returns a completion, run on the GUI thread to hand the typed result over (null: none);
//   - a failure is translated once (error_text.h) and reported by failed(title, message);
//   - cancel() asks the job to stop and still delivers what it returns (a cancelled training keeps the
//     network of its last epoch); abandon() drops it at once (nothing of it arrives, the runner is free;
//     a job started next waits on the thread until the old body returns); restart() = abandon + start;
//   - the destructor cancels the job in flight, quits the thread and waits for it.

#include <QObject>
#include <QString>
#include <QThread>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>

#include "style/training.h"

namespace motionstyle {

class JobRunner : public QObject {
  Q_OBJECT

 public:
  // What the body gets (on the worker thread).
  class Context {
   public:
    const std::atomic<bool>* cancelFlag() const { return cancel_.get(); }
    bool cancelled() const { return cancel_->load(); }
    // Runs `on_gui` on the GUI thread unless the job is stale by then.
    void post(std::function<void()> on_gui) const;
    // As post(), at most once per the runner's progress interval unless `always`.
    void postThrottled(std::function<void()> on_gui, bool always = false) const;
    // Callbacks for the core's training jobs: progress and log posted to these GUI-thread receivers.
    // Progress is throttled; loading messages, the first step and the last epoch end always go out.
    style::TrainingCallbacks trainingCallbacks(std::function<void(const style::TrainingProgress&)> on_progress,
                                               std::function<void(const QString&)> on_log) const;

   private:
    friend class JobRunner;
    JobRunner* runner_ = nullptr;
    quint64 id_ = 0;
    std::shared_ptr<std::atomic<bool>> cancel_;
    std::shared_ptr<std::chrono::steady_clock::time_point> last_post_;
    double interval_ = 0.05;
  };
  using Completion = std::function<void()>;
  using Body = std::function<Completion(const Context& context)>;

  explicit JobRunner(QObject* parent = nullptr);
  ~JobRunner() override;

  // Starts `body` unless a job is running (false then). `title` heads a failure report.
  bool start(const QString& title, Body body);
  void restart(const QString& title, Body body);
  void cancel();
  void abandon();
  // cancel(), then waits (handling events but not user input) until the job has ended and its
  // completion has run: for closing the window with a cancelled run's result in hand.
  void cancelAndWait();
  bool isBusy() const { return busy_; }
  bool isCancelling() const { return busy_ && cancel_ && cancel_->load(); }
  // At most one throttled post per this many seconds.
  void setProgressInterval(double seconds) { progress_interval_ = seconds; }

 signals:
  void failed(const QString& title, const QString& message);
  void finished(bool completed);  // after the completion; false: cancelled, abandoned or failed
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
