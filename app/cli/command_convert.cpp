// motionstyle-cli convert IN OUT [--fps N]: read, resample, write (atomically).
#include <iostream>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "cli_args.h"
#include "commands.h"
#include "common/output_paths.h"
#include "motion/resample.h"

namespace motionstyle::cli {

int runConvert(const Args& args) {
  const ParsedArgs parsed = parseArgs(args, {{"fps"}});
  if (parsed.positional.size() != 2) throw UsageError("convert needs IN and OUT");
  checkOutputPaths({{parsed.positional[0], "IN"}}, {{parsed.positional[1], "OUT"}});
  const double fps = parsed.number("fps", 0.0, kOutputFpsRange);
  // A skeleton-only file (Frames: 0) converts as it is; resampling needs motion.
  Motion motion = readBvh(parsed.positional[0], parsed.has("fps") ? 1 : 0);
  if (parsed.has("fps")) {
    requireResampleableTo(motion, fps);
    motion = resampleMotion(motion, fps);
  }
  writeBvh(motion, parsed.positional[1]);
  std::cout << "wrote " << parsed.positional[1] << ": " << motion.frameCount() << " frames at " << motion.fps()
            << " fps\n";
  return 0;
}

}  // namespace motionstyle::cli
