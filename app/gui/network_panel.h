#pragma once
// NetworkPanel: the "Style networks" dock: four tabs, the run buttons and the job they start.
//
//   Networks tab (network_list.h): the networks of the session (load, save, rename, remove, details).
//   Train tab (train_tab.h): the training set, style clips per content label, the loss network, the
//     loss weights, epochs, learning rate and hidden units.
//   Optimise tab (optimise_tab.h): the optimisation method (Holden 2016) for the content and style
//     clips; the result goes out as stylizedClipReady() (the result panel cleans it up and shows it).
//   Adapt tab (adapt_tab.h): adapts the loss network and chosen styles to the user's own clips; the
//     results join the network list unsaved, the adapted loss network becomes the Train tab's.
//   Below the tabs: Train, Retrain (warm start from the selected network with the new weights), Cancel
//   and Resume, a progress bar with ETA, a status line and the loss curve (the live run's, else the
//   selected network's history).
//
// Jobs (style::StyleTrainingJob, style::OptimizationTransferJob) run on a JobRunner; one at a time. A
// cancelled training keeps its last epoch's network and can be resumed from its checkpoint (Resume).
// While training, each epoch's network stylizes the content clip (at most every few seconds)
// and previewReady() carries it as the blue "output" figure.
//
// Safety: prepareToClose() asks before stopping a running job (then cancels, quits and waits; the
// core keeps the last good checkpoint and never writes a network file half-way), then lets the
// network list ask about unsaved networks. Dialogs go through the Confirmer (tests replace it) and
// errors through errorOccurred() (MainWindow's ErrorReporter).

#include <QMessageBox>
#include <QWidget>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "clip_roles.h"
#include "display_space.h"
#include "network_list.h"
#include "remembered_folder.h"
#include "optimise_tab.h"
#include "train_tab.h"
#include "figure_data.h"
#include "nn/network_file.h"
#include "style/style_training_job.h"
#include "style/stylizer.h"
#include "style/training.h"

class QLabel;
class QProgressBar;
class QPushButton;
class QTabWidget;
class QTemporaryDir;

namespace motionstyle {

class AdaptTab;
class LossCurveWidget;
class JobRunner;

class NetworkPanel : public QWidget {
  Q_OBJECT

 public:
  // Shows a question and returns the button chosen (default: a QMessageBox).
  using Confirmer = NetworkList::Confirmer;

  // What the Train tab holds (editable data; validated when a run starts).
  using TrainingForm = TrainTab::Form;

  // `roles`: the window's clips and roles (clip_roles.h); the owner connects its clipsChanged() to
  // onClipsChanged(). persist_settings: folders and the loss network are kept in QSettings.
  explicit NetworkPanel(ClipRoles roles, QWidget* parent = nullptr, bool persist_settings = true);
  ~NetworkPanel() override;  // cancels and joins a running job without asking

  void setConfirmer(Confirmer confirmer);  // for this panel's questions and the network list's

  // The Networks tab: the session's networks (the selection, names, files; network_list.h).
  NetworkList* networkList() const { return network_list_; }

  // ---- Training -----------------------------------------------------------------------------------
  TrainingForm trainingForm() const;
  void setTrainingForm(const TrainingForm& form);
  QString lossNetworkFile() const;
  void setLossNetworkFile(const QString& file);
  QStringList trainingFolders() const;
  void addTrainingFolder(const QString& folder);
  // Style clips per content label: an empty label pairs by the clip's file name / as the default.
  void addStyleClip(const QString& file, const QString& label = QString());
  int styleClipCount() const;
  // With no style clip listed, the clip with the Style role is used.
  std::vector<style::StyleSource> styleSources() const;

  // Starts a run (retrain: warm start from the selected network, its shape and loss network). Returns
  // false and reports why when it cannot start (busy, no data, no style clip, no loss network).
  bool startTraining(bool retrain);
  // Continues the last cancelled run from its checkpoint (as the CLI's --resume): the same data,
  // settings and name, up to its epoch count. false (and why) when there is none.
  bool resumeTraining();
  bool canResumeTraining() const;
  // The optimisation method on the content and style clips (stage-1 iterations; the
  // constraint stage gets 100 / 250 of them).
  bool startTransfer(int iterations);
  bool isBusy() const;  // a training, optimisation or adaptation job is running
  // Requests cancellation of the running job (returns at once; jobFinished() follows).
  void cancelJob();
  // The checkpoint file of the latest training run (its network loads with nn::loadStyleModel).
  QString lastCheckpointFile() const;

  // For MainWindow::closeEvent: true when the window may close (see the top of this file).
  bool prepareToClose();

  LossCurveWidget* lossCurve() const { return loss_curve_; }
  AdaptTab* adaptTab() const { return adapt_tab_; }
  // Shows the Adapt tab with just this clip and this style checked (the Result panel's "Adapt..."
  // link; AdaptTab::focus).
  void showAdaptTab(const QString& clip_path, const QString& style = {});
  QProgressBar* progressBar() const { return progress_bar_; }
  QString statusText() const;

 public slots:
  // The clips or their roles changed: the training summary, the Adapt tab and a stale preview follow.
  void onClipsChanged();
  void browseTrainingFolder();

 signals:
  // The live preview / optimisation result as the blue output figure (display space like the clips).
  void previewReady(const motionstyle::FigureData& figure);
  void previewCleared();  // a new run started: the old preview is stale
  // The optimisation method's output for the content clip (for the result panel's clean-up).
  void stylizedClipReady(const motionstyle::style::StylizedClip& clip, const QString& label);
  void errorOccurred(const QString& title, const QString& message);
  void trainingProgress(const motionstyle::style::TrainingProgress& progress);
  void jobFinished();  // any job ended (its completion has run)
  // How a job ended, or a network loaded or saved, as the panel's status line says it (for the
  // window's status bar, which the user sees whichever tab is up).
  void statusMessage(const QString& message);
  // A training, optimisation or adaptation job started (true) or ended (false): isBusy() changed.
  void busyChanged(bool busy);

 private:
  AdaptTab* createAdaptTab();
  void showLossHistory();  // the selected network's, unless a run is drawing its own
  void updateButtons();
  void report(const QString& title, const QString& message);
  void showOutcome(const QString& text);  // on the panel's status line and statusMessage
  QMessageBox::StandardButton ask(const QString& title, const QString& text, QMessageBox::StandardButtons buttons);
  // Where clips and training folders were last chosen (apart from the networks folder: saving a
  // network never starts among the clips).
  RememberedFolder clipFolder() const { return {kClipFolderKey, persist_settings_}; }

  // Jobs (network_panel_jobs.cpp).
  bool runTraining(style::StyleTrainingJob job, const QString& status);
  void onTrainingProgress(const style::TrainingProgress& progress);
  void onTrainingFinished(const style::StyleTrainingJob::Result& outcome);
  void onPreview(const std::shared_ptr<const style::StylizedClip>& clip);
  void onJobDone(bool completed);  // JobRunner::finished: false when cancelled or failed
  void capturePreviewTarget();
  std::filesystem::path scratchFile(const QString& name);

  ClipRoles roles_;
  bool persist_settings_;
  AdaptTab* adapt_tab_ = nullptr;
  Confirmer confirmer_;

  enum class Running { None, Training, Transfer };
  JobRunner* runner_ = nullptr;
  Running running_ = Running::None;
  QString training_name_;
  // The last cancelled run (its config and name), resumable from its checkpoint.
  std::optional<style::StyleTrainingJob> resumable_;
  QString resumable_name_;
  std::unique_ptr<QTemporaryDir> scratch_;
  QString last_checkpoint_;

  // Maps the stylized clip (content file space, 60 fps) onto the content figure (its display space, the
  // timeline's rate): fixed when a job starts.
  struct PreviewTarget {
    bool valid = false;
    std::uint64_t content_id = 0;
    QString name;
    DisplaySpace display_space;
    double display_fps = 60.0;
  };
  PreviewTarget preview_target_;
  std::uint64_t preview_content_id_ = 0;  // LoadedClip::id the shown preview was made from
  bool preview_shown_ = false;
  bool busy_ = false;  // isBusy() as busyChanged() last said

  QTabWidget* tabs_ = nullptr;
  QWidget* run_row_ = nullptr;  // Train, Retrain, Cancel, Resume
  QWidget* bottom_ = nullptr;   // the run row, the progress, the status line and the loss curve
  NetworkList* network_list_ = nullptr;
  TrainTab* train_tab_ = nullptr;
  QPushButton* train_button_ = nullptr;
  QPushButton* retrain_button_ = nullptr;
  QPushButton* cancel_button_ = nullptr;
  QPushButton* resume_button_ = nullptr;
  OptimiseTab* optimise_tab_ = nullptr;
  QProgressBar* progress_bar_ = nullptr;
  QLabel* status_label_ = nullptr;
  LossCurveWidget* loss_curve_ = nullptr;
};

}  // namespace motionstyle
