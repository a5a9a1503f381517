#pragma once
// The Result panel's background work: stylize the content clip with a style network, then clean it up
// with the Ceres IK onto the content's own skeleton, with quality metrics before and after. Runs in a
// worker QThread (CleanupWorker lives there); the panel talks to it only through queued signals.
//
// Cancellation: the panel sets the shared std::atomic<bool>; the worker polls it between steps
// (features, network, contact detection, IK, metrics) and reports cancelled() instead of a result. The
// IK solve itself has no cancellation hook (ik/cleanup.h); it is bounded by its time budget.

#include <QObject>
#include <QString>

#include <Eigen/Core>

#include <atomic>
#include <memory>
#include <optional>

#include "ik/cleanup.h"
#include "ik/metrics.h"
#include "mapping/joint_mapping.h"
#include "motion/motion.h"
#include "style/stylizer.h"

namespace motionstyle {

// What to compute (editable inputs, copied so the UI may change its own state meanwhile).
struct CleanupJob {
  Motion content;        // the user's clip at its own rate, file space
  JointMapping mapping;  // its canonical joints
  // Either a network (stylizer + strength in [0, 1]) or an already stylized clip (the optimisation
  // method's output) for the same content.
  std::shared_ptr<const style::Stylizer> stylizer;
  double strength = 1.0;
  style::PathMode path = style::PathMode::Content;  // whose root path the output follows
  std::optional<style::StylizedClip> stylized;
  // User contact overrides at the CONTENT's rate (frames x 4, -1 auto / 0 off / 1 on); empty: none.
  Eigen::MatrixXi contact_overrides;
  CleanupOptions options;
};

// What came out (computed results).
struct CleanupResult {
  style::StylizedClip stylized;  // raw network output: 21 canonical joints, file space, 60 fps
  Motion cleaned;                // on the content's skeleton, at the content's rate and frame count
  CleanupReport report;
  ClipMetrics raw_metrics;       // the raw output, judged by the content's contacts (60 fps)
  ClipMetrics cleaned_metrics;   // the cleaned clip, judged by the contacts the clean-up locked
  Eigen::MatrixXi contacts;      // frames x 4 at the stylized rate: the labels the clean-up locked
  double seconds = 0.0;          // wall clock of the whole job
};

// Stylizes (unless the job holds a stylized clip) and runs style::cleanUpStylizedClip
// (stylized_cleanup.h) with the user's contact overrides: the same chain as motionstyle-cli stylize.
// Throws InputError (an unmappable or too short clip), std::invalid_argument (a stylized clip that does
// not belong to the content) and style::OperationCancelled when `cancel` is seen between steps.
CleanupResult runCleanupJob(const CleanupJob& job, const std::atomic<bool>& cancel);

class CleanupWorker : public QObject {
  Q_OBJECT

 public:
  explicit CleanupWorker(std::shared_ptr<std::atomic<bool>> cancel) : cancel_(std::move(cancel)) {}

 public slots:
  void run(std::shared_ptr<const CleanupJob> job, quint64 job_id);

 signals:
  void progress(const QString& step, quint64 job_id);
  void finished(std::shared_ptr<const CleanupResult> result, quint64 job_id);
  void failed(const QString& message, quint64 job_id);
  void cancelled(quint64 job_id);

 private:
  std::shared_ptr<std::atomic<bool>> cancel_;
};

}  // namespace motionstyle

Q_DECLARE_METATYPE(std::shared_ptr<const motionstyle::CleanupJob>)
Q_DECLARE_METATYPE(std::shared_ptr<const motionstyle::CleanupResult>)
