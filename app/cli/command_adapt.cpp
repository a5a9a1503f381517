// motionstyle-cli adapt: fine-tunes the loss network on the user's own clips (style/adaptation.h).
#include <cstdio>
#include <iostream>

#include "cli_args.h"
#include "commands.h"
#include "common/output_paths.h"
#include "progress_bar.h"
#include "style/adaptation.h"
#include "style/training.h"
#include "style/training_state.h"

namespace motionstyle::cli {

int runAdapt(const Args& args) {
  const ParsedArgs parsed = parseArgs(args, {{"loss-network"}, {"data", true, true}, {"out"}, {"epochs"}, {"lr"}, {"seed"},
                                             {"replay", true, true}, {"replay-ratio"}, {"train-encoder", false},
                                             {"threads"}, {"skip-bad", false}, {"unit"}, {"checkpoint"},
                                             {"keep-checkpoints", false}, {"memory"}, {"memory-weight"}});
  style::AdaptationJob job;
  style::AdaptationSettings& settings = job.settings;
  settings.output = parsed.required("out");
  settings.epochs = parsed.integer("epochs", settings.epochs, 1, kMaxEpochs);
  settings.learning_rate = parsed.number("lr", settings.learning_rate, kLearningRateRange);
  settings.seed = static_cast<std::uint32_t>(parsed.integer("seed", 1, 0, std::numeric_limits<int>::max()));
  settings.replay_ratio = parsed.number("replay-ratio", settings.replay_ratio, {0.0, 100.0});
  settings.train_encoder = parsed.has("train-encoder");
  settings.memory_weight = parsed.number("memory-weight", settings.memory_weight, {0.0, 1000.0});
  if (auto checkpoint = parsed.value("checkpoint")) settings.checkpoint = *checkpoint;
  settings.keep_checkpoint = parsed.has("keep-checkpoints");
  if (parsed.has("threads")) applyThreadOption(parsed.integer("threads", 0));

  style::DatasetOptions dataset;
  dataset.features.unit = lengthUnit(parsed);
  if (parsed.has("skip-bad")) dataset.bad_files = style::BadFilePolicy::Skip;
  std::vector<std::filesystem::path> data;
  for (const std::string& value : parsed.values("data")) data.emplace_back(value);
  for (const std::string& value : parsed.positional) data.emplace_back(value);  // --data A B C
  if (data.empty()) throw UsageError("adapt needs --data with your clips (folders or .bvh files)");
  const std::filesystem::path loss_network_file = lossNetworkArgument(parsed);
  {  // before any work: the outputs can be written and none of them is an input
    const std::filesystem::path checkpoint = settings.checkpointPath();
    std::vector<NamedPath> inputs = {{loss_network_file, "--loss-network"}};
    for (const auto& value : data) inputs.push_back({value, "--data"});
    for (const std::string& value : parsed.values("replay")) inputs.push_back({value, "--replay"});
    if (const auto memory = parsed.value("memory"); memory && *memory != "none") inputs.push_back({*memory, "--memory"});
    std::vector<NamedPath> outputs = {{settings.output, "--out"},
                                      {checkpoint, "the checkpoint"},
                                      {style::statePath(checkpoint), "the checkpoint's state"}};
    if (!settings.train_encoder) outputs.push_back({style::memoryFileBeside(settings.output), "the memory beside --out"});
    checkOutputPaths(inputs, outputs);
  }
  job.loss_network = style::loadCompatibleLossNetwork(loss_network_file, dataset.features);
  job.loss_network_name = loss_network_file.filename().string();

  InterruptGuard guard;
  ProgressBar bar(std::cout, ProgressBar::stdoutIsTerminal());
  std::vector<std::string> warnings;
  job.clips = style::loadMotionClips(data, dataset, &warnings, guard.flag());
  std::vector<std::filesystem::path> replay;
  for (const std::string& value : parsed.values("replay")) replay.emplace_back(value);
  if (!replay.empty()) {
    style::DatasetOptions replay_options = dataset;
    replay_options.bad_files = style::BadFilePolicy::Skip;
    replay_options.features.canonical_rig = false;  // as the loss network learnt them
    job.replay = style::loadMotionClips(replay, replay_options, &warnings, guard.flag());
  }
  for (const std::string& warning : warnings) bar.line("warning: " + warning);
  const std::string memory_choice = parsed.value("memory").value_or("");
  if (memory_choice == "none" || (memory_choice.empty() && settings.train_encoder)) {
    if (job.replay.empty())
      bar.line("note: no reconstruction memory and no --replay clips: the network may forget some of what it knew");
  } else if (!memory_choice.empty()) {  // asked for: it must fit
    if (settings.train_encoder) throw UsageError("--memory keeps the encoder: it cannot go with --train-encoder");
    job.memory = style::loadReconstructionMemory(memory_choice);
    try {
      job.memory->requireMatches(job.loss_network, memory_choice);
    } catch (const std::invalid_argument& error) {
      throw InputError(memory_choice, 0, error.what());
    }
  } else {  // the default: a memory beside the network, or the shipped one, that fits
    job.memory = style::findMatchingMemory(job.loss_network, loss_network_file);
    if (!job.memory && job.replay.empty())
      bar.line("note: no reconstruction memory fits this loss network and no --replay clips are given: it may "
               "forget some of what it knew (motionstyle-cli remember writes a memory)");
  }

  TrainingReporter reporter(bar);
  style::TrainingCallbacks callbacks;
  callbacks.progress = [&](const style::TrainingProgress& p) { reporter(p); };
  callbacks.log = [&](const std::string& text) { bar.line(text); };
  callbacks.cancel = guard.flag();
  const style::AdaptationResult result = job.run(callbacks);
  bar.finish();
  if (result.status == style::TrainingStatus::Cancelled) {
    std::cout << (guard.interrupted() ? "interrupted" : "cancelled") << ": nothing written; the last checkpoint is "
              << settings.checkpointPath().string() << "\n";
    return kInterruptedExitCode;
  }
  std::printf("familiarity of your clips (mean reconstruction error, cm): before -> after\n");
  for (const style::ClipFamiliarity& clip : result.clips)
    std::printf("  %-40s %5.2f -> %5.2f\n", clip.file.filename().string().c_str(), clip.before_cm, clip.after_cm);
  std::printf("  %-40s %5.2f -> %5.2f (%s -> %s)\n", "all clips", result.mean_before_cm, result.mean_after_cm,
              style::familiarityName(style::familiarityLevel(result.mean_before_cm)),
              style::familiarityName(style::familiarityLevel(result.mean_after_cm)));
  if (!result.memory_file.empty())
    std::printf("wrote %s, what it must not forget when adapted again (%s)\n", result.memory_file.string().c_str(),
                result.memory_after->description.c_str());
  std::printf("wrote %s in %s; retrain a style against it with\n  motionstyle-cli train-style --loss-network %s --init STYLE "
              "--content YOUR_CLIPS... --out STYLE_ADAPTED.net\n",
              settings.output.string().c_str(), formatDuration(result.seconds).c_str(), settings.output.string().c_str());
  return 0;
}

}  // namespace motionstyle::cli
