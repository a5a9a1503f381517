#include "clip_file_watcher.h"

#include <QFileInfo>
#include <QFileSystemWatcher>
#include <QTimer>

#include <utility>

namespace motionstyle {

ClipFileWatcher::ClipFileWatcher(QObject* parent)
    : QObject(parent), watcher_(new QFileSystemWatcher(this)), settle_(new QTimer(this)) {
  settle_->setSingleShot(true);
  settle_->setInterval(300);
  connect(watcher_, &QFileSystemWatcher::fileChanged, this, &ClipFileWatcher::noticeChange);
  // A save by rename replaces the file: its folder changes, and the file is no longer watched.
  connect(watcher_, &QFileSystemWatcher::directoryChanged, this, [this](const QString& folder) {
    for (auto it = seen_.cbegin(); it != seen_.cend(); ++it)
      if (QFileInfo(it.key()).absolutePath() == folder && !(seenNow(it.key()) == it.value())) noticeChange(it.key());
  });
  connect(settle_, &QTimer::timeout, this, &ClipFileWatcher::reportChanges);
}

ClipFileWatcher::Seen ClipFileWatcher::seenNow(const QString& path) {
  const QFileInfo info(path);
  if (!info.exists()) return {};
  return {info.size(), info.lastModified()};
}

void ClipFileWatcher::watch(const QString& path) {
  seen_[path] = seenNow(path);
  pending_.remove(path);
  if (!watcher_->files().contains(path)) watcher_->addPath(path);
  const QString folder = QFileInfo(path).absolutePath();
  if (!watcher_->directories().contains(folder)) watcher_->addPath(folder);
}

void ClipFileWatcher::forget(const QString& path) {
  seen_.remove(path);
  pending_.remove(path);
  watcher_->removePath(path);
  const QString folder = QFileInfo(path).absolutePath();
  for (auto it = seen_.cbegin(); it != seen_.cend(); ++it)
    if (QFileInfo(it.key()).absolutePath() == folder) return;  // still watched for another clip
  watcher_->removePath(folder);
}

void ClipFileWatcher::noticeChange(const QString& path) {
  if (!seen_.contains(path)) return;
  pending_.insert(path);
  settle_->start();  // restarted by every write of a burst
}

void ClipFileWatcher::reportChanges() {
  const QSet<QString> changed = std::exchange(pending_, {});
  for (const QString& path : changed) {
    if (!seen_.contains(path)) continue;
    const Seen now = seenNow(path);
    if (now.size >= 0 && !watcher_->files().contains(path)) watcher_->addPath(path);  // replaced by a rename
    if (now == seen_[path]) continue;
    seen_[path] = now;
    emit changedOnDisk(path);
  }
}

}  // namespace motionstyle
