// MainWindow's file dialogs, recent-file list and remembered folder (QSettings), the joint-mapping
// template, and About box.
#include <QApplication>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QMenu>
#include <QMessageBox>
#include <QSettings>

#include "main_window.h"

#include "common/atomic_file.h"
#include "common/output_paths.h"
#include "error_text.h"
#include "mapping/mapping_file.h"

namespace motionstyle {
namespace {

const char* const kRecentFilesKey = "recentFiles";

}  // namespace

QStringList MainWindow::recentFiles() const {
  if (!persist_settings_) return session_recent_;
  return QSettings().value(kRecentFilesKey).toStringList();
}

void MainWindow::rememberRecent(const QStringList& files) {
  QStringList recent = recentFiles();
  for (const QString& file : files) {
    recent.removeAll(file);
    recent.prepend(file);
  }
  while (recent.size() > kMaxRecentFiles) recent.removeLast();
  if (persist_settings_) QSettings().setValue(kRecentFilesKey, recent);
  else session_recent_ = recent;
  rebuildRecentMenu();
}

void MainWindow::rebuildRecentMenu() {
  recent_menu_->clear();
  const QStringList recent = recentFiles();
  for (int i = 0; i < recent.size(); ++i) {
    const QString& file = recent[i];
    QAction* action = recent_menu_->addAction(QStringLiteral("&%1  %2").arg(i + 1).arg(QFileInfo(file).fileName()),
                                              this, [this, file] { openFiles({file}); });
    action->setToolTip(file);
    action->setStatusTip(file);
  }
  if (!recent.isEmpty()) recent_menu_->addSeparator();
  QAction* clear = recent_menu_->addAction(tr("&Clear List"), this, [this] {
    if (persist_settings_) QSettings().remove(kRecentFilesKey);
    session_recent_.clear();
    rebuildRecentMenu();
  });
  clear->setEnabled(!recent.isEmpty());
}

void MainWindow::browseFiles() {
  const QStringList files = QFileDialog::getOpenFileNames(this, tr("Open BVH clips"), clipFolder().folder(),
                                                          tr("BVH motion (*.bvh *.BVH);;All files (*)"));
  if (!files.isEmpty()) openFiles(files);
}

void MainWindow::browseFolder() {
  const QString folder = QFileDialog::getExistingDirectory(this, tr("Open a folder of BVH clips"), clipFolder().folder());
  if (!folder.isEmpty()) openFolder(folder);
}

void MainWindow::browseScreenshot() {
  const QString file = QFileDialog::getSaveFileName(this, tr("Save screenshot"),
                                                    QDir(clipFolder().folder()).filePath(QStringLiteral("motionstyle.png")),
                                                    tr("PNG image (*.png)"));
  if (!file.isEmpty()) saveScreenshot(file);
}

void MainWindow::browseMappingFile(int index) {
  const QString file = QFileDialog::getOpenFileName(this, tr("Load a joint mapping file"), clipFolder().folder(),
                                                    tr("Joint mapping (*.json);;All files (*)"));
  if (!file.isEmpty()) loadMappingFile(index, file);
}

void MainWindow::browseMappingTemplate(int index) {
  const QString suggested = clip(index).path + QStringLiteral(".mapping.json");
  const QString file = QFileDialog::getSaveFileName(this, tr("Save a joint mapping template"), suggested,
                                                    tr("Joint mapping (*.json);;All files (*)"));
  if (!file.isEmpty()) saveMappingTemplate(index, file);
}

bool MainWindow::saveMappingTemplate(int index, const QString& file) {
  if (index < 0 || index >= clipCount()) return false;
  const LoadedClip& c = clip(index);
  const JointMapping mapping = c.mapping ? *c.mapping : guessJointMapping(c.motion.skeleton);
  try {
    checkOutputPaths({{c.path.toStdString(), "the clip"}}, {{file.toStdString(), "the mapping template"}});
    writeFileAtomically(file.toStdString(), formatJointMappingTemplate(mapping, c.motion.skeleton, c.name.toStdString()));
  } catch (...) {
    report(tr("Could not save the mapping template"), errorText(std::current_exception(), file));
    return false;
  }
  const int gaps = static_cast<int>(mapping.missing().size());
  showStatus(gaps == 0 ? tr("Saved the mapping of %1 in %2").arg(c.name, file)
                       : tr("Saved the mapping template of %1 in %2: fill in its %3 empty joint(s), then Load Mapping File")
                             .arg(c.name, file)
                             .arg(gaps));
  return true;
}

QString MainWindow::emptyViewMessage() const {
  // With a style network chosen the Style clip is not drawn: clips, but no content, leave the view empty.
  return clipCount() == 0
             ? tr("<b>No clips yet</b><br><br>File &#9656; Open BVH (Ctrl+O), or drop BVH files or folders here.<br>"
                  "New to MotionStyle? Help &#9656; Open Demo loads two sample clips and a style.")
             : tr("<b>No content clip</b><br><br>Right-click a clip in the Clips list and choose Use as Content.");
}

void MainWindow::showShortcuts() {
  QMessageBox::information(
      this, tr("Keyboard Shortcuts"),
      tr("<table cellpadding='3'>"
         "<tr><td><b>Space</b></td><td>play / pause</td></tr>"
         "<tr><td><b>Left / Right</b></td><td>previous / next frame</td></tr>"
         "<tr><td><b>Home / End</b></td><td>first / last frame</td></tr>"
         "<tr><td><b>1 / 2</b></td><td>side by side / overlay</td></tr>"
         "<tr><td><b>C</b></td><td>follow camera on or off</td></tr>"
         "<tr><td><b>F</b></td><td>reset the camera</td></tr>"
         "<tr><td><b>T</b></td><td>show trajectories</td></tr>"
         "<tr><td><b>R</b></td><td>show the raw network output</td></tr>"
         "<tr><td><b>Ctrl+O</b></td><td>open BVH clips</td></tr>"
         "<tr><td><b>Ctrl+E</b></td><td>export the result</td></tr>"
         "<tr><td colspan='2'><br>A focused control keeps the keys it moves with: the arrows, Home and End "
         "move the strength slider; Up, Down, Home, End and a letter pick in a list or the style chooser. Space "
         "plays from anywhere.</td></tr>"
         "<tr><td colspan='2'><br>Viewport: drag to orbit, Shift or middle drag to pan, wheel or right drag to "
         "zoom.<br>Contact tracks: press on a foot's track to toggle contact there, drag to paint that value over "
         "the frames you cross.</td></tr>"
         "</table>"));
}

void MainWindow::showAbout() {
  QMessageBox::about(
      this, tr("About MotionStyle"),
      tr("<h3>MotionStyle %1</h3>"
         "<p>Fast neural style transfer for motion capture, after Holden, Habibie, Kusajima and Komura, "
         "<i>Fast Neural Style Transfer for Motion Data</i>, IEEE CG&amp;A 2017.</p>"
         "<p>Load a content clip and a style clip (BVH), get the content performed in that style, clean "
         "it up with IK and export it on your own skeleton.</p>"
         "<p>Colours: <span style='color:#4cbd5c'>content</span>, <span style='color:#db4a45'>style</span>, "
         "<span style='color:#4280eb'>output</span>.</p>")
          .arg(QApplication::applicationVersion()));
}

}  // namespace motionstyle
