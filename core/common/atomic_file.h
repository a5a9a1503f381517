#pragma once
// Atomic file writes: the content goes to a temporary file beside the destination, is flushed and
// fsync'ed, and only then renamed over the destination. A failure at any point (disk full, a throwing
// writer, a crash) leaves the destination as it was, never truncated or half-written.

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace motionstyle {

// Calls `write` with a stream on a temporary file, then commits it to `destination`.
// Throws WriteError if the stream fails or the commit fails; rethrows whatever `write` throws.
// In both cases the temporary file is removed and `destination` is untouched.
void writeFileAtomically(const std::filesystem::path& destination,
                         const std::function<void(std::ostream&)>& write);

// Convenience for content already in memory.
void writeFileAtomically(const std::filesystem::path& destination, std::string_view content);

}  // namespace motionstyle
