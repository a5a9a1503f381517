#include "recent_results.h"

#include <algorithm>

namespace motionstyle {

bool ResultInputs::operator==(const ResultInputs& other) const {
  return content_id == other.content_id && stylizer == other.stylizer && strength == other.strength &&
         path == other.path && kind == other.kind && contact_overrides.rows() == other.contact_overrides.rows() &&
         contact_overrides.cols() == other.contact_overrides.cols() && contact_overrides == other.contact_overrides;
}

void RecentResults::remember(Entry entry) {
  if (!entry.inputs.stylizer || !entry.result) return;
  std::erase_if(entries_, [&](const Entry& e) { return e.inputs.stylizer == entry.inputs.stylizer; });
  entries_.push_back(std::move(entry));
  if (static_cast<int>(entries_.size()) > kCapacity) entries_.erase(entries_.begin());
}

RecentResults::Entry* RecentResults::find(const ResultInputs& inputs) {
  const auto found = std::find_if(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.inputs == inputs; });
  if (found == entries_.end()) return nullptr;
  std::rotate(found, found + 1, entries_.end());  // now the most recently used
  return &entries_.back();
}

bool RecentResults::contains(const ResultInputs& inputs) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.inputs == inputs; });
}

std::shared_ptr<style::StylizeCleanupMemory> RecentResults::memoryFor(
    std::uint64_t content_id, const std::shared_ptr<const style::Stylizer>& stylizer) const {
  for (const Entry& e : entries_)
    if (e.inputs.content_id == content_id && e.inputs.stylizer == stylizer) return e.memory;
  return nullptr;
}

bool RecentResults::holds(const std::shared_ptr<style::StylizeCleanupMemory>& memory) const {
  return std::any_of(entries_.begin(), entries_.end(), [&](const Entry& e) { return e.memory == memory; });
}

void RecentResults::renameNetwork(const QString& old_name, const QString& new_name) {
  for (Entry& entry : entries_)
    if (entry.network_name == old_name) entry.network_name = new_name;
}

}  // namespace motionstyle
