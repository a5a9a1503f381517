// motionstyle-cli stylize: a content clip through a trained style network (T, then the manifold
// projection), written as BVH.
//
// Two steps:
//   1. the clip's canonical joints in the style, in the clip's file space, with the content's foot
//      contacts, at the representation's 60 fps (the network loaded once for every clip);
//   2. writeStylizedOutput() (stylized_output.h): the IK clean-up onto the input's own skeleton, or
//      with --no-cleanup the raw canonical positions.
// Several clips or folders: batch mode (batch.h).
#include <chrono>
#include <iostream>
#include <memory>
#include <sstream>

#include "batch.h"
#include "bvh/bvh_writer.h"
#include "cli_args.h"
#include "commands.h"
#include "common/errors.h"
#include "ik/contact_file.h"
#include "nn/loss_network.h"
#include "style/motion_dataset.h"
#include "style/position_clip.h"
#include "style/familiarity.h"
#include "style/locomotion_kind.h"
#include "style/stylizer.h"
#include "style/training.h"
#include "stylized_output.h"

namespace motionstyle::cli {
namespace {

struct StylizeRequest {
  std::filesystem::path network;
  std::optional<std::filesystem::path> loss_network;  // checked against the network's own loss network
  double strength = 1.0;
  style::StyleRefinement refinement;  // --refine-steps
  std::string kind;                   // --kind: "" read from each clip
  style::DatasetOptions dataset;
  OutputOptions output;  // --path, --no-cleanup, --fps, --time-limit; --metrics per clip
};

// The style network, loaded and checked once for every clip.
std::shared_ptr<const style::Stylizer> loadStylizer(const StylizeRequest& request) {
  nn::StyleModel model = style::loadCompatibleStyleModel(request.network, request.dataset.features);
  if (request.loss_network) {
    const nn::LossNetworkModel loss_network = style::loadCompatibleLossNetwork(*request.loss_network, request.dataset.features);
    if (!nn::sameWeights(loss_network.network, model.loss_network))
      throw InputError(request.network.string(), 0,
                       "this style network was trained against another loss network than " +
                           request.loss_network->string() + " (it embeds its own; omit --loss-network to use it)");
  }
  return std::make_shared<const style::Stylizer>(std::move(model), request.network.string(), request.refinement);
}

// One clip: its familiarity, the stylized targets (60 fps), then the clean-up and OUT
// (writeStylizedOutput). Returns the report lines.
std::string stylizeFile(const style::Stylizer& stylizer, const StylizeRequest& request, const std::filesystem::path& input,
                        const std::filesystem::path& output, const std::optional<std::filesystem::path>& metrics) {
  const style::MotionClip clip = style::loadMotionClip(input, request.dataset);
  const style::Familiarity familiarity = style::measureFamiliarity(stylizer, clip.features.values);
  const auto start = std::chrono::steady_clock::now();
  const style::StylizedClip stylized =
      stylizer.stylize(clip.features, request.strength, request.output.path, request.kind);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ostringstream log;
  log << "stylized " << stylized.frameCount() << " frames (60 fps) at strength " << request.strength << " in "
      << seconds * 1000.0 << " ms (path: " << style::pathModeName(request.output.path)
      << ", refinement steps: " << (stylizer.refinementSteps() > 0 ? "up to " : "") << stylizer.refinementSteps()
      << ")\n";
  OutputOptions options = request.output;
  options.metrics = metrics;
  if (!stylized.kind.empty()) {
    const bool given = !request.kind.empty();
    log << "aimed at the style's " << style::locomotionKindText(stylized.kind)
        << (given ? " (--kind)" : " (read from the clip; --kind sets it)") << "\n";
    options.extra_metrics["style_target"] = {{"kind", stylized.kind}, {"from", given ? "--kind" : "clip"}};
  }
  writeStylizedOutput(input, stylized, options, output, log, &familiarity);
  std::string text = log.str();
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text;
}

}  // namespace

int runStylize(const Args& args) {
  std::vector<OptionSpec> specs = {{"loss-network"}, {"net"}, {"out"}, {"strength"}, {"refine-steps"}, {"kind"}, {"unit"}, {"jobs"}};
  for (const OptionSpec& spec : outputOptionSpecs()) specs.push_back(spec);
  const ParsedArgs parsed = parseArgs(args, specs);
  if (parsed.positional.empty()) throw UsageError("stylize needs an input clip IN.bvh (or several, or folders)");
  StylizeRequest request;
  request.output = outputOptions(parsed);
  request.network = resolveNetworkArgument(parsed.required("net"));
  if (auto loss_network = parsed.value("loss-network")) request.loss_network = resolveNetworkArgument(*loss_network);
  request.strength = parsed.number("strength", 1.0, {0.0, 1.0});
  request.refinement.iterations =
      parsed.integer("refine-steps", request.refinement.iterations, 0, style::StyleRefinement::kMaxIterations);
  if (auto kind = parsed.value("kind"); kind && *kind != "auto") {
    if (!style::isLocomotionKind(*kind))
      throw UsageError("--kind must be auto, " + style::locomotionKindList() + ", not '" + *kind + "'");
    request.kind = *kind;
  }
  request.dataset.features.unit = lengthUnit(parsed);
  const std::filesystem::path out = parsed.required("out");
  std::vector<NamedPath> networks = {{request.network, "--net"}};
  if (request.loss_network) networks.push_back({*request.loss_network, "--loss-network"});

  if (isBatch(parsed.positional)) {
    const std::vector<BatchItem> items = batchItems(parsed.positional, out, request.output.metrics);
    std::vector<NamedPath> extra = networks;
    for (const BatchItem& item : items) extra.push_back({contactTracksPath(item.input), "the clip's contact tracks"});
    prepareBatchOutputs(items, extra);
    const std::shared_ptr<const style::Stylizer> stylizer = loadStylizer(request);
    request.output.cleanup_threads = 1;  // --jobs says how many cores: one per clip
    return runBatch(items, jobsOption(parsed), [&](const BatchItem& item) {
      return stylizeFile(*stylizer, request, item.input, item.output, item.metrics);
    }, "stylize", std::cout);
  }
  const std::filesystem::path input = parsed.positional[0];
  std::vector<NamedPath> inputs = networks;
  inputs.insert(inputs.begin(), {input, "the input clip"});
  inputs.push_back({contactTracksPath(input), "the clip's contact tracks"});
  checkOutputPaths(inputs, outputPaths(request.output, out));
  const std::shared_ptr<const style::Stylizer> stylizer = loadStylizer(request);
  std::cout << stylizeFile(*stylizer, request, input, out, request.output.metrics) << "\n";
  return 0;
}

}  // namespace motionstyle::cli
