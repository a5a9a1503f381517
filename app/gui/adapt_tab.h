#pragma once
// AdaptTab: the Style networks panel's "Adapt" tab: one action that adapts the networks to the user's
// own clips (style/adaptation.h: AdaptNetworksJob): the loss network learns to reconstruct them, then
// the chosen style networks are retrained on them, warm-started, with the style targets they store.
//
//   - Your clips: the mapped clips loaded in the app (checked by default) and any folders added.
//   - Styles to retrain: the shipped styles and the panel's networks that store style targets.
//   - Adapt runs on a JobRunner (job_runner.h): progress with ETA per stage, Cancel within a second.
//   - Before/after: each clip's familiarity (style/familiarity.h) with the original and the adapted
//     loss network.
// When it completes, adapted() hands over the adapted loss network and the retrained style networks
// (the panel lists them as unsaved networks: nothing is lost without a prompt).

#include <QWidget>

class QTemporaryDir;

#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

#include "clip_loader.h"
#include "nn/network_file.h"
#include "style/adaptation.h"

class QLabel;
class QListWidget;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTableWidget;

namespace motionstyle {

class JobRunner;

class AdaptTab : public QWidget {
  Q_OBJECT

 public:
  // A network the user may retrain: its name and model (only those storing style targets are listed).
  struct NamedNetwork {
    QString name;
    std::shared_ptr<const nn::StyleModel> model;
    std::shared_ptr<const style::ReconstructionMemory> memory;  // an adapted network's own; may be null
  };
  using ClipsProvider = std::function<std::vector<const LoadedClip*>()>;   // the app's loaded clips
  using NetworksProvider = std::function<std::vector<NamedNetwork>()>;     // besides the shipped ones

  AdaptTab(ClipsProvider clips, NetworksProvider networks, QWidget* parent = nullptr);
  ~AdaptTab() override;

  // Rebuilds the two lists (keeps the user's checks by name).
  void refresh();
  // Checks just this clip (by path) among the listed ones and, when `style` names a listed network
  // (case aside), just that style: the Result panel's "Adapt..." link adapts what is on screen.
  void focus(const QString& clip_path, const QString& style);
  // The style chosen in the Result panel: checked alone, as long as the user has not chosen styles here.
  void followStyle(const QString& style);
  void setStyleChecked(const QString& name, bool checked);
  void setEpochs(int loss_epochs, int style_epochs);
  bool start();  // false and a report when it cannot start
  void cancel();
  bool isBusy() const;
  QTableWidget* familiarityTable() const { return table_; }
  QString statusText() const;

 signals:
  // `memory`: what the adapted networks must go on reconstructing when adapted again (may be null).
  void adapted(std::shared_ptr<const nn::LossNetworkModel> loss_network,
               std::vector<motionstyle::style::StyleToRetrain> styles,
               std::shared_ptr<const motionstyle::style::ReconstructionMemory> memory);
  void errorOccurred(const QString& title, const QString& message);
  void busyChanged(bool busy);
  // How a run ended, as the tab's status line says it (for the window's status bar).
  void statusMessage(const QString& message);

 private:
  void showResult(const style::AdaptNetworksJob::Result& result);
  void onProgress(const style::TrainingProgress& progress);

  ClipsProvider clips_;
  NetworksProvider networks_;
  JobRunner* runner_ = nullptr;
  std::unique_ptr<QTemporaryDir> scratch_;  // the adaptation's checkpoints, removed with the tab
  QListWidget* clip_list_ = nullptr;
  QListWidget* style_list_ = nullptr;
  bool styles_chosen_here_ = false;  // the user toggled a style: followStyle leaves the checks alone
  QSpinBox* loss_epochs_ = nullptr;
  QSpinBox* style_epochs_ = nullptr;
  QPushButton* adapt_button_ = nullptr;
  QPushButton* cancel_button_ = nullptr;
  QProgressBar* progress_ = nullptr;
  QLabel* status_ = nullptr;
  QTableWidget* table_ = nullptr;
};

}  // namespace motionstyle
