#pragma once
// The style networks the Result panel has prepared, by file, so that switching back to a style skips
// reading its file and preparing its layers (a shipped network: 14-16 ms to read, 13-14 ms to prepare,
// measured by test_gui_live's style switch; a style picked in the chooser is read on a worker,
// ResultPanel::chooseNetwork). A file whose size or modification
// time changed since is read again. At most kCapacity networks, the least recently used going first:
// a prepared shipped network holds about 38 MB (its model and its transformation network's kernel
// spectra; the loss network's, about 40 MB, are shared: style::sharedProjection), so the cache keeps
// the styles a user compares and the look-ahead computes (as many as RecentResults keeps, so that a
// style computed ahead is found prepared when it is chosen), not every network ever opened.

#include <QDateTime>
#include <QString>

#include <memory>
#include <vector>

#include "style/stylizer.h"

namespace motionstyle {

class StylizerCache {
 public:
  static constexpr int kCapacity = 10;

  // The network prepared from `file` when the file is unchanged since, else null.
  std::shared_ptr<const style::Stylizer> find(const QString& file);
  // Keeps `stylizer` as the one prepared from `file` as it is now.
  void store(const QString& file, std::shared_ptr<const style::Stylizer> stylizer);

 private:
  struct Entry {
    QString file;  // absolute
    QDateTime modified;
    qint64 size = -1;
    std::shared_ptr<const style::Stylizer> stylizer;
  };
  std::vector<Entry> entries_;  // least recently used first
};

}  // namespace motionstyle
