#pragma once
// CLI support for the long commands (train-loss-network, train-style, transfer): progress display, Ctrl-C, and
// the options every training command shares.
//
// Progress:
//   On a terminal: one line redrawn in place (at most 10 times a second): a bar, the position, the ETA
//   and the loss terms; permanent lines (epoch summaries, notes) scroll above it.
//   Otherwise (a pipe, a log file, CI): plain lines only - every permanent line, plus a status line at
//   most every 5 seconds - so logs stay readable.

#include <atomic>
#include <chrono>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "cli_args.h"
#include "style/training.h"

namespace motionstyle::cli {

class ProgressBar {
 public:
  ProgressBar(std::ostream& out, bool interactive);
  ~ProgressBar() { finish(); }  // an error printed after it starts on a line of its own
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Whether stdout is a terminal (isatty).
  static bool stdoutIsTerminal();

  // fraction in [0, 1] (negative: unknown, no bar); text follows the bar. Throttled unless `force`.
  void update(double fraction, const std::string& text, bool force = false);
  // A permanent line.
  void line(const std::string& text);
  // Ends the in-place line (call before printing anything else).
  void finish();

 private:
  std::ostream& out_;
  bool interactive_;
  bool drawn_ = false;
  std::size_t last_width_ = 0;
  std::chrono::steady_clock::time_point last_update_{};
};

// "0.4s", "12s", "4m05s", "1h02m": tenths under 10 s, so that a sub-second run does not read "0s".
std::string formatDuration(double seconds);
// "total 0.0123  mse 0.0101  sparsity 0.0220" with 4 significant digits.
std::string formatLosses(double total, const std::vector<style::NamedLoss>& terms);

// Adapts training progress to a ProgressBar: the bar over all steps, a permanent line per epoch.
class TrainingReporter {
 public:
  explicit TrainingReporter(ProgressBar& bar) : bar_(bar) {}
  void operator()(const style::TrainingProgress& progress);

 private:
  ProgressBar& bar_;
};

// Ctrl-C during a long command: the first SIGINT sets `flag()` (the operation's cancellation flag), so
// training stops cleanly within a second with its last checkpoint intact; a second SIGINT kills the
// process as usual. The previous handler is restored on destruction.
class InterruptGuard {
 public:
  InterruptGuard();
  ~InterruptGuard();
  InterruptGuard(const InterruptGuard&) = delete;
  InterruptGuard& operator=(const InterruptGuard&) = delete;
  const std::atomic<bool>* flag() const;
  bool interrupted() const;
};

// Exit code of a command stopped by Ctrl-C (the shell convention, 128 + SIGINT).
constexpr int kInterruptedExitCode = 130;

// --threads T: sets MOTIONSTYLE_NN_THREADS so the nn compute pool starts with T threads. Must run before
// any network does (each command calls it first). UsageError unless 1 <= T <= 8.
void applyThreadOption(int threads);

// "a=1,b=2.5" as (name, number) pairs in order, for list options such as --weights and --augment.
// Throws UsageError naming `option` for an empty list or item, a missing name or number, or a number
// with trailing text ("style=1," and "style=1x" are errors, not "style=1").
std::vector<std::pair<std::string, double>> parseNamedNumbers(const std::string& text, const std::string& option);

// Options shared by train-loss-network and train-style (their specs, then the settings they give):
//   --out FILE --epochs N --seed S --batch B --lr LR --threads T --resume --init NET --checkpoint FILE
//   --holdout N --skip-bad --unit UNIT --hidden H
std::vector<OptionSpec> trainingOptionSpecs();
// Throws UsageError for out-of-range values.
// The command's defaults: `learning_rate` and `epochs` differ per network kind; `augmentation` is
// what --augment on means and what runs without --augment.
struct TrainingDefaults {
  double learning_rate = 1e-3;
  int epochs = 100;
  style::AugmentationOptions augmentation;
};
style::TrainingSettings trainingSettings(const ParsedArgs& parsed, const TrainingDefaults& defaults);

// Prints a finished training's outcome (held-out files, output or where the checkpoint is). Returns the
// exit code: 0 done, 130 cancelled by Ctrl-C (checkpoint kept).
int reportTraining(const style::TrainingResult& result, const style::TrainingSettings& settings, const InterruptGuard& guard,
                   ProgressBar& bar);

}  // namespace motionstyle::cli
