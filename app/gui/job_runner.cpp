#include "job_runner.h"

#include <QCoreApplication>

#include <new>

#include "common/errors.h"
#include "style/cancellation.h"

namespace motionstyle {

QString errorText(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const InputError& e) {
    return QString::fromStdString(e.what());
  } catch (const WriteError& e) {
    return QCoreApplication::translate("JobRunner", "Could not write %1: %2")
        .arg(QString::fromStdString(e.file()), QString::fromStdString(e.what()));
  } catch (const style::TrainingDiverged& e) {
    return QString::fromStdString(e.what());
  } catch (const std::bad_alloc&) {
    return QCoreApplication::translate("JobRunner", "Not enough memory.");
  } catch (const std::invalid_argument& e) {
    return QString::fromStdString(e.what());
  } catch (const std::exception& e) {
    return QCoreApplication::translate("JobRunner", "Internal error: %1").arg(QString::fromStdString(e.what()));
  } catch (...) {
    return QCoreApplication::translate("JobRunner", "Internal error.");
  }
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
  auto cancel = cancel_;
  const double interval = progress_interval_;
  QMetaObject::invokeMethod(context_, [this, id, cancel, title, interval, body = std::move(body)] {
    style::TrainingCallbacks callbacks;
    callbacks.cancel = cancel.get();
    auto last = std::make_shared<std::chrono::steady_clock::time_point>();
    callbacks.progress = [this, id, last, interval](const style::TrainingProgress& p) {
      const auto now = std::chrono::steady_clock::now();
      if (p.phase == style::TrainingProgress::Phase::Training &&
          std::chrono::duration<double>(now - *last).count() < interval)
        return;
      *last = now;
      QMetaObject::invokeMethod(this, [this, id, p] { if (id == job_id_) emit progress(p); }, Qt::QueuedConnection);
    };
    callbacks.log = [this, id](const std::string& text) {
      const QString line = QString::fromStdString(text);
      QMetaObject::invokeMethod(this, [this, id, line] { if (id == job_id_) emit logMessage(line); }, Qt::QueuedConnection);
    };
    Completion completion;
    std::exception_ptr error;
    try {
      completion = body(callbacks);
    } catch (const style::OperationCancelled&) {
      completion = nullptr;
    } catch (...) {
      error = std::current_exception();
    }
    const bool cancelled = cancel->load();
    QMetaObject::invokeMethod(this, [this, id, title, error, cancelled, completion = std::move(completion)] {
      if (id != job_id_) return;  // replaced or shut down: nothing stale arrives
      if (error) {
        emit failed(title, errorText(error));
        end(id, false);
      } else if (cancelled || !completion) {
        end(id, false);
      } else {
        completion();
        end(id, true);
      }
    }, Qt::QueuedConnection);
  }, Qt::QueuedConnection);
  return true;
}

void JobRunner::cancel() {
  if (busy_ && cancel_) cancel_->store(true);
}

void JobRunner::end(quint64 id, bool completed) {
  if (id != job_id_ || !busy_) return;
  busy_ = false;
  emit finished(completed);
  emit busyChanged(false);
}

}  // namespace motionstyle
