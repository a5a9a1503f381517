// motionstyle-cli train-style: trains one style network against a loss network.
#include <cmath>

#include "cli_args.h"
#include "commands.h"
#include "progress_bar.h"
#include "training_command.h"
#include "style/training.h"

namespace motionstyle::cli {
namespace {

// "content=1,style=100,foot=F,bone=B,traj=R": any subset, any order; unnamed terms keep the
// nn::LossWeights defaults (transformation_objective.h).
nn::LossWeights parseWeights(const std::string& text) {
  nn::LossWeights weights;
  for (const auto& [name, value] : parseNamedNumbers(text, "--weights")) {
    if (!(value >= kLossWeightRange.min && value <= kLossWeightRange.max))
      throw UsageError("--weights: " + name + " must be in [0, 1e+06], got " + std::to_string(value));
    if (name == "content") weights.content = value;
    else if (name == "style") weights.style = value;
    else if (name == "foot") weights.foot = value;
    else if (name == "bone") weights.bone = value;
    else if (name == "traj" || name == "trajectory") weights.trajectory = value;
    else throw UsageError("--weights: unknown term '" + name + "' (content, style, foot, bone, traj)");
  }
  return weights;
}

}  // namespace

int runTrainStyle(const Args& args) {
  std::vector<OptionSpec> specs = trainingOptionSpecs();
  specs.push_back({"loss-network"});
  specs.push_back({"content", true, true});
  specs.push_back({"style", true, true});
  specs.push_back({"weights"});
  specs.push_back({"quick", false});
  const ParsedArgs parsed = parseArgs(args, specs);
  const bool quick = parsed.has("quick");
  if (quick && parsed.has("epochs")) throw UsageError("--quick is a number of epochs: give --quick or --epochs, not both");

  style::StyleTrainingJob job;
  style::StyleTrainingConfig& config = job.config;
  config.settings = trainingSettings(
      parsed, {1e-3, quick ? style::kQuickStyleEpochs : style::kFullStyleEpochs, style::defaultContentAugmentation()});
  config.loss_network = lossNetworkArgument(parsed);
  for (const std::string& content : parsed.values("content")) config.content.emplace_back(content);
  for (const std::string& content : parsed.positional) config.content.emplace_back(content);  // --content A B
  if (config.content.empty()) throw UsageError("train-style needs --content DIR (folders or .bvh files)");
  for (const std::string& style : parsed.values("style")) config.styles.push_back(style::parseStyleSource(style));
  if (config.styles.empty() && config.settings.init.empty())
    throw UsageError("train-style needs --style CLIP.bvh (or --style LABEL=CLIP.bvh), or --init NET to retrain NET "
                     "with the style targets it stores");
  if (auto weights = parsed.value("weights")) config.weights = parseWeights(*weights);
  config.shape.hidden = parsed.integer("hidden", config.shape.hidden, 1, 4096);

  return runTrainingWithProgress(job);
}

}  // namespace motionstyle::cli
