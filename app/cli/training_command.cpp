#include "training_command.h"

#include <iostream>

#include "progress_bar.h"

namespace motionstyle::cli {
namespace {

template <typename Config, typename Train>
int trainAndReport(const Config& config, Train train) {
  InterruptGuard guard;
  ProgressBar bar(std::cout, ProgressBar::stdoutIsTerminal());
  TrainingReporter reporter(bar);
  style::TrainingCallbacks callbacks;
  callbacks.progress = [&](const style::TrainingProgress& p) { reporter(p); };
  callbacks.log = [&](const std::string& text) { bar.line(text); };
  callbacks.cancel = guard.flag();
  try {
    const auto result = train(config, callbacks);
    return reportTraining(result, config.settings, guard, bar);
  } catch (const style::TrainingDiverged& error) {
    bar.finish();
    std::cerr << "error: " << error.what() << "\nthe last good checkpoint (if any) is kept: "
              << config.settings.checkpointPath().string() << "\n";
    return 1;
  }
}

}  // namespace

int runTrainingWithProgress(const style::AutoencoderTrainingConfig& config) {
  return trainAndReport(config, [](const style::AutoencoderTrainingConfig& c, const style::TrainingCallbacks& callbacks) {
    return style::trainAutoencoder(c, callbacks);
  });
}

int runTrainingWithProgress(const style::StyleTrainingConfig& config) {
  return trainAndReport(config, [](const style::StyleTrainingConfig& c, const style::TrainingCallbacks& callbacks) {
    return style::trainStyleNetwork(c, callbacks);
  });
}

}  // namespace motionstyle::cli
