#pragma once
// Workers for the "Style networks" panel: QObjects that live in their own QThread and run the core's
// long jobs without blocking the UI.
//
//   TrainingWorker: style::trainStyleNetwork (a new network, or a warm start = Retrain) with progress,
//                   per-epoch snapshots of the network and a live preview on one content clip.
//   TransferWorker: the optimisation method (Holden 2016, style/optimization_transfer.h) for one
//                   content clip and one style clip; no training.
//
// Threading contract (the house rule): construct on the GUI thread, moveToThread(), then invoke run()
// queued. Everything run() reports goes out by signals, so receivers on the GUI thread get them
// queued. requestCancel() may be called from any thread: it sets a std::atomic<bool> that the core
// polls (between micro-batches in training, every iteration in the optimisation), so the job ends well
// within a second. Exactly one of finished()/failed() is emitted per run, and done() always last: the
// owner connects done() to QThread::quit and shuts down with cancel, quit, wait.
//
// Errors never escape run(): InputError (bad clip, incompatible or corrupt network), WriteError (a
// checkpoint could not be written), TrainingDiverged (NaN), std::invalid_argument (bad settings) and
// anything else become failed(title, message). The core keeps the last good checkpoint in every case.

#include <QObject>
#include <QString>

#include <atomic>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "nn/network_file.h"
#include "style/optimization_transfer.h"
#include "style/stylizer.h"
#include "style/training.h"

namespace motionstyle {

struct TrainingJob {
  // Complete but for callbacks. settings.checkpoint must name a writable file (the GUI keeps its
  // checkpoints in a scratch folder); settings.output is usually empty (the user saves explicitly).
  style::StyleTrainingConfig config;
  // A content clip (BVH) to stylize with each snapshot for the live preview; empty = no preview.
  std::filesystem::path preview_content;
  // At most one preview per this many seconds (snapshots come once per epoch).
  double preview_interval_seconds = 3.0;
  // Step progress is sent at most once per this many seconds (epoch ends and loading always go out):
  // a tiny network makes thousands of steps a second and would flood the GUI's event queue.
  double progress_interval_seconds = 0.05;
};

struct TrainingOutcome {
  bool cancelled = false;
  int epochs_completed = 0;
  // Completed: the trained network. Cancelled: the network of the last completed epoch (the same as the
  // checkpoint file), or null when no epoch completed.
  std::shared_ptr<const nn::StyleModel> model;
  std::vector<style::EpochRecord> history;
  std::filesystem::path checkpoint;  // the checkpoint file of this run (may not exist if no epoch ended)
  double seconds = 0;
};

class TrainingWorker : public QObject {
  Q_OBJECT

 public:
  explicit TrainingWorker(TrainingJob job, QObject* parent = nullptr);

  void requestCancel() noexcept { cancel_.store(true); }
  bool cancelRequested() const noexcept { return cancel_.load(); }

 public slots:
  void run();

 signals:
  void progress(const motionstyle::style::TrainingProgress& progress);
  void logMessage(const QString& text);
  // After every epoch's checkpoint: a copy of the network so far.
  void snapshotReady(std::shared_ptr<const motionstyle::nn::StyleModel> model, int epoch);
  // The snapshot applied to TrainingJob::preview_content (strength 1).
  void previewReady(std::shared_ptr<const motionstyle::style::StylizedClip> clip, int epoch);
  void finished(const motionstyle::TrainingOutcome& outcome);
  void failed(const QString& title, const QString& message);
  void done();

 private:
  void makePreview(const nn::StyleModel& model, int epoch);

  TrainingJob job_;
  std::atomic<bool> cancel_{false};
  std::optional<style::MotionClip> preview_clip_;
  double last_preview_seconds_ = -1e9;
};

struct TransferJob {
  nn::AutoencoderModel autoencoder;  // the loss network
  std::filesystem::path content;     // BVH
  std::filesystem::path style;       // BVH
  style::OptimizationOptions options;
  double progress_interval_seconds = 0.05;
};

class TransferWorker : public QObject {
  Q_OBJECT

 public:
  explicit TransferWorker(TransferJob job, QObject* parent = nullptr);

  void requestCancel() noexcept { cancel_.store(true); }

 public slots:
  void run();

 signals:
  void progress(const motionstyle::style::OptimizationProgress& progress);
  // result is null when cancelled.
  void finished(std::shared_ptr<const motionstyle::style::StylizedClip> result, bool cancelled, double seconds);
  void failed(const QString& title, const QString& message);
  void done();

 private:
  TransferJob job_;
  std::atomic<bool> cancel_{false};
};

// Registers the signal argument types for queued connections (idempotent). Qt 6 needs no
// Q_DECLARE_METATYPE for them: the moc-generated code names the types itself.
void registerWorkerMetaTypes();

}  // namespace motionstyle
