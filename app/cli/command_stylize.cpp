// motionstyle-cli stylize: a content clip through a trained style network (T, then the manifold
// projection), written as BVH.
//
// Two steps:
//   1. stylizedTargets(): the clip's canonical joints in the style, in the clip's file space, with the
//      content's foot contacts, at the representation's 60 fps;
//   2. writeStylizedOutput() (stylized_output.h): the IK clean-up onto the input's own skeleton, or
//      with --no-cleanup the raw canonical positions.
#include <chrono>
#include <iostream>

#include "bvh/bvh_writer.h"
#include "cli_args.h"
#include "commands.h"
#include "common/errors.h"
#include "nn/loss_network.h"
#include "style/motion_dataset.h"
#include "style/position_clip.h"
#include "style/familiarity.h"
#include "style/stylizer.h"
#include "style/training.h"
#include "stylized_output.h"

namespace motionstyle::cli {
namespace {

struct StylizeRequest {
  std::filesystem::path network;
  std::optional<std::filesystem::path> loss_network;  // checked against the network's own loss network
  std::filesystem::path input;
  double strength = 1.0;
  style::PathMode path = style::PathMode::Content;
  style::DatasetOptions dataset;
};

style::StylizedClip stylizedTargets(const StylizeRequest& request, double& seconds, style::Familiarity& familiarity) {
  nn::StyleModel model = style::loadCompatibleStyleModel(request.network, request.dataset.features);
  if (request.loss_network) {
    const nn::LossNetworkModel loss_network = style::loadCompatibleLossNetwork(*request.loss_network, request.dataset.features);
    if (!nn::sameWeights(loss_network.network, model.loss_network))
      throw InputError(request.network.string(), 0,
                       "this style network was trained against another loss network than " +
                           request.loss_network->string() + " (it embeds its own; omit --loss-network to use it)");
  }
  const style::MotionClip clip = style::loadMotionClip(request.input, request.dataset);
  familiarity = style::measureFamiliarity(model, clip.features.values);
  const style::Stylizer stylizer(std::move(model), request.network.string());
  const auto start = std::chrono::steady_clock::now();
  style::StylizedClip result = stylizer.stylize(clip.features, request.strength, request.path);
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

int runStylize(const Args& args) {
  std::vector<OptionSpec> specs = {{"loss-network"}, {"net"}, {"out"}, {"strength"}, {"unit"}};
  for (const OptionSpec& spec : outputOptionSpecs()) specs.push_back(spec);
  const ParsedArgs parsed = parseArgs(args, specs);
  const OutputOptions output_options = outputOptions(parsed);
  if (parsed.positional.size() != 1) throw UsageError("stylize needs exactly one input clip IN.bvh");
  StylizeRequest request;
  request.network = resolveNetworkArgument(parsed.required("net"));
  if (auto loss_network = parsed.value("loss-network")) request.loss_network = resolveNetworkArgument(*loss_network);
  request.input = parsed.positional[0];
  request.strength = parsed.number("strength", 1.0, {0.0, 1.0});
  request.path = output_options.path;
  request.dataset.features.unit = lengthUnit(parsed);
  const std::filesystem::path output = parsed.required("out");
  std::vector<NamedPath> inputs = {{request.input, "the input clip"}, {request.network, "--net"}};
  if (request.loss_network) inputs.push_back({*request.loss_network, "--loss-network"});
  checkOutputPaths(inputs, outputPaths(output_options, output));

  double seconds = 0;
  style::Familiarity familiarity;
  const style::StylizedClip clip = stylizedTargets(request, seconds, familiarity);
  std::cout << "stylized " << clip.frameCount() << " frames (60 fps) at strength " << request.strength << " in "
            << seconds * 1000.0 << " ms (path: " << style::pathModeName(request.path) << ")\n";
  writeStylizedOutput(request.input, clip, output_options, output, std::cout, &familiarity);
  return 0;
}

}  // namespace motionstyle::cli
