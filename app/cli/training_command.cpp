#include "training_command.h"

#include <iostream>

#include "common/output_paths.h"
#include "progress_bar.h"
#include "style/training_state.h"

namespace motionstyle::cli {
namespace {

// Before the first epoch (a failure after an hour of training helps nobody): --out and the checkpoint
// pair can be written, and none of them is an input.
void checkTrainingOutputs(const style::TrainingSettings& settings, std::vector<NamedPath> inputs) {
  if (!settings.init.empty()) inputs.push_back({settings.init, "--init"});
  std::vector<NamedPath> outputs;
  if (!settings.output.empty()) outputs.push_back({settings.output, "--out"});
  outputs.push_back({settings.checkpointPath(), "the checkpoint"});
  outputs.push_back({style::statePath(settings.checkpointPath()), "the checkpoint's state"});
  checkOutputPaths(inputs, outputs);
}

template <typename Config, typename Train>
int trainAndReport(const Config& config, Train train) {
  InterruptGuard guard;
  ProgressBar bar(std::cout, ProgressBar::stdoutIsTerminal());
  TrainingReporter reporter(bar);
  style::TrainingCallbacks callbacks;
  callbacks.progress = [&](const style::TrainingProgress& p) { reporter(p); };
  callbacks.log = [&](const std::string& text) { bar.line(text); };
  callbacks.cancel = guard.flag();
  // A divergence (TrainingDiverged, naming the kept checkpoint) goes to main's one translation.
  const auto result = train(config, callbacks);
  return reportTraining(result, config.settings, guard, bar);
}

}  // namespace

int runTrainingWithProgress(const style::AutoencoderTrainingConfig& config) {
  std::vector<NamedPath> inputs;
  for (const auto& data : config.data) inputs.push_back({data, "--data"});
  checkTrainingOutputs(config.settings, inputs);
  return trainAndReport(config, [](const style::AutoencoderTrainingConfig& c, const style::TrainingCallbacks& callbacks) {
    return style::trainAutoencoder(c, callbacks);
  });
}

int runTrainingWithProgress(const style::StyleTrainingConfig& config) {
  std::vector<NamedPath> inputs = {{config.autoencoder, "--ae"}};
  for (const auto& content : config.content) inputs.push_back({content, "--content"});
  for (const auto& style : config.styles) inputs.push_back({style.file, "--style"});
  checkTrainingOutputs(config.settings, inputs);
  return trainAndReport(config, [](const style::StyleTrainingConfig& c, const style::TrainingCallbacks& callbacks) {
    return style::trainStyleNetwork(c, callbacks);
  });
}

}  // namespace motionstyle::cli
