#pragma once
// RememberedFolder: where the user last chose files of one kind, so that the next dialog starts
// there. Kept in QSettings under its key when the window persists settings (tests do not); a folder
// that no longer exists, or none yet, gives the home folder.
//
// The kinds: kClipFolderKey (BVH clips, training folders and style clips: File > Open, the Train
// tab) and kNetworkFolderKey (network files: Load, Save As, Save All, the loss network).

#include <QDir>
#include <QSettings>
#include <QString>

namespace motionstyle {

inline constexpr const char* kClipFolderKey = "lastFolder";
inline constexpr const char* kNetworkFolderKey = "networks/lastFolder";

class RememberedFolder {
 public:
  RememberedFolder(const char* key, bool persist) : key_(key), persist_(persist) {}

  QString folder() const {
    const QString folder = persist_ ? QSettings().value(QString::fromLatin1(key_)).toString() : QString();
    return !folder.isEmpty() && QDir(folder).exists() ? folder : QDir::homePath();
  }
  void remember(const QString& folder) const {
    if (persist_) QSettings().setValue(QString::fromLatin1(key_), folder);
  }

 private:
  const char* key_;
  bool persist_;
};

}  // namespace motionstyle
