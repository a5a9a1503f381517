// motionstyle-cli transfer: the optimisation method (Holden et al. 2016) for one content clip and one
// style clip, no trained style network needed (style::OptimizationTransferJob). Output as stylize: the
// IK clean-up onto the content's skeleton unless --no-cleanup.
#include <iostream>

#include "cli_args.h"
#include "commands.h"
#include "stylized_output.h"
#include "progress_bar.h"
#include "style/optimization_transfer_job.h"
#include "style/training.h"

namespace motionstyle::cli {


int runTransfer(const Args& args) {
  const ParsedArgs parsed = parseArgs(args, {{"loss-network"},
                                             {"style"},
                                             {"out"},
                                             {"iterations"},
                                             {"constraint-iterations"},
                                             {"style-weight"},
                                             {"lr"},
                                             {"noise-start", false},
                                             {"unit"},
                                             {"no-cleanup", false},
                                             {"metrics"},
                                             {"fps"},
                                             {"path"}});
  const OutputOptions output_options = outputOptions(parsed);
  if (parsed.positional.size() != 1) throw UsageError("transfer needs exactly one input clip IN.bvh");
  style::OptimizationOptions options;
  options.iterations = parsed.integer("iterations", options.iterations, 0, 100000);
  options.constraint_iterations = parsed.integer("constraint-iterations", options.constraint_iterations, 0, 100000);
  options.style_weight = parsed.number("style-weight", options.style_weight, kLossWeightRange);
  options.learning_rate = parsed.number("lr", options.learning_rate, kLearningRateRange);
  options.start_from_noise = parsed.has("noise-start");
  options.path = output_options.path;
  style::DatasetOptions dataset;
  dataset.features.unit = lengthUnit(parsed);
  const std::filesystem::path output = parsed.required("out");
  const std::filesystem::path loss_network_file = lossNetworkArgument(parsed);
  const std::filesystem::path style_file = parsed.required("style");
  checkOutputPaths({{parsed.positional[0], "the input clip"}, {loss_network_file, "--loss-network"}, {style_file, "--style"}},
                   outputPaths(output_options, output));

  style::OptimizationTransferJob job;
  job.loss_network = style::loadCompatibleLossNetwork(loss_network_file, dataset.features);
  job.content = parsed.positional[0];
  job.style = style_file;
  job.options = options;
  job.dataset = dataset;

  InterruptGuard guard;
  ProgressBar bar(std::cout, ProgressBar::stdoutIsTerminal());
  const int total = options.iterations + options.constraint_iterations;
  style::OptimizationCallbacks callbacks;
  callbacks.cancel = guard.flag();
  callbacks.progress = [&](const style::OptimizationProgress& p) {
    const int done = (p.stage == "style" ? 0 : options.iterations) + p.iteration;
    const double eta = p.elapsed_seconds / done * (total - done);
    bar.update(static_cast<double>(done) / total,
               p.stage + " " + std::to_string(p.iteration) + "/" + std::to_string(p.iterations) + "  ETA " +
                   formatDuration(eta) + "  " +
                   formatLosses(p.total, {{"content", p.content}, {"style", p.style}, {"foot", p.foot},
                                          {"bone", p.bone}, {"trajectory", p.trajectory}}),
               done == total);
  };
  const style::OptimizationTransferJob::Result result = job.run(callbacks);
  bar.finish();
  if (result.cancelled) {
    std::cout << "interrupted: nothing written\n";
    return kInterruptedExitCode;
  }
  // How much style the optimisation added (eval's definitions), printed and in --metrics.
  const style::StyleDistances& distances = result.distances;
  std::cout << "optimised in " << formatDuration(result.seconds) << ": style distance " << distances.style_before
            << " -> " << distances.style_after << " (ratio " << distances.styleRatio() << "), content distance "
            << distances.content_after << "\n";
  OutputOptions with_distances = output_options;
  with_distances.extra_metrics = {{"style_distance", {{"before", distances.style_before},
                                                      {"after", distances.style_after},
                                                      {"ratio", distances.styleRatio()}}},
                                  {"content_distance", distances.content_after}};
  writeStylizedOutput(parsed.positional[0], *result.clip, with_distances, output, std::cout);
  return 0;
}

}  // namespace motionstyle::cli
