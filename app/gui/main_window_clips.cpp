// MainWindow: opening clips (the File menu, the command line, drag-and-drop, folders) and keeping
// the user's contact edits (saved beside each clip, asked about before they could be lost).
#include "main_window.h"

#include <QDir>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileInfo>
#include <QMimeData>
#include <QProgressDialog>
#include <QUrl>

#include "bvh/bvh_reader.h"
#include "clip_file_watcher.h"
#include "error_text.h"
#include "result_panel.h"

namespace motionstyle {
namespace {

bool isBvhPath(const QString& path) { return path.endsWith(QStringLiteral(".bvh"), Qt::CaseInsensitive); }

}  // namespace

int MainWindow::openFiles(const QStringList& paths) { return loadClips(paths, nullptr); }

int MainWindow::loadClips(const QStringList& paths, QProgressDialog* progress) {
  QStringList failures;
  QStringList loaded;
  bool cancelled = false;
  // With a style network chosen the Style role plays no part (and is not drawn): a clip opened beside a
  // content clip becomes the content, shown and stylized, rather than a Style clip nothing shows.
  const bool style_role_unused = result_panel_->resultComesFromNetwork();
  const int previous_content = content_;
  for (qsizetype i = 0; i < paths.size(); ++i) {
    if (progress) {
      if (progress->wasCanceled()) {
        cancelled = true;
        break;
      }
      progress->setValue(static_cast<int>(i));
    }
    const QString& path = paths[i];
    try {
      clips_.push_back(loadClip(std::filesystem::path(path.toStdString())));
      loaded << clips_.back().path;
      file_watcher_->watch(clips_.back().path);
      if (content_ < 0 || (style_role_unused && content_ == previous_content)) content_ = clipCount() - 1;
      else if (style_ < 0 && !style_role_unused) style_ = clipCount() - 1;
    } catch (...) {
      failures << errorText(std::current_exception(), path);
    }
  }
  if (progress) progress->setValue(progress->maximum());
  if (!loaded.isEmpty()) {
    rememberRecent(loaded);
    clipFolder().remember(QFileInfo(loaded.back()).absolutePath());
    refreshClipList();
    rebuildFigures();
  }
  QStringList contact_notes;  // contacts read from the files beside the clips, or why not
  for (int i = clipCount() - static_cast<int>(loaded.size()); i < clipCount(); ++i)
    if (!clip(i).contacts_note.isEmpty()) contact_notes << clip(i).contacts_note;
  const QString content_note = previous_content >= 0 && content_ != previous_content
                                   ? tr("; %1 is the content now (%2 stays open: its menu's Use as Content goes back)")
                                         .arg(clip(content_).name, clip(previous_content).name)
                                   : QString();
  showStatus((loaded.size() == 1 ? tr("Loaded 1 clip") : tr("Loaded %1 clips").arg(loaded.size())) + content_note +
             (failures.isEmpty() ? QString() : tr(", %1 failed").arg(failures.size())) +
             (cancelled ? tr("; cancelled") : QString()) +
             (contact_notes.isEmpty() ? QString() : QStringLiteral("; ") + contact_notes.join(QStringLiteral("; "))));
  if (!failures.isEmpty())
    report(failures.size() == 1 ? tr("Could not open the clip") : tr("Could not open %1 clips").arg(failures.size()),
           failures.join(QStringLiteral("\n\n")));
  return static_cast<int>(loaded.size());
}

int MainWindow::openFolder(const QString& folder) {
  const QDir dir(folder);
  if (!dir.exists()) {
    report(tr("Could not open the folder"), tr("%1 does not exist.").arg(folder));
    return 0;
  }
  QStringList files;
  for (const QFileInfo& info : dir.entryInfoList({QStringLiteral("*.bvh"), QStringLiteral("*.BVH")}, QDir::Files, QDir::Name))
    files << info.absoluteFilePath();
  files.removeDuplicates();
  clipFolder().remember(dir.absolutePath());
  if (files.isEmpty()) {
    report(tr("No clips found"), tr("%1 holds no .bvh files.").arg(dir.absolutePath()));
    return 0;
  }
  // A large folder takes a while: a cancellable progress dialog; one refresh and one report at the end.
  QProgressDialog progress(tr("Loading clips..."), tr("Cancel"), 0, static_cast<int>(files.size()), this);
  progress.setWindowModality(Qt::WindowModal);
  progress.setMinimumDuration(500);
  return loadClips(files, &progress);
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
  // Any local file: what cannot be opened is said on the drop, never refused without a word.
  for (const QUrl& url : event->mimeData()->urls()) {
    if (url.isLocalFile()) {
      event->acceptProposedAction();
      return;
    }
  }
}

void MainWindow::dropEvent(QDropEvent* event) {
  QStringList paths;     // folders and clips, and other tools' motion files (their error says what to do)
  QStringList networks;  // style networks: used in the Result panel, as its "Open network file..." does
  QStringList ignored;   // anything else (notes, videos); a clip's saved contact tracks are read with it
  for (const QUrl& url : event->mimeData()->urls()) {
    if (!url.isLocalFile()) continue;
    const QString path = url.toLocalFile();
    if (QFileInfo(path).isDir() || isBvhPath(path) || otherMotionFormat({}, path.toStdString()) != nullptr) paths << path;
    else if (path.endsWith(QStringLiteral(".net"), Qt::CaseInsensitive)) networks << path;
    else if (!path.endsWith(QStringLiteral(".contacts.json"), Qt::CaseInsensitive)) ignored << QFileInfo(path).fileName();
  }
  event->acceptProposedAction();
  if (paths.isEmpty() && networks.isEmpty() && !ignored.isEmpty()) {
    report(tr("Nothing to open"), tr("%1: MotionStyle opens BVH clips (.bvh), folders of them and style networks (.net).")
                                      .arg(ignored.join(QStringLiteral(", "))));
    return;
  }
  openPaths(paths);
  for (const QString& network : networks) result_panel_->openNetworkFile(network);
}

int MainWindow::openPaths(const QStringList& paths) {
  int loaded = 0;
  QStringList files;
  const auto openRun = [&] {
    if (!files.isEmpty()) loaded += openFiles(files);
    files.clear();
  };
  for (const QString& path : paths) {
    if (!QFileInfo(path).isDir()) {
      files << path;
      continue;
    }
    openRun();
    loaded += openFolder(path);
  }
  openRun();
  return loaded;
}

bool MainWindow::keepContactEdits(const std::vector<int>& clips) {
  QStringList names;
  for (int i : clips)
    if (clip(i).hasUnsavedContactEdits()) names << clip(i).name;
  if (names.isEmpty()) return true;
  const QMessageBox::StandardButton answer = choice_asker_(
      tr("Unsaved contact edits"),
      tr("The foot contacts you edited on %1 are not saved.\n\nSave them beside the clip (as .contacts.json, which "
         "the clean-up reads), or discard them?", nullptr, static_cast<int>(names.size()))
          .arg(names.join(QStringLiteral(", "))),
      QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel);
  if (answer == QMessageBox::Discard) return true;
  if (answer != QMessageBox::Save) return false;
  for (int i : clips) {
    if (!clip(i).hasUnsavedContactEdits()) continue;
    try {
      saveContactTracksBeside(clips_[static_cast<size_t>(i)]);
    } catch (...) {
      report(tr("Could not save the contact tracks"), errorText(std::current_exception(), clip(i).path));
      return false;
    }
  }
  return true;
}

void MainWindow::noticeClipFileChanged(const QString& path) {
  QString name;
  for (const LoadedClip& c : clips_)
    if (c.path == path) name = c.name;
  if (name.isEmpty()) return;
  changed_on_disk_.insert(path);
  refreshClipList();
  showStatus(QFileInfo::exists(path)
                 ? tr("%1 changed on disk: what is shown is the file as it was opened; right-click it and choose "
                      "Reload from Disk to see the new one.").arg(name)
                 : tr("%1 was removed or renamed on disk: what is shown is the file as it was opened.").arg(name));
}

bool MainWindow::reloadClip(int index) {
  if (index < 0 || index >= clipCount() || !keepContactEdits({index})) return false;
  const QString path = clip(index).path;
  try {
    LoadedClip reloaded = loadClip(std::filesystem::path(path.toStdString()));
    clips_[static_cast<size_t>(index)] = std::move(reloaded);  // a new id: results of the old take go
  } catch (...) {
    report(tr("Could not reload the clip"), errorText(std::current_exception(), path));
    return false;
  }
  file_watcher_->watch(path);
  changed_on_disk_.remove(path);
  refreshClipList();
  rebuildFigures();
  const LoadedClip& c = clip(index);
  showStatus(tr("Reloaded %1: %2 frames at %3 fps").arg(c.name).arg(c.frameCount()).arg(c.fps(), 0, 'g', 4) +
             (c.contacts_note.isEmpty() ? QString() : QStringLiteral("; ") + c.contacts_note));
  return true;
}

}  // namespace motionstyle
