#pragma once
// Atomic file writes: the content goes to a temporary file beside the destination, is flushed and
// fsync'ed (FileDurability below), and only then renamed over the destination. A failure at any
// point (disk full, a throwing writer, a crash) leaves the destination as it was, never truncated or
// half-written.
//
// What the user owns is kept as it was, apart from the content:
// - a symlink is written through: the temporary goes beside the link's final target and replaces the
//   target, so the link stays a link (and a link to a file elsewhere does not become a local copy);
// - an existing destination keeps its permission bits (a 600 file stays 600); a new one gets the
//   usual 666 minus the umask.
// Temporaries are named ".NAME.tmp-PID-RANDOM". A process killed mid-write (kill -9, power cut) leaves
// its temporary behind; every later write to the same destination removes the temporaries whose
// process no longer runs, so they never pile up (a temporary of a live process is never touched).

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>
#include <vector>

namespace motionstyle {

// Whether a write reaches the disk before it replaces the destination.
//   Synced   (the default): fsync'ed first, so a power cut leaves the old file or the new one.
//   Unsynced: no fsync: the swap is still atomic for every reader while the system runs, but a power
//             cut may leave an empty file. For scratch files no later boot reads (the app's training
//             checkpoints): an fsync waits for the disk's journal, however busy, and a cancel would
//             wait for it.
enum class FileDurability { Synced, Unsynced };

// Calls `write` with a stream on a temporary file, then commits it to `destination`.
// Throws WriteError if the stream fails or the commit fails; rethrows whatever `write` throws.
// In both cases the temporary file is removed and `destination` is untouched.
void writeFileAtomically(const std::filesystem::path& destination,
                         const std::function<void(std::ostream&)>& write);

// Convenience for content already in memory.
void writeFileAtomically(const std::filesystem::path& destination, std::string_view content,
                         FileDurability durability = FileDurability::Synced);

// Several files written all or none (a clip and its metrics, say): stage() writes each to its
// temporary and fsyncs it (unless Unsynced); commit() then renames them all. A failure while staging,
// or destroying the batch before commit(), removes every temporary and leaves every destination
// untouched. Why: a command that fails half-way must not leave half of what was asked.
class AtomicFileBatch {
 public:
  explicit AtomicFileBatch(FileDurability durability = FileDurability::Synced) : durability_(durability) {}
  AtomicFileBatch(const AtomicFileBatch&) = delete;
  AtomicFileBatch& operator=(const AtomicFileBatch&) = delete;
  ~AtomicFileBatch();

  // WriteError (temporary removed) on failure; rethrows what `write` throws.
  void stage(const std::filesystem::path& destination, const std::function<void(std::ostream&)>& write);
  void stage(const std::filesystem::path& destination, std::string_view content);
  // Renames every staged file over its destination, in staging order. WriteError if a rename fails
  // (then the remaining temporaries are removed; destinations renamed before stay written).
  void commit();

 private:
  struct Staged {
    std::filesystem::path destination;  // symlinks resolved
    std::filesystem::path temporary;
  };
  FileDurability durability_;
  std::vector<Staged> staged_;
};

// `path` with the symlinks of its last component followed to the final target (relative links are
// read from the link's folder). A path that is not a symlink, or does not exist, is returned as is;
// WriteError on a loop (more than 40 links).
std::filesystem::path followSymlinks(const std::filesystem::path& path);

// Removes the temporaries of `destination` (".NAME.tmp-PID-*" beside it) whose process PID no longer
// runs. Returns how many were removed. Never throws.
int removeStaleTemporaries(const std::filesystem::path& destination);

}  // namespace motionstyle
