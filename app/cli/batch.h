#pragma once
// Batch mode of motionstyle-cli stylize and cleanup: several clips (files, and folders searched for
// .bvh files below them) into one output folder, on several threads, under one progress bar.
//
//   motionstyle-cli cleanup A.bvh B.bvh mocap/ --out cleaned/ [--metrics reports/] [--jobs N]
//
// Each clip is written to <out>/<its path below the folder it was found in> (a file given by name:
// <out>/<its name>), its metrics to <metrics>/<the same path>.json. Everything is checked before the
// first clip starts (prepareBatchOutputs: no output is an input, or inside an input folder, or
// another clip's output). A clip that fails is reported at the end and does not stop the others.
// Exit code: 0 all written; 2 some failed on their input or output; 1 some failed otherwise (an
// internal error); 130 after Ctrl-C (the clips being written finish; no new one starts).

#include <filesystem>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cli_args.h"
#include "common/output_paths.h"

// The --help lines of batch mode (a literal, so command tables can concatenate it).
#define MOTIONSTYLE_BATCH_HELP                                                                          \
  "\nSeveral clips, or folders (every .bvh below them): OUT is a folder, each clip is written to\n"     \
  "OUT/<its path below its folder> (--metrics FOLDER likewise, .json), on --jobs N cores, one clip\n"   \
  "per core (default: every core), under one progress bar. A clip that fails is reported at the end\n" \
  "without stopping the others (exit 2); no output may be an input.\n"

namespace motionstyle::cli {

struct BatchItem {
  std::filesystem::path input;
  std::filesystem::path output;
  std::optional<std::filesystem::path> metrics;
};

// True when the command's clips ask for batch mode: more than one, or a folder.
bool isBatch(const std::vector<std::string>& inputs);

// The clips of `inputs` and where each goes (see the top of this file). A folder's search skips the
// output and metrics folders when they lie inside it, so a second run into shots/cleaned/ takes the
// same clips as the first. InputError naming an input that does not exist or a folder without clips;
// UsageError when --out (or --metrics) names an existing file. Creates nothing.
std::vector<BatchItem> batchItems(const std::vector<std::string>& inputs, const std::filesystem::path& out_folder,
                                  const std::optional<std::filesystem::path>& metrics_folder);

// Creates the output folders, then checkOutputPaths over every item: the clips and `extra_inputs` (a
// mapping file, a network) against every output. On failure the folders it created are removed
// again: a command that never starts leaves nothing behind.
void prepareBatchOutputs(const std::vector<BatchItem>& items, const std::vector<NamedPath>& extra_inputs);

// --jobs N: at least 1, at most 64; default: the machine's hardware threads.
int jobsOption(const ParsedArgs& parsed);

// One clip's work: writes item.output (and item.metrics) and returns its summary lines. Throws on
// failure (the message names the file).
using BatchWork = std::function<std::string(const BatchItem& item)>;

// Runs `work` for every item on `jobs` threads (at most one per item), prints each clip's summary as
// it finishes above a progress bar with ETA on `out`, then every failure on stderr. Returns the exit
// code above.
// `command` names the command in those messages (failure_report.h, the CLI's one translation).
int runBatch(const std::vector<BatchItem>& items, int jobs, const BatchWork& work, const std::string& command,
             std::ostream& out);

}  // namespace motionstyle::cli
