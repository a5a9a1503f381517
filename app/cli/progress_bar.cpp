#include "progress_bar.h"

#include "commands.h"

#include <signal.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli_args.h"

namespace motionstyle::cli {
namespace {

constexpr double kInteractiveInterval = 0.1;  // seconds between redraws on a terminal
constexpr double kPlainInterval = 5.0;        // seconds between status lines in a log
constexpr int kBarWidth = 24;

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4g", value);
  return buffer;
}

}  // namespace

ProgressBar::ProgressBar(std::ostream& out, bool interactive) : out_(out), interactive_(interactive) {}

bool ProgressBar::stdoutIsTerminal() { return ::isatty(STDOUT_FILENO) == 1; }

void ProgressBar::update(double fraction, const std::string& text, bool force) {
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_update_).count();
  if (!force && since < (interactive_ ? kInteractiveInterval : kPlainInterval)) return;
  last_update_ = now;
  std::string bar;
  if (fraction >= 0.0) {
    const int filled = static_cast<int>(std::lround(std::clamp(fraction, 0.0, 1.0) * kBarWidth));
    bar = "[" + std::string(static_cast<std::size_t>(filled), '#') +
          std::string(static_cast<std::size_t>(kBarWidth - filled), '.') + "] ";
    bar += std::to_string(static_cast<int>(std::floor(100.0 * std::clamp(fraction, 0.0, 1.0)))) + "% ";
  }
  const std::string full = bar + text;
  if (interactive_) {
    out_ << '\r' << full;
    if (full.size() < last_width_) out_ << std::string(last_width_ - full.size(), ' ');
    out_.flush();
    last_width_ = full.size();
    drawn_ = true;
  } else {
    out_ << full << '\n';
    out_.flush();
  }
}

void ProgressBar::line(const std::string& text) {
  if (interactive_ && drawn_) {
    out_ << '\r' << std::string(last_width_, ' ') << '\r';
    drawn_ = false;
    last_width_ = 0;
    last_update_ = {};  // redraw the bar at the next update
  }
  out_ << text << '\n';
  out_.flush();
}

void ProgressBar::finish() {
  if (interactive_ && drawn_) out_ << '\n';
  drawn_ = false;
  last_width_ = 0;
  out_.flush();
}

std::string formatDuration(double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) return "?";
  char buffer[32];
  if (seconds < 9.95) {
    std::snprintf(buffer, sizeof buffer, "%.1fs", seconds);
    return buffer;
  }
  const long total = std::lround(seconds);
  if (total < 60)
    std::snprintf(buffer, sizeof buffer, "%lds", total);
  else if (total < 3600)
    std::snprintf(buffer, sizeof buffer, "%ldm%02lds", total / 60, total % 60);
  else
    std::snprintf(buffer, sizeof buffer, "%ldh%02ldm", total / 3600, (total % 3600) / 60);
  return buffer;
}

std::string formatLosses(double total, const std::vector<style::NamedLoss>& terms) {
  std::string text = "total " + number(total);
  for (const style::NamedLoss& term : terms) text += "  " + term.name + " " + number(term.value);
  return text;
}

void TrainingReporter::operator()(const style::TrainingProgress& p) {
  using Phase = style::TrainingProgress::Phase;
  if (p.phase == Phase::Loading) {
    bar_.update(-1.0, p.message);
    return;
  }
  const std::string position = "epoch " + std::to_string(p.epoch) + "/" + std::to_string(p.epochs);
  if (p.phase == Phase::EpochEnd) {
    bar_.line(position + "  " + formatLosses(p.total, p.terms) + "  (" + formatDuration(p.elapsed_seconds) +
              " elapsed, ETA " + formatDuration(p.eta_seconds) + ")");
    return;
  }
  const double steps_total = static_cast<double>(p.epochs) * p.steps_per_epoch;
  const double steps_done = static_cast<double>(p.epoch - 1) * p.steps_per_epoch + p.step;
  bar_.update(steps_total > 0 ? steps_done / steps_total : -1.0,
              position + " step " + std::to_string(p.step) + "/" + std::to_string(p.steps_per_epoch) + "  ETA " +
                  formatDuration(p.eta_seconds) + "  " + formatLosses(p.total, p.terms));
}

namespace {

std::atomic<bool> g_interrupted{false};
struct sigaction g_previous {};

extern "C" void onInterrupt(int) {
  if (g_interrupted.load()) {
    ::signal(SIGINT, SIG_DFL);  // second Ctrl-C: die now
    ::raise(SIGINT);
    return;
  }
  g_interrupted.store(true);
}

}  // namespace

InterruptGuard::InterruptGuard() {
  static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");
  g_interrupted.store(false);
  struct sigaction action {};
  action.sa_handler = onInterrupt;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, &g_previous);
}

InterruptGuard::~InterruptGuard() { ::sigaction(SIGINT, &g_previous, nullptr); }

const std::atomic<bool>* InterruptGuard::flag() const { return &g_interrupted; }

bool InterruptGuard::interrupted() const { return g_interrupted.load(); }

void applyThreadOption(int threads) {
  if (threads < 1 || threads > 8) throw UsageError("--threads must be between 1 and 8");
  ::setenv("MOTIONSTYLE_NN_THREADS", std::to_string(threads).c_str(), 1);
}

std::vector<OptionSpec> trainingOptionSpecs() {
  return {{"out"},     {"epochs"},     {"seed"},    {"batch"},          {"lr"},   {"lr-schedule"}, {"clip"}, {"threads"},
          {"resume", false}, {"init"},    {"checkpoint"}, {"holdout"}, {"skip-bad", false}, {"unit"}, {"hidden"}, {"augment"},
          {"keep-checkpoints", false}};
}

std::vector<std::pair<std::string, double>> parseNamedNumbers(const std::string& text, const std::string& option) {
  std::vector<std::pair<std::string, double>> pairs;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, end - start);
    const std::size_t equals = item.find('=');
    if (equals == std::string::npos || equals == 0 || equals + 1 == item.size())
      throw UsageError(option + " expects NAME=NUMBER pairs separated by commas, got '" + item + "'");
    const std::optional<double> value = parseDecimal(std::string_view(item).substr(equals + 1));
    if (!value) throw UsageError(option + ": '" + item + "' is not NAME=NUMBER");
    pairs.emplace_back(item.substr(0, equals), *value);
    start = end + 1;
  }
  return pairs;
}

namespace {

// "off", "on" (the command's default) or any of girdle=DEG,offsets=DEG,proportions=J,warp=W,
// mirror=P over the command's default.
style::AugmentationOptions parseAugmentation(const std::string& text, const style::AugmentationOptions& defaults) {
  if (text == "off") return {};
  style::AugmentationOptions options = defaults;
  if (text == "on") return options;
  for (const auto& [name, value] : parseNamedNumbers(text, "--augment")) {
    if (name == "girdle") options.girdle_offset_degrees = value;
    else if (name == "offsets") options.offset_degrees = value;
    else if (name == "proportions") options.proportion_jitter = value;
    else if (name == "warp") options.time_warp = value;
    else if (name == "mirror") options.mirror_probability = value;
    else throw UsageError("--augment: unknown setting '" + name + "' (girdle, offsets, proportions, warp, mirror)");
  }
  try {
    options.validate();
  } catch (const std::invalid_argument& error) {
    throw UsageError(std::string("--augment: ") + error.what());
  }
  return options;
}

}  // namespace

style::TrainingSettings trainingSettings(const ParsedArgs& parsed, const TrainingDefaults& defaults) {
  style::TrainingSettings settings;
  settings.augmentation = defaults.augmentation;
  settings.output = parsed.required("out");
  settings.epochs = parsed.integer("epochs", defaults.epochs, 1, kMaxEpochs);
  settings.seed = static_cast<std::uint32_t>(parsed.integer("seed", 1, 0, std::numeric_limits<int>::max()));
  settings.batch_size = parsed.integer("batch", settings.batch_size, 1, 4096);
  settings.learning_rate = parsed.number("lr", defaults.learning_rate, kLearningRateRange);
  if (auto schedule = parsed.value("lr-schedule")) {
    if (*schedule == "cosine")
      settings.schedule = style::LearningRateSchedule::Cosine;
    else if (*schedule == "constant")
      settings.schedule = style::LearningRateSchedule::Constant;
    else
      throw UsageError("--lr-schedule must be cosine or constant, not '" + *schedule + "'");
  }
  settings.gradient_clip = parsed.number("clip", settings.gradient_clip, {0.0, 1000.0});
  if (parsed.has("threads")) {
    settings.threads = parsed.integer("threads", 0);
    applyThreadOption(settings.threads);
  }
  settings.resume = parsed.has("resume");
  if (auto init = parsed.value("init")) settings.init = resolveNetworkArgument(*init);  // "elderly": shipped
  if (settings.resume && !settings.init.empty()) throw UsageError("--resume and --init exclude each other");
  if (auto checkpoint = parsed.value("checkpoint")) settings.checkpoint = *checkpoint;
  settings.keep_checkpoint = parsed.has("keep-checkpoints");
  settings.holdout_every = parsed.integer("holdout", 0, 0, 1000000);
  if (settings.holdout_every < 0 || settings.holdout_every == 1) throw UsageError("--holdout must be >= 2");
  if (parsed.has("skip-bad")) settings.dataset.bad_files = style::BadFilePolicy::Skip;
  settings.dataset.features.unit = lengthUnit(parsed);
  if (auto augment = parsed.value("augment")) settings.augmentation = parseAugmentation(*augment, defaults.augmentation);
  return settings;
}

int reportTraining(const style::TrainingResult& result, const style::TrainingSettings& settings, const InterruptGuard& guard,
                   ProgressBar& bar) {
  bar.finish();
  for (const auto& file : result.held_out_files) bar.line("held out: " + file.string());
  if (result.status == style::TrainingStatus::Cancelled) {
    bar.line(std::string(guard.interrupted() ? "interrupted" : "cancelled") + " after " +
             std::to_string(result.epochs_completed) + " epoch(s); " +
             (result.epochs_completed > 0 ? "the last checkpoint is " + settings.checkpointPath().string() +
                                                " (continue with --resume)"
                                          : std::string("no checkpoint was written")));
    return kInterruptedExitCode;
  }
  bar.line("wrote " + settings.output.string() + ": " + std::to_string(result.epochs_completed) + " epochs in " +
           formatDuration(result.seconds) + (result.history.empty() ? std::string() : ", final " +
           formatLosses(result.history.back().total, result.history.back().terms)));
  return 0;
}

}  // namespace motionstyle::cli

