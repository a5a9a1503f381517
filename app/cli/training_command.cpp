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

template <typename Job>
int trainAndReport(const Job& job) {
  InterruptGuard guard;
  ProgressBar bar(std::cout, ProgressBar::stdoutIsTerminal());
  TrainingReporter reporter(bar);
  style::TrainingCallbacks callbacks;
  callbacks.progress = [&](const style::TrainingProgress& p) { reporter(p); };
  callbacks.log = [&](const std::string& text) { bar.line(text); };
  callbacks.cancel = guard.flag();
  // A divergence (TrainingDiverged, naming the kept checkpoint) goes to main's one translation.
  const typename Job::Result result = job.run(callbacks);
  return reportTraining(result, job.config.settings, guard, bar);
}

}  // namespace

int runTrainingWithProgress(const style::LossNetworkTrainingJob& job) {
  std::vector<NamedPath> inputs;
  for (const auto& data : job.config.data) inputs.push_back({data, "--data"});
  checkTrainingOutputs(job.config.settings, inputs);
  return trainAndReport(job);
}

int runTrainingWithProgress(const style::StyleTrainingJob& job) {
  std::vector<NamedPath> inputs = {{job.config.loss_network, "--loss-network"}};
  for (const auto& content : job.config.content) inputs.push_back({content, "--content"});
  for (const auto& style : job.config.styles) inputs.push_back({style.file, "--style"});
  checkTrainingOutputs(job.config.settings, inputs);
  return trainAndReport(job);
}

}  // namespace motionstyle::cli
