// motionstyle-cli remember: writes a loss network's reconstruction memory of its training clips
// (style/reconstruction_memory.h), which adapt then uses so that the network forgets nothing of them.
#include <chrono>
#include <cstdio>
#include <iostream>

#include "cli_args.h"
#include "commands.h"
#include "common/output_paths.h"
#include "progress_bar.h"
#include "style/reconstruction_memory.h"
#include "style/training.h"

namespace motionstyle::cli {

int runRemember(const Args& args) {
  const ParsedArgs parsed =
      parseArgs(args, {{"loss-network"}, {"data", true, true}, {"out"}, {"holdout"}, {"description"}, {"precision"}, {"threads"},
                       {"skip-bad", false}, {"unit"}});
  const std::filesystem::path output = parsed.required("out");
  const int holdout = parsed.integer("holdout", 0, 0, 1000000);
  const std::string precision_name = parsed.value("precision").value_or("f16");
  if (precision_name != "f16" && precision_name != "f32") throw UsageError("--precision must be f16 or f32, not '" + precision_name + "'");
  const nn::WeightPrecision precision = precision_name == "f16" ? nn::WeightPrecision::F16 : nn::WeightPrecision::F32;
  if (holdout == 1) throw UsageError("--holdout must be 0 (none) or every N >= 2");
  if (parsed.has("threads")) applyThreadOption(parsed.integer("threads", 0));
  std::vector<std::filesystem::path> data;
  for (const std::string& value : parsed.values("data")) data.emplace_back(value);
  for (const std::string& value : parsed.positional) data.emplace_back(value);
  if (data.empty()) throw UsageError("remember needs --data with the clips the loss network learnt from");
  const std::filesystem::path loss_network_file = lossNetworkArgument(parsed);
  {
    std::vector<NamedPath> inputs = {{loss_network_file, "--loss-network"}};
    for (const auto& value : data) inputs.push_back({value, "--data"});
    checkOutputPaths(inputs, {{output, "--out"}});
  }
  style::DatasetOptions dataset;
  dataset.features.unit = lengthUnit(parsed);
  dataset.features.canonical_rig = false;  // as the loss network learnt them (trainLossNetwork)
  if (parsed.has("skip-bad")) dataset.bad_files = style::BadFilePolicy::Skip;
  const nn::LossNetworkModel model = style::loadCompatibleLossNetwork(loss_network_file, dataset.features);

  InterruptGuard guard;
  const auto started = std::chrono::steady_clock::now();
  const style::HoldoutSplit split = style::splitHoldout(style::findBvhFiles(data), holdout);
  std::vector<std::string> warnings;
  const std::vector<style::MotionClip> clips = style::loadMotionClips(split.training, dataset, &warnings, guard.flag());
  for (const std::string& warning : warnings) std::cerr << "warning: " << warning << "\n";
  const std::string description =
      parsed.value("description").value_or(std::to_string(clips.size()) + " clips the loss network learnt from");
  try {
    const style::ReconstructionMemory memory = style::rememberReconstruction(model, clips, description, guard.flag());
    try {
      style::saveReconstructionMemory(memory, output, precision);
    } catch (const std::invalid_argument&) {  // a moment beyond f16's range: the exact values instead
      if (precision != nn::WeightPrecision::F16) throw;
      std::cerr << "note: some values are beyond f16's range: written as f32\n";
      style::saveReconstructionMemory(memory, output, nn::WeightPrecision::F32);
    }
    std::printf("wrote %s: the reconstruction memory of %d clips (%.0f frames at 60 fps; %zu held out) in %.1f s\n",
                output.string().c_str(), memory.clips, memory.frames, split.held_out.size(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  } catch (const OperationCancelled&) {
    std::cout << "interrupted: nothing written\n";
    return kInterruptedExitCode;
  }
  return 0;
}

}  // namespace motionstyle::cli
