// MainWindow's side of the "Style networks" dock (network_panel.h): the dock and its wiring to the
// viewport, the result panel and the error reporter, and the "training set" clip role.
#include <QDockWidget>

#include <algorithm>

#include "adapt_tab.h"
#include "main_window.h"
#include "network_panel.h"
#include "result_panel.h"
#include "timeline_widget.h"

namespace motionstyle {

void MainWindow::createNetworkDock() {
  ClipRoles roles;
  roles.clips = [this] {
    std::vector<const LoadedClip*> all;
    for (int i = 0; i < clipCount(); ++i) all.push_back(&clip(i));
    return all;
  };
  roles.content = [this]() -> const LoadedClip* { return content_ >= 0 ? &clip(content_) : nullptr; };
  roles.style = [this]() -> const LoadedClip* { return style_ >= 0 ? &clip(style_) : nullptr; };
  roles.training_paths = [this] { return trainingClipPaths(); };
  roles.display_fps = [this] { return timeline_->frameRate(); };
  network_panel_ = new NetworkPanel(std::move(roles), this, persist_settings_);
  connect(this, &MainWindow::clipsChanged, network_panel_, &NetworkPanel::onClipsChanged);
  auto* dock = new QDockWidget(tr("Style networks"), this);
  dock->setObjectName(QStringLiteral("NetworksDock"));
  dock->setWidget(network_panel_);
  dock->setMinimumWidth(360);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  if (auto* result_dock = findChild<QDockWidget*>(QStringLiteral("ResultDock"))) {
    tabifyDockWidget(result_dock, dock);
    result_dock->raise();  // the one-click path (load a network, stylize) comes first
  }

  connect(network_panel_, &NetworkPanel::errorOccurred, this, &MainWindow::report);
  connect(network_panel_, &NetworkPanel::statusMessage, this, &MainWindow::showStatus);
  connect(network_panel_, &NetworkPanel::previewReady, this, [this](const FigureData& figure) {
    training_preview_ = figure;
    rebuildFigures();
  });
  connect(network_panel_, &NetworkPanel::previewCleared, this, [this] {
    if (!training_preview_) return;
    training_preview_.reset();
    rebuildFigures();
  });
  // The result panel stylizes with the selected network and cleans up the optimisation method's output.
  connect(network_panel_->networkList(), &NetworkList::currentNetworkChanged, this,
          [this](std::shared_ptr<const nn::StyleModel> model) {
            result_panel_->setStyleNetwork(std::move(model), network_panel_->networkList()->currentNetworkName());
          });
  connect(network_panel_, &NetworkPanel::stylizedClipReady, result_panel_, &ResultPanel::setStylizedClip);
  // A training, optimisation or adaptation has the cores: nothing is computed ahead meanwhile.
  connect(network_panel_, &NetworkPanel::busyChanged, result_panel_, &ResultPanel::holdLookAhead);
  connect(network_panel_->networkList(), &NetworkList::networkRenamed, result_panel_, &ResultPanel::renameNetwork);
  connect(network_panel_->networkList(), &NetworkList::networkRemoved, result_panel_, &ResultPanel::forgetNetwork);
  // The Adapt tab checks the style chosen for the result until the user chooses styles there.
  connect(result_panel_, &ResultPanel::networkChosen, network_panel_->adaptTab(), &AdaptTab::followStyle);
  // The familiarity row's "Adapt..." link: the Adapt tab with the content clip and the chosen style
  // checked.
  connect(result_panel_, &ResultPanel::adaptRequested, this, [this] {
    network_panel_->showAdaptTab(content_ >= 0 ? clip(content_).path : QString(), result_panel_->networkName());
  });
  // A real result replaces the training preview (both are blue "output" figures).
  connect(result_panel_, &ResultPanel::resultChanged, this, [this] {
    if (!training_preview_ || result_panel_->resultFigures(false).empty()) return;
    training_preview_.reset();
    rebuildFigures();
  });
}

bool MainWindow::isTrainingClip(int index) const {
  return std::binary_search(training_clips_.begin(), training_clips_.end(), index);
}

QStringList MainWindow::trainingClipPaths() const {
  QStringList paths;
  for (int index : training_clips_) paths << clip(index).path;
  return paths;
}

void MainWindow::setTrainingClip(int index, bool on) {
  if (index < 0 || index >= clipCount() || isTrainingClip(index) == on) return;
  if (on) training_clips_.insert(std::upper_bound(training_clips_.begin(), training_clips_.end(), index), index);
  else training_clips_.erase(std::find(training_clips_.begin(), training_clips_.end(), index));
  refreshClipList();
}

void MainWindow::forgetTrainingClip(int removed_index) {
  std::vector<int> kept;
  for (int index : training_clips_)
    if (index != removed_index) kept.push_back(index > removed_index ? index - 1 : index);
  training_clips_ = std::move(kept);
}

}  // namespace motionstyle
