#include "commands.h"

namespace motionstyle::cli {

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {"info", "describe BVH files (joints, frames, fps, units, mapping, contacts)",
       "usage: motionstyle-cli info FILE... [--json] [--mapping MAP.json] [--unit UNIT]\n\n"
       "Prints what MotionStyle reads from each BVH file: joints, frames, frame rate, the up axis and\n"
       "length unit it assumed, the mapping to the 21 canonical joints, and a foot-contact summary.\n\n"
       "  --json            print JSON instead of text\n"
       "  --mapping FILE    use this joint-mapping JSON instead of the automatic mapping\n"
       "  --unit UNIT       the file's length unit: cm, m, mm, inch, ft, dm or cmu (default: guessed)\n",
       runInfo},
      {"convert", "read a BVH file, optionally resample it, write it",
       "usage: motionstyle-cli convert IN.bvh OUT.bvh [--fps N]\n\n"
       "Reads IN, resamples it to N frames per second if --fps is given (slerp for rotations, linear\n"
       "for positions), and writes OUT atomically with the same hierarchy and channel layout.\n",
       runConvert},
  };
  return table;
}

}  // namespace motionstyle::cli
