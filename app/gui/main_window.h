#pragma once
// MainWindow: the desktop app's frame. The viewport is the central widget, the timeline is docked at
// the bottom and the "Clips" dock lists loaded clips (frames, fps, joints, role).
//
// Roles for now: the first loaded clip is the content (green), the second the style (red); the
// clips list's context menu reassigns them. Later steps add a clip library, training and output
// panels as further docks; the figure set is rebuilt in one place (rebuildFigures) for them.
//
// Errors: every user-facing failure goes through the ErrorReporter (default: a warning QMessageBox),
// which tests replace; the window stays usable after any failed load.

#include <QMainWindow>
#include <QMessageBox>
#include <QSet>
#include <QStringList>

#include <functional>
#include <optional>
#include <vector>

#include "clip_loader.h"
#include "remembered_folder.h"

class QAction;
class QActionGroup;
class QLabel;
class QMenu;
class QProgressDialog;
class QTreeWidget;

namespace motionstyle {

class ClipFileWatcher;
class ContactTrackController;
class LiveResolution;
class NetworkPanel;
class ResultPanel;
class SkeletonViewport;
class TimelineWidget;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  using ErrorReporter = std::function<void(const QString& title, const QString& message)>;
  // Asks before an action replaces what the user set up; true = go ahead (default: a Yes/No box).
  using Confirmer = std::function<bool(const QString& title, const QString& question)>;
  // Asks with a choice of buttons (unsaved contact edits: Save, Discard, Cancel); returns the answer.
  using ChoiceAsker = std::function<QMessageBox::StandardButton(const QString& title, const QString& question,
                                                                QMessageBox::StandardButtons buttons)>;
  static constexpr int kMaxRecentFiles = 8;

  // persist_settings = false leaves QSettings untouched (screenshots, tests): no geometry restore, no
  // recent-file writes.
  explicit MainWindow(bool persist_settings = true, QWidget* parent = nullptr);
  ~MainWindow() override;

  void setErrorReporter(ErrorReporter reporter);
  void setConfirmer(Confirmer confirmer) { confirmer_ = std::move(confirmer); }
  void setChoiceAsker(ChoiceAsker asker) { choice_asker_ = std::move(asker); }

  // Help > Open Demo (demo_scene.h): sample clips as content and style, the bundled style selected.
  // With clips or a result already there it asks first (the roles and the result change); false when
  // declined. Samples already open are reused, never added twice.
  bool openDemoScene();
  // The status bar's line, shown (a temporary QStatusBar message, which hides it, is cleared) and
  // written to the app's log as "status: TEXT". Every message of the window goes here.
  void showStatus(const QString& text);

  SkeletonViewport* viewport() const { return viewport_; }
  TimelineWidget* timeline() const { return timeline_; }
  QTreeWidget* clipList() const { return clip_list_; }
  ResultPanel* resultPanel() const { return result_panel_; }
  NetworkPanel* networkPanel() const { return network_panel_; }
  ContactTrackController* contactTracks() const { return contact_tracks_; }
  int clipCount() const { return static_cast<int>(clips_.size()); }
  const LoadedClip& clip(int index) const { return clips_.at(static_cast<size_t>(index)); }
  int contentClip() const { return content_; }  // index into the clips, -1 when none
  int styleClip() const { return style_; }
  QStringList recentFiles() const;

 // The "training set" role (main_window_networks.cpp): any number of clips may have it; they are
  // the content clips the Style networks panel trains on, with its folders.
  bool isTrainingClip(int index) const;
  QStringList trainingClipPaths() const;

 signals:
  // The clip list or a role changed (emitted by refreshClipList).
  void clipsChanged();

 public slots:
  void setTrainingClip(int index, bool on);
  // Loads every file (the same path the File menu, drag-and-drop and the command line take), reports
  // all failures in one message, and returns how many loaded.
  int openFiles(const QStringList& paths);
  // Loads every *.bvh directly inside `folder`, in name order.
  int openFolder(const QString& folder);
  // Files and folders in the order given (the command line, drag-and-drop): each run of files with
  // openFiles, each folder with openFolder. Returns how many clips loaded.
  int openPaths(const QStringList& paths);
  // Reads clip `index` from its file again (a new take exported over it), keeping its roles; asks first
  // when its contact edits are unsaved. False (and a report) when the file cannot be read: the clip
  // stays as it was.
  bool reloadClip(int index);
  void setContentClip(int index);
  void setStyleClip(int index);
  void removeClip(int index);
  // Re-maps clip `index` with a joint mapping file (mapping/mapping_file.h); its contacts are found
  // again (asking first about unsaved contact edits). False and a report if the file does not fit the rig.
  bool loadMappingFile(int index, const QString& file);
  // Writes clip `index`'s mapping (or the automatic mapping's guess, gaps empty) as a mapping file to
  // complete by hand (formatJointMappingTemplate); false (and a report) on failure.
  bool saveMappingTemplate(int index, const QString& file);
  // Shows or hides the raw network output (grey) beside the cleaned output.
  void setRawOutputVisible(bool visible);
  // Saves a PNG of the whole window as it is now; false (and a report) on failure.
  bool saveScreenshot(const QString& file);

 protected:
  void closeEvent(QCloseEvent* event) override;
  void dragEnterEvent(QDragEnterEvent* event) override;
  void dropEvent(QDropEvent* event) override;

 private:
  void createDocks();
  void createMenus();
  void rebuildFigures();
  void renameResultFigures();  // the result went out of date: its figures' names only
  // openFiles and openFolder: loads in order (stopping when `progress` is cancelled), then one list
  // refresh, one status line for all of them and one report of every failure.
  int loadClips(const QStringList& paths, QProgressDialog* progress);
  void refreshClipList();
  // Before the contact edits of `clips` (indices) could be lost (closing, removing a clip): asks to
  // save them beside their clips, or to discard them. False when the user cancels or a save fails.
  bool keepContactEdits(const std::vector<int>& clips);
  // The file of an open clip changed (or went) on disk: the list marks it and the status line says so.
  void noticeClipFileChanged(const QString& path);
  void rememberRecent(const QStringList& files);
  void rebuildRecentMenu();
  void showClipMenu(const QPoint& position);
  void browseFiles();
  void browseFolder();
  void browseScreenshot();
  void browseMappingFile(int index);
  void browseMappingTemplate(int index);
  void createResultDock();
  void createNetworkDock();
  void forgetTrainingClip(int removed_index);
  void showAbout();
  void showShortcuts();
  // What the view shows when it has no figure: how to open clips, or how to choose the content.
  QString emptyViewMessage() const;
  void report(const QString& title, const QString& message);
  RememberedFolder clipFolder() const { return {kClipFolderKey, persist_settings_}; }

  bool persist_settings_;
  ErrorReporter reporter_;
  Confirmer confirmer_;
  ChoiceAsker choice_asker_;
  std::vector<LoadedClip> clips_;
  ClipFileWatcher* file_watcher_ = nullptr;
  QSet<QString> changed_on_disk_;  // paths of open clips whose file is no longer what is shown
  int content_ = -1;
  int style_ = -1;
  QStringList session_recent_;  // recent files when settings are not persisted

  SkeletonViewport* viewport_ = nullptr;
  LiveResolution* live_resolution_ = nullptr;
  TimelineWidget* timeline_ = nullptr;
  QTreeWidget* clip_list_ = nullptr;
  QMenu* recent_menu_ = nullptr;
  QAction* side_by_side_action_ = nullptr;
  QAction* overlay_action_ = nullptr;
  QAction* follow_action_ = nullptr;
  QLabel* status_label_ = nullptr;
  ResultPanel* result_panel_ = nullptr;
  NetworkPanel* network_panel_ = nullptr;
  std::vector<int> training_clips_;           // indices with the training-database role, ascending
  std::optional<FigureData> training_preview_;  // the live training preview (blue), while fresh
  ContactTrackController* contact_tracks_ = nullptr;
  QAction* raw_output_action_ = nullptr;
};

}  // namespace motionstyle
