#pragma once
// The output step shared by stylize and transfer: the stylized targets become OUT.bvh.
// By default through the IK clean-up, on the content's own skeleton at its own frame rate;
// with --no-cleanup as the raw positions of the 21 canonical joints (60 fps). --metrics writes the
// quality figures (before and after clean-up) as JSON.

#include <filesystem>
#include <limits>
#include <optional>
#include <nlohmann/json.hpp>
#include <ostream>

#include "cli_args.h"
#include "common/output_paths.h"
#include "style/familiarity.h"
#include "style/stylizer.h"

// The --help lines of those options (a literal, so command tables can concatenate it).
#define MOTIONSTYLE_OUTPUT_OPTIONS_HELP                                                                   \
  "  --no-cleanup    skip the IK clean-up: OUT holds the raw positions of the 21 canonical joints at\n" \
  "                  60 fps (default: a clean clip on IN's own skeleton and frame rate, feet locked\n"   \
  "                  during contact, bone lengths exact, feet on the floor)\n"                          \
  "  --metrics FILE  write quality figures (foot skate, floor penetration, bone error, residual,\n"    \
  "                  jerk) of the raw output and of the cleaned clip, the input's familiarity and the\n" \
  "                  output's path against the input's as JSON\n"                                       \
  "  --fps N         output frame rate (default: IN's own)\n"                                         \
  "  --path P        content (default): the output keeps IN's root path and timing; style: the style\n" \
  "                  may change the pace and the path\n"                                                \
  MOTIONSTYLE_TIME_LIMIT_HELP

// --time-limit, shared with cleanup.
#define MOTIONSTYLE_TIME_LIMIT_HELP                                                                     \
  "  --time-limit S  stop the clean-up after S seconds: frames past it keep their first guess and are\n" \
  "                  named in a warning (default: no limit, every frame is solved)\n"

namespace motionstyle::cli {

struct OutputOptions {
  bool cleanup = true;
  style::PathMode path = style::PathMode::Content;  // applied by the caller when stylizing
  std::optional<std::filesystem::path> metrics;  // JSON report
  double fps = 0.0;                              // output frame rate; 0 = the content's own
  // --time-limit: the clean-up's wall-clock budget (CleanupOptions::max_total_seconds); none by default.
  double time_limit_seconds = std::numeric_limits<double>::infinity();
  // Threads of the clean-up (CleanupOptions::threads; 0: every hardware thread). Batch mode gives
  // each clip one: --jobs says how many cores work.
  int cleanup_threads = 0;
  nlohmann::ordered_json extra_metrics = nlohmann::ordered_json::object();  // added to --metrics
};

// A familiarity reading as JSON: mean_cm, worst_second_cm, level, summary and, with `per_frame`,
// per_frame_cm (one shape for info, stylize --metrics and transfer --metrics).
nlohmann::ordered_json familiarityJson(const style::Familiarity& familiarity, bool per_frame);

// --time-limit S: > 0 and finite, else UsageError; infinity when absent.
double timeLimitOption(const ParsedArgs& parsed);

// Reads --no-cleanup, --metrics FILE, --fps N, --path P and --time-limit S from parsed arguments (declare them with
// outputOptionSpecs).
OutputOptions outputOptions(const ParsedArgs& parsed);
std::vector<OptionSpec> outputOptionSpecs();

// OUT (--out) and the --metrics file, for checkOutputPaths before any work starts.
std::vector<NamedPath> outputPaths(const OutputOptions& options, const std::filesystem::path& output);

// Writes OUT and the --metrics file all or none (AtomicFileBatch).
// content_file: the clip that was stylized (read again for its full skeleton). `familiarity`, when
// given, is printed and goes into the metrics.
void writeStylizedOutput(const std::filesystem::path& content_file, const style::StylizedClip& stylized,
                         const OutputOptions& options, const std::filesystem::path& output, std::ostream& log,
                         const style::Familiarity* familiarity = nullptr);

}  // namespace motionstyle::cli
