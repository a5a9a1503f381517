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
#include <QStringList>

#include <functional>
#include <vector>

#include "clip_loader.h"

class QAction;
class QActionGroup;
class QLabel;
class QMenu;
class QTreeWidget;

namespace motionstyle {

class SkeletonViewport;
class TimelineWidget;

class MainWindow : public QMainWindow {
  Q_OBJECT

 public:
  using ErrorReporter = std::function<void(const QString& title, const QString& message)>;
  static constexpr int kMaxRecentFiles = 8;

  // persist_settings = false leaves QSettings untouched (screenshots, tests): no geometry restore, no
  // recent-file writes.
  explicit MainWindow(bool persist_settings = true, QWidget* parent = nullptr);
  ~MainWindow() override;

  void setErrorReporter(ErrorReporter reporter);

  SkeletonViewport* viewport() const { return viewport_; }
  TimelineWidget* timeline() const { return timeline_; }
  QTreeWidget* clipList() const { return clip_list_; }
  int clipCount() const { return static_cast<int>(clips_.size()); }
  const LoadedClip& clip(int index) const { return clips_.at(static_cast<size_t>(index)); }
  int contentClip() const { return content_; }  // index into the clips, -1 when none
  int styleClip() const { return style_; }
  QStringList recentFiles() const;

 public slots:
  // Loads every file (the same path the File menu, drag-and-drop and the command line take), reports
  // all failures in one message, and returns how many loaded.
  int openFiles(const QStringList& paths);
  // Loads every *.bvh directly inside `folder`, in name order.
  int openFolder(const QString& folder);
  void setContentClip(int index);
  void setStyleClip(int index);
  void removeClip(int index);
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
  void refreshClipList();
  void rememberRecent(const QStringList& files);
  void rebuildRecentMenu();
  void showClipMenu(const QPoint& position);
  void browseFiles();
  void browseFolder();
  void browseScreenshot();
  void showAbout();
  void report(const QString& title, const QString& message);
  QString lastFolder() const;
  void setLastFolder(const QString& folder);

  bool persist_settings_;
  ErrorReporter reporter_;
  std::vector<LoadedClip> clips_;
  int content_ = -1;
  int style_ = -1;
  QStringList session_recent_;  // recent files when settings are not persisted

  SkeletonViewport* viewport_ = nullptr;
  TimelineWidget* timeline_ = nullptr;
  QTreeWidget* clip_list_ = nullptr;
  QMenu* recent_menu_ = nullptr;
  QAction* side_by_side_action_ = nullptr;
  QAction* overlay_action_ = nullptr;
  QAction* follow_action_ = nullptr;
  QLabel* status_label_ = nullptr;
};

}  // namespace motionstyle
