// motionstyle-cli eval: the JSON evaluation report of a style network on clips it never trained on.
#include <iostream>

#include "cli_args.h"
#include "commands.h"
#include "common/atomic_file.h"
#include "common/output_paths.h"
#include "style/evaluation.h"
#include "style/familiarity.h"
#include "style/motion_dataset.h"
#include "style/style_pairing.h"
#include "style/training.h"

namespace motionstyle::cli {

int runEval(const Args& args) {
  const ParsedArgs parsed = parseArgs(args, {{"ae"}, {"net"}, {"style", true, true}, {"json"}, {"unit"}, {"path"}});
  if (parsed.positional.empty()) throw UsageError("eval needs the clips to evaluate (files or folders)");
  style::DatasetOptions dataset;
  dataset.features.unit = lengthUnit(parsed);
  const std::filesystem::path ae_file = resolveNetworkArgument(parsed.required("ae"));
  const std::filesystem::path net_file = resolveNetworkArgument(parsed.required("net"));
  std::vector<NamedPath> read = {{ae_file, "--ae"}, {net_file, "--net"}};
  for (const std::string& clip : parsed.positional) read.push_back({clip, "an evaluated clip"});
  for (const std::string& style : parsed.values("style")) read.push_back({style::parseStyleSource(style).file, "--style"});
  if (auto file = parsed.value("json")) checkOutputPaths(read, {{*file, "--json"}});
  const nn::AutoencoderModel autoencoder = style::loadCompatibleAutoencoder(ae_file, dataset.features);
  const nn::StyleModel network = style::loadCompatibleStyleModel(net_file, dataset.features);

  std::vector<style::StyleSource> sources;
  for (const std::string& style : parsed.values("style")) sources.push_back(style::parseStyleSource(style));
  if (sources.empty()) throw UsageError("eval needs --style CLIP.bvh (the style clip to measure against)");
  const style::DatasetOptions style_options = style::styleClipOptions(dataset, network.loss_network.shape().width);
  std::vector<style::MotionClip> styles;
  for (const style::StyleSource& source : sources) styles.push_back(style::loadMotionClip(source.file, style_options));

  std::vector<std::filesystem::path> inputs(parsed.positional.begin(), parsed.positional.end());
  const std::vector<style::MotionClip> clips = style::loadMotionClips(inputs, dataset);
  std::vector<std::string> labels;
  for (const style::MotionClip& clip : clips) labels.push_back(clip.labels.content);
  const std::vector<int> pairing = style::pairStyles(labels, sources);

  style::PathMode path = style::PathMode::Content;
  if (auto value = parsed.value("path")) {
    const std::optional<style::PathMode> mode = style::parsePathMode(*value);
    if (!mode) throw UsageError("--path must be content or style, not '" + *value + "'");
    path = *mode;
  }
  style::EvaluationReport report = style::evaluateStyleNetwork(autoencoder, network, clips, styles, pairing, path);
  report.autoencoder_file = ae_file.string();
  report.network_file = net_file.string();
  const std::string json = style::evaluationJson(report);
  if (auto file = parsed.value("json")) {
    writeFileAtomically(*file, json);
    const style::ClipEvaluation& m = report.mean;
    std::cout << "evaluated " << clips.size() << " clip(s), " << m.frames << " frames: style distance "
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
