#include "cleanup_worker.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <new>

#include "common/errors.h"
#include "display_space.h"
#include "ik/contacts.h"
#include "motion/kinematics.h"
#include "motion/resample.h"
#include "style/cancellation.h"
#include "style/stylized_cleanup.h"

namespace motionstyle {
namespace {

bool sameRate(double a, double b) { return std::abs(a - b) <= 1e-6 * b; }

Eigen::MatrixXi contactsPerFrame(const Eigen::MatrixXd& contacts) {
  return (contacts.transpose().array() > 0.5).cast<int>().matrix();
}

// Overrides at the content's rate -> the stylized rate (nearest frame in time), padded with "auto" if
// the schedule comes out a frame short.
Eigen::MatrixXi overridesAtRate(const Eigen::MatrixXi& overrides, double content_fps, double fps, int frames) {
  Eigen::MatrixXi at_rate = labelsAtRate(overrides, content_fps, fps);
  Eigen::MatrixXi out = Eigen::MatrixXi::Constant(frames, kContactCount, -1);
  const Eigen::Index rows = std::min<Eigen::Index>(frames, at_rate.rows());
  out.topRows(rows) = at_rate.topRows(rows);
  return out;
}

}  // namespace

CleanupResult runCleanupJob(const CleanupJob& job, const std::atomic<bool>& cancel) {
  const auto start = std::chrono::steady_clock::now();
  CleanupResult result;
  if (job.stylized) {
    result.stylized = *job.stylized;
  } else {
    if (!job.stylizer) throw std::invalid_argument("no style network and no stylized clip to clean up");
    const MotionFeatures features = extractFeatures(job.content, job.mapping);
    style::throwIfCancelled(&cancel);
    result.stylized = job.stylizer->stylize(features, job.strength);
  }
  style::throwIfCancelled(&cancel);

  // As style::cleanUpStylizedClip: the solve runs at the stylized rate, the locks follow the feet of
  // the output (a style changes timing), and the user's overrides win over the detection.
  const style::StylizedClip& stylized = result.stylized;
  const Motion at_rate = sameRate(job.content.fps(), stylized.fps) ? job.content : resampleMotion(job.content, stylized.fps);
  if (at_rate.frameCount() != stylized.frameCount())
    throw std::invalid_argument("the stylized clip has " + std::to_string(stylized.frameCount()) +
                                " frames, its content " + std::to_string(at_rate.frameCount()) + " at the same rate");
  const FeatureAnchor& anchor = stylized.anchor;
  const Eigen::Vector3d up = anchor.convention.fileUp();
  const double floor = style::fileFloorHeight(anchor);
  Eigen::MatrixXi contacts = detectContacts(stylized.world_positions, canonicalContactJoints(), up, floor, stylized.fps,
                                            restPoseBodyHeight(job.content.skeleton, up));
  if (job.contact_overrides.size() > 0)
    contacts = applyContactOverrides(
        contacts, overridesAtRate(job.contact_overrides, job.content.fps(), stylized.fps, stylized.frameCount()));
  style::throwIfCancelled(&cancel);

  const CleanupInput input(at_rate, job.mapping, stylized.world_positions, contacts, up, floor,
                           anchor.convention.cm_per_unit);
  Motion cleaned = cleanupMotion(input, job.options, &result.report);
  style::throwIfCancelled(&cancel);

  const Eigen::MatrixXd content_world = worldPositions(at_rate);
  MetricsInput raw(stylized.world_positions, identityCanonicalJoints(), canonicalBones(content_world, job.mapping));
  raw.contacts = contactsPerFrame(stylized.contacts);
  raw.up = up;
  raw.floor_height = floor;
  raw.cm_per_unit = anchor.convention.cm_per_unit;
  raw.fps = stylized.fps;
  result.raw_metrics = computeMetrics(raw);

  const Eigen::MatrixXd cleaned_world = worldPositions(cleaned);
  MetricsInput after(cleaned_world, job.mapping.joints, skeletonBones(cleaned.skeleton));
  after.contacts = contacts;
  after.targets = stylized.world_positions;
  after.up = up;
  after.floor_height = floor;
  after.cm_per_unit = anchor.convention.cm_per_unit;
  after.fps = stylized.fps;
  result.cleaned_metrics = computeMetrics(after);
  result.contacts = contacts;

  result.cleaned = sameRate(cleaned.fps(), job.content.fps()) ? std::move(cleaned) : resampleMotion(cleaned, job.content.fps());
  // Back at the content's rate the clip can come out a frame or two short (720 frames at 120 fps are
  // 360 at 60 fps, which give 719 at 120 fps): the content's last frames lie past the last solved one.
  // They hold that pose, as resampling does past the end, so the export has the content's frame count.
  const Eigen::Index solved = result.cleaned.values.rows();
  if (solved > 0 && solved < job.content.frameCount()) {
    result.cleaned.values.conservativeResize(job.content.frameCount(), Eigen::NoChange);
    for (Eigen::Index f = solved; f < result.cleaned.values.rows(); ++f)
      result.cleaned.values.row(f) = result.cleaned.values.row(solved - 1);
  }
  result.cleaned.source = job.content.source;
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
