#include "main_window.h"

#include "demo_scene.h"

#include <QActionGroup>
#include <QApplication>
#include <QCloseEvent>
#include <QDockWidget>
#include <QHeaderView>
#include <QLabel>
#include <QMenu>
#include <QMenuBar>
#include <QMessageBox>
#include <QSettings>
#include <QScreen>
#include <QStatusBar>
#include <QTreeWidget>

#include <algorithm>
#include <exception>
#include <new>

#include "app_log.h"
#include "common/errors.h"
#include "clip_file_watcher.h"
#include "contact_tracks.h"
#include "error_text.h"
#include "focused_keys.h"
#include "item_view_layout.h"
#include "live_resolution.h"
#include "network_panel.h"
#include "result_panel.h"
#include "skeleton_viewport.h"
#include "timeline_widget.h"
#include "track_view.h"
#include "wheel_guard.h"

namespace motionstyle {
namespace {

const char* const kGeometryKey = "mainWindow/geometry";
const char* const kStateKey = "mainWindow/state";

enum ClipColumn { kNameColumn, kRoleColumn, kFramesColumn, kFpsColumn, kJointsColumn, kMappingColumn, kColumnCount };

}  // namespace

MainWindow::MainWindow(bool persist_settings, QWidget* parent)
    : QMainWindow(parent), persist_settings_(persist_settings) {
  setWindowTitle(QStringLiteral("MotionStyle"));
  setObjectName(QStringLiteral("MainWindow"));
  setAcceptDrops(true);
  if (auto* application = qobject_cast<QApplication*>(QCoreApplication::instance())) {
    installWheelGuard(*application);
    installFocusedKeys(*application);
  }
  reporter_ = [this](const QString& title, const QString& message) { QMessageBox::warning(this, title, message); };
  confirmer_ = [this](const QString& title, const QString& question) {
    return QMessageBox::question(this, title, question, QMessageBox::Yes | QMessageBox::Cancel) == QMessageBox::Yes;
  };
  choice_asker_ = [this](const QString& title, const QString& question, QMessageBox::StandardButtons buttons) {
    return QMessageBox::question(this, title, question, buttons);
  };

  file_watcher_ = new ClipFileWatcher(this);
  connect(file_watcher_, &ClipFileWatcher::changedOnDisk, this, &MainWindow::noticeClipFileChanged);
  viewport_ = new SkeletonViewport(this);
  live_resolution_ = new LiveResolution(viewport_, this);
  viewport_->setEmptyMessage(emptyViewMessage());
  setCentralWidget(viewport_);
  createDocks();
  // The look-ahead waits for the rest meant for a drag's steps only while the hand is on a control.
  result_panel_->setHandOnControl([this] { return live_resolution_->handOnControl(); });
  connect(live_resolution_, &LiveResolution::handReleased, result_panel_, &ResultPanel::handReleased);
  createMenus();

  status_label_ = new QLabel(tr("Open a BVH clip (Ctrl+O) or drop files here"), this);
  status_label_->setObjectName(QStringLiteral("StatusLine"));
  statusBar()->addWidget(status_label_, 1);

  connect(timeline_, &TimelineWidget::frameChanged, viewport_, &SkeletonViewport::setFrame);

  // 1440 x 900, or less on a smaller screen (a 1366 x 768 laptop): never larger than its free area.
  resize(QSize(1440, 900).boundedTo(screen()->availableGeometry().size()));
  if (persist_settings_) {
    const QSettings settings;
    restoreGeometry(settings.value(kGeometryKey).toByteArray());
    restoreState(settings.value(kStateKey).toByteArray());
  }
  rebuildRecentMenu();
}

MainWindow::~MainWindow() = default;

void MainWindow::setErrorReporter(ErrorReporter reporter) { reporter_ = std::move(reporter); }

void MainWindow::createDocks() {
  timeline_ = new TimelineWidget(this);
  TrackView* tracks = timeline_->trackView();
  tracks->addBoolTrack(tr("Left foot"), QColor(240, 170, 60));
  tracks->addBoolTrack(tr("Right foot"), QColor(90, 200, 220));
  auto* timeline_dock = new QDockWidget(tr("Timeline"), this);
  timeline_dock->setObjectName(QStringLiteral("TimelineDock"));
  timeline_dock->setWidget(timeline_);
  timeline_dock->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable |
                             QDockWidget::DockWidgetClosable);
  addDockWidget(Qt::BottomDockWidgetArea, timeline_dock);

  clip_list_ = new QTreeWidget(this);
  clip_list_->setObjectName(QStringLiteral("ClipList"));
  clip_list_->setColumnCount(kColumnCount);
  clip_list_->setHeaderLabels({tr("Clip"), tr("Role"), tr("Frames"), tr("FPS"), tr("Joints"), tr("Mapping")});
  clip_list_->setRootIsDecorated(false);
  clip_list_->setAlternatingRowColors(true);
  clip_list_->setSelectionMode(QAbstractItemView::SingleSelection);
  clip_list_->setContextMenuPolicy(Qt::CustomContextMenu);
  // Every column as wide as its longest entry, names and mappings never cut: a narrow dock scrolls
  // sideways instead.
  clip_list_->header()->setStretchLastSection(false);
  for (int column = kNameColumn; column < kColumnCount; ++column)
    clip_list_->header()->setSectionResizeMode(column, QHeaderView::ResizeToContents);
  clip_list_->setHorizontalScrollBarPolicy(Qt::ScrollBarAsNeeded);
  connect(clip_list_, &QTreeWidget::customContextMenuRequested, this, &MainWindow::showClipMenu);
  auto* clips_dock = new QDockWidget(tr("Clips"), this);
  clips_dock->setObjectName(QStringLiteral("ClipsDock"));
  clips_dock->setWidget(clip_list_);
  clips_dock->setMinimumWidth(300);
  addDockWidget(Qt::LeftDockWidgetArea, clips_dock);
  resizeDocks({clips_dock}, {380}, Qt::Horizontal);
  // The timeline spans the full width under both the clips list and the viewport.
  setCorner(Qt::BottomLeftCorner, Qt::BottomDockWidgetArea);
  setCorner(Qt::BottomRightCorner, Qt::BottomDockWidgetArea);
  createResultDock();
  createNetworkDock();
}

void MainWindow::createResultDock() {
  result_panel_ = new ResultPanel(this);
  result_panel_->setErrorReporter([this](const QString& title, const QString& message) { report(title, message); });
  auto* dock = new QDockWidget(tr("Result"), this);
  dock->setObjectName(QStringLiteral("ResultDock"));
  dock->setWidget(result_panel_);
  addDockWidget(Qt::RightDockWidgetArea, dock);
  connect(result_panel_, &ResultPanel::resultChanged, this, &MainWindow::rebuildFigures);
  connect(result_panel_, &ResultPanel::resultRenamed, this, &MainWindow::renameResultFigures);
  connect(result_panel_, &ResultPanel::sourceChanged, this, &MainWindow::rebuildFigures);
  connect(result_panel_, &ResultPanel::statusMessage, this, &MainWindow::showStatus);
  connect(result_panel_, &ResultPanel::frameRequested, timeline_, &TimelineWidget::setFrame);
  const auto content = [this]() -> LoadedClip* { return content_ >= 0 ? &clips_[static_cast<size_t>(content_)] : nullptr; };
  contact_tracks_ = new ContactTrackController(timeline_->trackView(), content,
                                               [this](const QString& title, const QString& message) { report(title, message); }, this);
  connect(contact_tracks_, &ContactTrackController::overridesChanged, result_panel_, &ResultPanel::setContactOverrides);
  // A held-down warning's fix: the foot's contact ended there (the clip is cleaned again), shown there.
  connect(result_panel_, &ResultPanel::contactEndRequested, this, [this](int contact, int first, int last) {
    contact_tracks_->endFootContact(contact, first, last);
    timeline_->setFrame(first);
  });
  connect(result_panel_, &ResultPanel::familiarityChanged, this,
          [this] { contact_tracks_->setQualityTracks(result_panel_->qualityTracks()); });
}

void MainWindow::createMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(tr("&Open BVH..."), QKeySequence::Open, this, &MainWindow::browseFiles);
  file->addAction(tr("Open &Folder..."), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_O), this,
                  &MainWindow::browseFolder);
  recent_menu_ = file->addMenu(tr("&Recent Files"));
  file->addAction(tr("Open &Demo"), this, &MainWindow::openDemoScene);
  file->addSeparator();
  file->addAction(tr("Open &Network..."), result_panel_, &ResultPanel::browseNetwork);
  file->addAction(tr("&Export Result..."), QKeySequence(Qt::CTRL | Qt::Key_E), result_panel_, &ResultPanel::browseExport);
  contact_tracks_->addActions(file->addMenu(tr("&Contacts")));
  file->addSeparator();
  file->addAction(tr("Save &Screenshot..."), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S), this,
                  &MainWindow::browseScreenshot);
  file->addSeparator();
  QAction* quit = file->addAction(tr("&Quit"), QKeySequence::Quit, this, &QWidget::close);
  quit->setMenuRole(QAction::QuitRole);

  QMenu* view = menuBar()->addMenu(tr("&View"));
  auto* layouts = new QActionGroup(this);
  side_by_side_action_ = view->addAction(tr("&Side by Side"), QKeySequence(Qt::Key_1), this,
                                         [this] { viewport_->setLayout(SkeletonViewport::Layout::SideBySide); });
  overlay_action_ = view->addAction(tr("&Overlay"), QKeySequence(Qt::Key_2), this,
                                    [this] { viewport_->setLayout(SkeletonViewport::Layout::Overlay); });
  for (QAction* action : {side_by_side_action_, overlay_action_}) {
    action->setCheckable(true);
    layouts->addAction(action);
  }
  side_by_side_action_->setChecked(true);
  view->addSeparator();
  follow_action_ = view->addAction(tr("&Follow Camera"), QKeySequence(Qt::Key_C), this, [this](bool follow) {
    viewport_->setCameraMode(follow ? SkeletonViewport::CameraMode::Follow : SkeletonViewport::CameraMode::Fixed);
  });
  follow_action_->setCheckable(true);
  follow_action_->setChecked(viewport_->cameraMode() == SkeletonViewport::CameraMode::Follow);
  view->addAction(tr("&Reset Camera"), QKeySequence(Qt::Key_F), viewport_, &SkeletonViewport::resetCamera);
  QAction* paths = view->addAction(tr("Show &Trajectories"), QKeySequence(Qt::Key_T), viewport_,
                                   &SkeletonViewport::setTrajectoriesVisible);
  paths->setCheckable(true);
  paths->setChecked(viewport_->trajectoriesVisible());
  raw_output_action_ = view->addAction(tr("Show &Raw Output"), QKeySequence(Qt::Key_R), this, &MainWindow::setRawOutputVisible);
  raw_output_action_->setCheckable(true);
  raw_output_action_->setStatusTip(tr("The network's output before clean-up, in grey beside the cleaned output"));
  view->addSeparator();
  for (QDockWidget* dock : findChildren<QDockWidget*>()) view->addAction(dock->toggleViewAction());

  // Keep the menu's checks true when the viewport changes by itself (its own C key, for instance).
  connect(viewport_, &SkeletonViewport::cameraModeChanged, this, [this](SkeletonViewport::CameraMode mode) {
    follow_action_->setChecked(mode == SkeletonViewport::CameraMode::Follow);
  });
  connect(viewport_, &SkeletonViewport::layoutChanged, this, [this](SkeletonViewport::Layout layout) {
    (layout == SkeletonViewport::Layout::SideBySide ? side_by_side_action_ : overlay_action_)->setChecked(true);
  });

  QMenu* help = menuBar()->addMenu(tr("&Help"));
  help->addAction(tr("Open &Demo"), this, &MainWindow::openDemoScene);
  help->addAction(tr("&Keyboard Shortcuts"), QKeySequence::HelpContents, this, &MainWindow::showShortcuts);
  help->addSeparator();
  help->addAction(tr("&About MotionStyle"), this, &MainWindow::showAbout);
}

void MainWindow::setContentClip(int index) {
  if (index < 0 || index >= clipCount()) return;
  if (style_ == index) style_ = content_;
  content_ = index;
  refreshClipList();
  rebuildFigures();
}

void MainWindow::setStyleClip(int index) {
  if (index < 0 || index >= clipCount()) return;
  if (content_ == index) content_ = style_;
  style_ = index;
  refreshClipList();
  rebuildFigures();
}

void MainWindow::removeClip(int index) {
  if (index < 0 || index >= clipCount() || !keepContactEdits({index})) return;
  const QString path = clip(index).path;
  clips_.erase(clips_.begin() + index);
  if (std::none_of(clips_.begin(), clips_.end(), [&](const LoadedClip& c) { return c.path == path; })) {
    file_watcher_->forget(path);
    changed_on_disk_.remove(path);
  }
  const auto shift = [index](int& role) { role = role == index ? -1 : (role > index ? role - 1 : role); };
  shift(content_);
  shift(style_);
  forgetTrainingClip(index);
  if (content_ < 0 && style_ >= 0) std::swap(content_, style_);
  refreshClipList();
  rebuildFigures();
}

void MainWindow::rebuildFigures() {
  // Every figure plays at the content's rate (resampled by time), so clips of any rate stay in sync;
  // the result is at the content's rate already.
  const double fps = content_ >= 0 ? clip(content_).fps() : 30.0;
  result_panel_->setContentClip(content_ >= 0 ? &clip(content_) : nullptr);
  std::vector<FigureData> figures;
  const auto add = [&](int index, FigureRole role) {
    if (index >= 0 && clip(index).frameCount() > 0) figures.push_back(figureFromClip(clip(index), role, fps));
  };
  add(content_, FigureRole::Content);
  // The Style clip is drawn while it is what a result would come from (training, the optimisation
  // method); with a style network chosen in the Result panel it plays no part, so it is not shown.
  if (!result_panel_->resultComesFromNetwork()) add(style_, FigureRole::Style);
  // The live training preview stands in for the result while it is fresh (the viewport holds at most
  // four figures); a new result drops the preview (main_window_networks.cpp).
  if (training_preview_) {
    figures.push_back(*training_preview_);
  } else {
    for (FigureData& figure : result_panel_->resultFigures(raw_output_action_->isChecked()))
      figures.push_back(std::move(figure));
  }
  viewport_->setEmptyMessage(emptyViewMessage());
  try {
    viewport_->setFigures(std::move(figures));
  } catch (...) {
    report(tr("Could not show the clips"), errorText(std::current_exception()));
    viewport_->clearFigures();
  }
  // The content clip sets the time base and the loop (the result is as long as the content); the
  // other figures hold their last frame when shorter and are cut when longer.
  timeline_->setFrameRate(fps);
  timeline_->setFrameCount(content_ >= 0 && clip(content_).frameCount() > 0 ? clip(content_).frameCount()
                                                                           : viewport_->frameCount());
  viewport_->setFrame(timeline_->frame());
  contact_tracks_->refresh();
  contact_tracks_->setQualityTracks(result_panel_->qualityTracks());
  // Painted now, not at the event loop's next pass: a result counts as shown when it is on screen
  // (the live latency in the log is measured to here); at reduced resolution while a drag goes on.
  live_resolution_->resultShown();
  viewport_->repaint();
}

void MainWindow::renameResultFigures() {
  // The result's figures are the last ones (rebuildFigures), unless the training preview stands in.
  const QStringList names = result_panel_->resultFigureNames(raw_output_action_->isChecked());
  const int first = viewport_->figureCount() - static_cast<int>(names.size());
  if (training_preview_ || names.isEmpty() || first < 0) {
    rebuildFigures();
    return;
  }
  for (int i = 0; i < names.size(); ++i) viewport_->renameFigure(first + i, names[i]);
}

void MainWindow::setRawOutputVisible(bool visible) {
  if (raw_output_action_->isChecked() != visible) raw_output_action_->setChecked(visible);
  rebuildFigures();
}

bool MainWindow::loadMappingFile(int index, const QString& file) {
  if (index < 0 || index >= clipCount() || !keepContactEdits({index})) return false;  // contacts are found again
  try {
    remapClip(clips_[static_cast<size_t>(index)], file.toStdString());
  } catch (...) {
    report(tr("Could not use the mapping file"), errorText(std::current_exception(), file));
    return false;
  }
  refreshClipList();
  rebuildFigures();
  return true;
}

void MainWindow::refreshClipList() {
  clip_list_->clear();
  for (int i = 0; i < clipCount(); ++i) {
    const LoadedClip& c = clip(i);
    auto* item = new QTreeWidgetItem(clip_list_);
    item->setText(kNameColumn, c.name);
    item->setToolTip(kNameColumn, c.path);
    if (changed_on_disk_.contains(c.path)) {
      item->setText(kNameColumn, tr("%1 (changed on disk)").arg(c.name));
      item->setForeground(kNameColumn, QColor(230, 120, 60));
      item->setToolTip(kNameColumn, tr("%1 changed on disk after it was opened: what is shown is the file as it was. "
                                       "Right-click and choose Reload from Disk.").arg(c.path));
    }
    const bool is_content = i == content_;
    const bool is_style = i == style_;
    if (is_content || is_style) {
      const FigureRole role = is_content ? FigureRole::Content : FigureRole::Style;
      item->setText(kRoleColumn, figureRoleName(role));
      item->setForeground(kRoleColumn, figureColor(role));
    }
    if (isTrainingClip(i))
      item->setText(kRoleColumn, item->text(kRoleColumn).isEmpty() ? tr("Training") : item->text(kRoleColumn) + tr(" + training"));
    item->setText(kFramesColumn, QString::number(c.frameCount()));
    item->setText(kFpsColumn, QString::number(c.fps(), 'g', 4));
    item->setText(kJointsColumn, QString::number(c.animatedJointCount()));
    item->setText(kMappingColumn, c.mappingStatus());
    item->setToolTip(kMappingColumn, c.isMapped() ? c.mappingStatus()
                                                  : tr("This rig cannot be stylized until it is mapped: "
                                                       "right-click, Save Mapping Template, complete it and Load Mapping File."));
    if (!c.isMapped()) item->setForeground(kMappingColumn, QColor(230, 120, 60));
    for (int column = kFramesColumn; column < kMappingColumn; ++column)
      item->setTextAlignment(column, Qt::AlignRight | Qt::AlignVCenter);
  }
  layOutItemsNow(*clip_list_);
  emit clipsChanged();
}

void MainWindow::showClipMenu(const QPoint& position) {
  QTreeWidgetItem* item = clip_list_->itemAt(position);
  if (item == nullptr) return;
  const int index = clip_list_->indexOfTopLevelItem(item);
  QMenu menu(this);
  menu.addAction(tr("Use as &Content"), this, [this, index] { setContentClip(index); });
  menu.addAction(tr("Use as &Style"), this, [this, index] { setStyleClip(index); });
  QAction* training = menu.addAction(tr("In the &Training Set"), this, [this, index](bool on) { setTrainingClip(index, on); });
  training->setCheckable(true);
  training->setChecked(isTrainingClip(index));
  menu.addAction(tr("Add &Folder to the Training Set..."), network_panel_, &NetworkPanel::browseTrainingFolder);
  menu.addAction(tr("Load &Mapping File..."), this, [this, index] { browseMappingFile(index); });
  menu.addAction(tr("Save Mapping &Template..."), this, [this, index] { browseMappingTemplate(index); })
      ->setStatusTip(tr("Write how this rig maps to the 21 joints the networks use, to complete or correct by hand"));
  menu.addSeparator();
  menu.addAction(tr("Re&load from Disk"), this, [this, index] { reloadClip(index); });
  menu.addAction(tr("&Remove"), this, [this, index] { removeClip(index); });
  menu.exec(clip_list_->viewport()->mapToGlobal(position));
}

bool MainWindow::saveScreenshot(const QString& file) {
  const QImage image = grab().toImage();
  if (image.isNull() || !image.save(file, "PNG")) {
    report(tr("Could not save the screenshot"), tr("Writing %1 failed.").arg(file));
    return false;
  }
  return true;
}

void MainWindow::report(const QString& title, const QString& message) {
  if (reporter_) reporter_(title, message);
}

void MainWindow::closeEvent(QCloseEvent* event) {
  // Unsaved contact edits, a running training and unsaved networks ask before they are lost.
  std::vector<int> edited;
  for (int i = 0; i < clipCount(); ++i)
    if (clip(i).hasUnsavedContactEdits()) edited.push_back(i);
  if (!keepContactEdits(edited)) {
    event->ignore();
    return;
  }
  if (network_panel_ != nullptr && !network_panel_->prepareToClose()) {
    event->ignore();
    return;
  }
  if (persist_settings_) {
    QSettings settings;
    settings.setValue(kGeometryKey, saveGeometry());
    settings.setValue(kStateKey, saveState());
  }
  QMainWindow::closeEvent(event);
}

bool MainWindow::openDemoScene() {
  if ((!clips_.empty() || result_panel_->result() != nullptr) &&
      !confirmer_(tr("Open the demo?"),
                  tr("The demo makes its two sample clips the content and the style and chooses the elderly style. "
                     "Your clips stay open but lose their roles, and the current result is replaced.")))
    return false;
  const DemoOutcome outcome = openDemo(*this, *result_panel_);
  showStatus(outcome.message);
  return true;
}

void MainWindow::showStatus(const QString& text) {
  statusBar()->clearMessage();  // a temporary message would hide the line
  status_label_->setText(text);
  if (app_log::enabled()) app_log::write(QStringLiteral("status: ") + text);
}

}  // namespace motionstyle
