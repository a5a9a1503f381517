#pragma once
// NetworkPanel: the "Style networks" dock.
//
//   Networks tab: load/save network files (saved atomically by the core; an existing file is never
//     replaced without a confirmation), the list of networks with their metadata (style clips, loss
//     weights, epochs, date) and the selected one's loss history in the curve below.
//   Train tab: the training set (clips with the "training set" role plus folders),
//     style clips per content label (style_pairing.h), the loss network, the loss weights (defaults
//     from nn::LossWeights), epochs, learning rate and hidden units; Train, Retrain (warm start from
//     the selected network with the new weights) and Cancel.
//   Adapt tab (adapt_tab.h): adapts the loss network and chosen styles to the user's own clips; the
//     results join the networks list unsaved, the adapted loss network becomes the Train tab's.
//   Optimise tab: the optimisation method (Holden 2016) for the content and style clips; the
//     result goes out as stylizedClipReady() (the result panel cleans it up and shows it).
//   Below the tabs: a progress bar with ETA, a status line and the live loss curve.
//
// Jobs (style::StyleTrainingJob, style::OptimizationTransferJob) run on a JobRunner; one at a time. A
// cancelled training keeps its last epoch's network and can be resumed from its checkpoint (Resume).
// While training, each epoch's network stylizes the content clip (at most every few seconds)
// and previewReady() carries it as the blue "output" figure. The selected network is currentNetwork();
// currentNetworkChanged() announces it to the other panels (the result panel).
//
// Safety: prepareToClose() asks before stopping a running job (then cancels, quits and waits; the
// core keeps the last good checkpoint and never writes a network file half-way), and asks before any
// trained network that was never saved is dropped: removing one asks for it; closing asks once for
// all of them (Save All into one folder, never over a file; Discard; Cancel).
// Dialogs go through the Confirmer (tests replace it) and errors through errorOccurred() (MainWindow's
// ErrorReporter).

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
#include "optimise_tab.h"
#include "train_tab.h"
#include "figure_data.h"
#include "nn/network_file.h"
#include "style/style_training_job.h"
#include "style/stylizer.h"
#include "style/training.h"

class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTabWidget;
class QTemporaryDir;
class QTreeWidget;

namespace motionstyle {

class AdaptTab;
class LossCurveWidget;
class JobRunner;

class NetworkPanel : public QWidget {
  Q_OBJECT

 public:
  // Shows a question and returns the button chosen (default: a QMessageBox).
  using Confirmer = std::function<QMessageBox::StandardButton(const QString& title, const QString& text,
                                                              QMessageBox::StandardButtons buttons)>;

  // What the Train tab holds (editable data; validated when a run starts).
  using TrainingForm = TrainTab::Form;

  // `roles`: the window's clips and roles (clip_roles.h); the owner connects its clipsChanged() to
  // onClipsChanged(). persist_settings: folders and the loss network are kept in QSettings.
  explicit NetworkPanel(ClipRoles roles, QWidget* parent = nullptr, bool persist_settings = true);
  ~NetworkPanel() override;  // cancels and joins a running job without asking

  void setConfirmer(Confirmer confirmer);
  // Picks the folder "Save all" writes into, starting at `start` (default: a folder dialog).
  using FolderChooser = std::function<QString(const QString& start)>;
  void setFolderChooser(FolderChooser chooser) { folder_chooser_ = std::move(chooser); }

  // ---- Networks -----------------------------------------------------------------------------------
  int networkCount() const { return static_cast<int>(networks_.size()); }
  int currentIndex() const;
  void setCurrentIndex(int index);
  std::shared_ptr<const nn::StyleModel> currentNetwork() const;
  QString currentNetworkName() const;  // the list's name (file name without .net), empty when none
  std::shared_ptr<const nn::StyleModel> network(int index) const;
  QString networkFile(int index) const;   // empty while never saved
  bool isNetworkSaved(int index) const;
  // Loads a style network (or, for an autoencoder file, takes it as the loss network). Errors are
  // reported; returns false then.
  bool loadNetworkFile(const QString& file);
  // Saves atomically; an existing file is replaced only after the Confirmer answers Yes (or when
  // `overwrite_confirmed`, e.g. after a file dialog asked). false (and a report) on failure.
  bool saveNetwork(int index, const QString& file, bool overwrite_confirmed = false);
  // Asks before dropping an unsaved network; false when the user keeps it.
  bool removeNetwork(int index);
  // A new name for the network (the list's name cell is editable: F2 or a double click). Refused, with
  // a report, when empty or taken by another network; networkRenamed() tells the other panels.
  bool renameNetwork(int index, const QString& name);

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
  void browseLoad();
  void browseSave();
  void browseTrainingFolder();

 signals:
  void currentNetworkChanged(std::shared_ptr<const motionstyle::nn::StyleModel> network);
  // The live preview / optimisation result as the blue output figure (display space like the clips).
  void previewReady(const motionstyle::FigureData& figure);
  void previewCleared();  // a new run started: the old preview is stale
  // The optimisation method's output for the content clip (for the result panel's clean-up).
  void stylizedClipReady(const motionstyle::style::StylizedClip& clip, const QString& label);
  void errorOccurred(const QString& title, const QString& message);
  void trainingProgress(const motionstyle::style::TrainingProgress& progress);
  void jobFinished();  // any job ended (its completion has run)
  void networkRenamed(const QString& old_name, const QString& new_name);

 private:
  struct NetworkEntry {
    std::shared_ptr<const nn::StyleModel> model;
    QString name;
    QString file;
    bool saved = false;
  };

  QWidget* createNetworksTab();
  AdaptTab* createAdaptTab();
  void addNetwork(NetworkEntry entry);
  void refreshNetworkList();
  void showNetworkDetails();
  void updateButtons();
  void report(const QString& title, const QString& message);
  QMessageBox::StandardButton ask(const QString& title, const QString& text, QMessageBox::StandardButtons buttons);
  bool confirmDropUnsaved(int index, bool allow_cancel);
  // Where network files were last loaded or saved (the user's networks folder), and, apart from it,
  // where clips and training folders were last chosen: saving a network never starts among the clips.
  QString lastFolder() const;
  void rememberFolder(const QString& path);
  QString lastClipFolder() const;
  void rememberClipFolder(const QString& path);

  // Jobs (network_panel_jobs.cpp).
  bool runTraining(style::StyleTrainingJob job, const QString& status);
  void onTrainingProgress(const style::TrainingProgress& progress);
  void onTrainingFinished(const style::StyleTrainingJob::Result& outcome);
  void onPreview(const std::shared_ptr<const style::StylizedClip>& clip);
  void onJobDone();
  void capturePreviewTarget();
  std::filesystem::path scratchFile(const QString& name);

  ClipRoles roles_;
  bool persist_settings_;
  AdaptTab* adapt_tab_ = nullptr;
  Confirmer confirmer_;
  FolderChooser folder_chooser_;
  std::vector<NetworkEntry> networks_;

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

  QTabWidget* tabs_ = nullptr;
  QTreeWidget* network_list_ = nullptr;
  QLabel* details_label_ = nullptr;
  QPushButton* save_button_ = nullptr;
  QPushButton* remove_button_ = nullptr;
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
