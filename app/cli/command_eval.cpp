// motionstyle-cli eval: the JSON evaluation report of a style network on clips it never trained on
// (style::EvaluationJob).
#include <iostream>

#include "cli_args.h"
#include "commands.h"
#include "common/atomic_file.h"
#include "common/output_paths.h"
#include "style/evaluation_job.h"
#include "style/familiarity.h"
#include "style/training.h"

namespace motionstyle::cli {

int runEval(const Args& args) {
  const ParsedArgs parsed = parseArgs(args, {{"loss-network"}, {"net"}, {"style", true, true}, {"json"}, {"unit"}, {"path"}, {"refine-steps"}});
  if (parsed.positional.empty()) throw UsageError("eval needs the clips to evaluate (files or folders)");
  style::DatasetOptions dataset;
  dataset.features.unit = lengthUnit(parsed);
  const std::filesystem::path loss_network_file = lossNetworkArgument(parsed);
  const std::filesystem::path net_file = resolveNetworkArgument(parsed.required("net"));
  std::vector<NamedPath> read = {{loss_network_file, "--loss-network"}, {net_file, "--net"}};
  for (const std::string& clip : parsed.positional) read.push_back({clip, "an evaluated clip"});
  for (const std::string& style : parsed.values("style")) read.push_back({style::parseStyleSource(style).file, "--style"});
  if (auto file = parsed.value("json")) checkOutputPaths(read, {{*file, "--json"}});
  style::EvaluationJob job;
  job.loss_network = style::loadCompatibleLossNetwork(loss_network_file, dataset.features);
  job.network = style::loadCompatibleStyleModel(net_file, dataset.features);
  for (const std::string& style : parsed.values("style")) job.styles.push_back(style::parseStyleSource(style));
  if (job.styles.empty()) throw UsageError("eval needs --style CLIP.bvh (the style clip to measure against)");
  job.clips.assign(parsed.positional.begin(), parsed.positional.end());
  job.dataset = dataset;
  if (auto value = parsed.value("path")) {
    const std::optional<style::PathMode> mode = style::parsePathMode(*value);
    if (!mode) throw UsageError("--path must be content or style, not '" + *value + "'");
    job.path = *mode;
  }
  job.refinement.iterations =
      parsed.integer("refine-steps", job.refinement.iterations, 0, style::StyleRefinement::kMaxIterations);
  style::EvaluationReport report = job.run();
  report.loss_network_file = loss_network_file.string();
  report.network_file = net_file.string();
  const std::string json = style::evaluationJson(report);
  if (auto file = parsed.value("json")) {
    writeFileAtomically(*file, json);
    const style::ClipEvaluation& m = report.mean;
    std::cout << "evaluated " << report.clips.size() << " clip(s), " << m.frames << " frames: style distance "
              << m.style_distance_before << " -> " << m.style_distance_after << " (projection alone "
              << m.style_distance_projection << "), content distance "
              << m.content_distance_before << " -> " << m.content_distance_after << ", reconstruction "
              << m.reconstruction_joint_error_cm << " cm ("
              << style::familiarityName(style::familiarityLevel(m.reconstruction_joint_error_cm))
              << "), the network's own path covers " << m.network_path_distance_ratio
              << " x the content's distance, bone error " << m.bone_error_cm_output
              << " cm, foot skate " << m.foot_skate_cm_s_output << " cm/s\nwrote " << *file << "\n";
  } else {
    std::cout << json;
  }
  return 0;
}

}  // namespace motionstyle::cli
