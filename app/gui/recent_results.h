#pragma once
// The Result panel's last results, one per style network, each with the inputs it was made from:
// going back to a style already shown for the same clip, strength, path, aim and contacts shows its result
// at once instead of computing it again. An artist compares styles by switching back and forth; a
// switch to a style not yet computed costs a job (75-116 ms for 500 frames, the network included; 45-50 ms
// when it was computed on the clip before: only the clean-up), one back costs a paint.
// At most kCapacity results (a few MB each for a 500-frame clip, plus the prepared network each holds),
// the least recently used going first.

#include <QString>

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "style/path_mode.h"
#include "style/stylize_cleanup_job.h"

namespace motionstyle {

// What a result of a network depends on. Networks are compared by identity: a file read again is
// another network (StylizerCache hands out the same one while its file is unchanged).
struct ResultInputs {
  std::uint64_t content_id = 0;  // LoadedClip::id: another clip, or the same clip mapped again
  std::shared_ptr<const style::Stylizer> stylizer;
  double strength = 1.0;
  style::PathMode path = style::PathMode::Content;
  std::string kind;  // the style clip aimed at: "" read from the clip (StylizeCleanupJob::kind)
  Eigen::MatrixXi contact_overrides;  // at the content's rate, as the job takes them

  bool operator==(const ResultInputs& other) const;
};

class RecentResults {
 public:
  // The shown style, the eight its look-ahead computes at most (ResultPanel::kLookAheadMaxStyles) and
  // one more: the one shown before.
  static constexpr int kCapacity = 10;

  struct Entry {
    ResultInputs inputs;
    std::shared_ptr<const style::StylizeCleanupResult> result;
    QString network_name;
    // The job memory that made it: the next live edit of this style starts from its solution.
    std::shared_ptr<style::StylizeCleanupMemory> memory;
    bool computed_ahead = false;  // by the look-ahead, and not shown yet
  };

  // Keeps `entry`, replacing the one of the same network.
  void remember(Entry entry);
  // The entry made from exactly `inputs` (and now the most recently used), else null.
  Entry* find(const ResultInputs& inputs);
  // Whether there is one, without making it the most recently used (a look, not a use).
  bool contains(const ResultInputs& inputs) const;
  // The job memory of `stylizer`'s result on clip `content_id`, whatever its strength, path, kind and
  // contacts (its network output serves them all, or the job computes it again), else null. A look, not a use.
  std::shared_ptr<style::StylizeCleanupMemory> memoryFor(std::uint64_t content_id,
                                                         const std::shared_ptr<const style::Stylizer>& stylizer) const;
  // Whether an entry holds `memory` (a job on another network would overwrite its network output).
  bool holds(const std::shared_ptr<style::StylizeCleanupMemory>& memory) const;
  void clear() { entries_.clear(); }
  // The network called `old_name` is now `new_name` (ResultPanel::renameNetwork).
  void renameNetwork(const QString& old_name, const QString& new_name);
  int size() const { return static_cast<int>(entries_.size()); }

 private:
  std::vector<Entry> entries_;  // least recently used first
};

}  // namespace motionstyle
