#include "stylizer_cache.h"

#include <QFileInfo>

#include <algorithm>

namespace motionstyle {

std::shared_ptr<const style::Stylizer> StylizerCache::find(const QString& file) {
  const QFileInfo info(file);
  const auto found = std::find_if(entries_.begin(), entries_.end(),
                                  [&](const Entry& entry) { return entry.file == info.absoluteFilePath(); });
  if (found == entries_.end()) return nullptr;
  if (!info.exists() || info.lastModified() != found->modified || info.size() != found->size) {
    entries_.erase(found);  // changed on disk: read again
    return nullptr;
  }
  std::rotate(found, found + 1, entries_.end());  // now the most recently used
  return entries_.back().stylizer;
}

void StylizerCache::store(const QString& file, std::shared_ptr<const style::Stylizer> stylizer) {
  const QFileInfo info(file);
  std::erase_if(entries_, [&](const Entry& entry) { return entry.file == info.absoluteFilePath(); });
  if (static_cast<int>(entries_.size()) >= kCapacity) entries_.erase(entries_.begin());
  entries_.push_back({info.absoluteFilePath(), info.lastModified(), info.size(), std::move(stylizer)});
}

}  // namespace motionstyle
