#include "cleanup_worker.h"

#include <chrono>
#include <exception>
#include <new>

#include "common/errors.h"
#include "style/cancellation.h"
#include "style/stylized_cleanup.h"

namespace motionstyle {

CleanupResult runCleanupJob(const CleanupJob& job, const std::atomic<bool>& cancel) {
  const auto start = std::chrono::steady_clock::now();
  CleanupResult result;
  if (job.stylized) {
    result.stylized = *job.stylized;
  } else {
    if (!job.stylizer) throw std::invalid_argument("no style network and no stylized clip to clean up");
    const MotionFeatures features = extractFeatures(job.content, job.mapping);
    style::throwIfCancelled(&cancel);
    result.stylized = job.stylizer->stylize(features, job.strength, job.path);
  }
  style::throwIfCancelled(&cancel);
  style::StylizedCleanup cleanup =
      style::cleanUpStylizedClip(job.content, job.mapping, result.stylized, job.options, 0.0, job.contact_overrides);
  style::throwIfCancelled(&cancel);
  result.cleaned = std::move(cleanup.motion);
  result.report = std::move(cleanup.report);
  result.raw_metrics = std::move(cleanup.raw);
  result.cleaned_metrics = std::move(cleanup.cleaned);
  result.contacts = std::move(cleanup.contacts);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

void CleanupWorker::run(std::shared_ptr<const CleanupJob> job, quint64 job_id) {
  if (cancel_->load()) {
    emit cancelled(job_id);
    return;
  }
  emit progress(job->stylized ? tr("Cleaning up...") : tr("Stylizing and cleaning up..."), job_id);
  try {
    auto result = std::make_shared<const CleanupResult>(runCleanupJob(*job, *cancel_));
    emit finished(std::move(result), job_id);
  } catch (const style::OperationCancelled&) {
    emit cancelled(job_id);
  } catch (const InputError& error) {
    emit failed(QString::fromStdString(error.what()), job_id);
  } catch (const std::bad_alloc&) {
    emit failed(tr("Not enough memory for this clip."), job_id);
  } catch (const std::exception& error) {
    emit failed(tr("Internal error: %1").arg(QString::fromStdString(error.what())), job_id);
  }
}

}  // namespace motionstyle
