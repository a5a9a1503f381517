// libFuzzer target for the BVH reader (and, on what it accepts, the writer).
//
// parseBvh may only return a valid Motion or throw InputError. Anything else is a finding: a crash,
// a sanitizer report, another exception type escaping (libFuzzer reports it as a crash), a Motion
// that fails validate(), or a text whose write -> read round trip does not reproduce the Motion.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "common/errors.h"

namespace {

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_bvh_reader finding: %s\n", what);
  std::abort();
}

void checkRoundTrip(const motionstyle::Motion& motion) {
  motion.validate();  // throws std::invalid_argument, which escapes and is reported
  motionstyle::Motion again;
  try {
    again = motionstyle::parseBvh(motionstyle::formatBvh(motion), "rewritten.bvh");
  } catch (const motionstyle::InputError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    finding("the reader rejects what the writer wrote");
  }
  if (again.skeleton.jointCount() != motion.skeleton.jointCount()) finding("round trip changed the joint count");
  for (int j = 0; j < motion.skeleton.jointCount(); ++j) {
    const auto& a = motion.skeleton.joints[static_cast<std::size_t>(j)];
    const auto& b = again.skeleton.joints[static_cast<std::size_t>(j)];
    if (a.name != b.name || a.parent != b.parent || a.channels != b.channels || a.offset != b.offset || a.end_site != b.end_site)
      finding("round trip changed a joint");
  }
  if (again.frame_time != motion.frame_time) finding("round trip changed the frame time");
  if (again.values != motion.values) finding("round trip changed a value");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    checkRoundTrip(motionstyle::parseBvh(text, "fuzz.bvh"));
  } catch (const motionstyle::InputError& error) {
    if (error.file().empty() || error.line() < 0) finding("InputError without a file or with a negative line");
    // A clean rejection: the expected outcome for most inputs.
  }
  return 0;
}
