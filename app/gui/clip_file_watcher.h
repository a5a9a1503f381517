#pragma once
// ClipFileWatcher: tells when a clip's file changes on disk after it was opened (an animator exports a
// new take over it from another tool), so that the window can say the clip it shows is no longer the
// file's and offer to reload it.
//
// changedOnDisk(path) is emitted once per burst of writes (a tool may write a file in several steps),
// 300 ms after the last one, when the file's size or modification time differs from the last seen;
// removed files are reported too (exists() then says so). A file replaced by a rename (the atomic save
// of most tools, MotionStyle's own included) stays watched.

#include <QDateTime>
#include <QHash>
#include <QObject>
#include <QSet>
#include <QString>

class QFileSystemWatcher;
class QTimer;

namespace motionstyle {

class ClipFileWatcher : public QObject {
  Q_OBJECT

 public:
  explicit ClipFileWatcher(QObject* parent = nullptr);

  // Starts (or restarts, after a reload) watching `path` as it is now.
  void watch(const QString& path);
  void forget(const QString& path);

 signals:
  void changedOnDisk(const QString& path);

 private:
  struct Seen {
    qint64 size = -1;
    QDateTime modified;
    bool operator==(const Seen& other) const { return size == other.size && modified == other.modified; }
  };
  static Seen seenNow(const QString& path);
  void noticeChange(const QString& path);
  void reportChanges();

  QFileSystemWatcher* watcher_ = nullptr;
  QTimer* settle_ = nullptr;
  QHash<QString, Seen> seen_;
  QSet<QString> pending_;
};

}  // namespace motionstyle
