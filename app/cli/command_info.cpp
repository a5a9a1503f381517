// motionstyle-cli info FILE...: what MotionStyle reads from each BVH file. Every string read from a file
// is printed as safe text (common/text_safety.h), and the JSON is always valid UTF-8.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "bvh/bvh_reader.h"
#include "cli_args.h"
#include "commands.h"
#include "common/atomic_file.h"
#include "common/errors.h"
#include "common/output_paths.h"
#include "features/representation.h"
#include "mapping/canonical_joints.h"
#include "mapping/joint_mapping.h"
#include "mapping/mapping_file.h"
#include "common/resource_paths.h"
#include "common/text_safety.h"
#include "nn/network_file.h"
#include "style/familiarity.h"
#include "style/locomotion_kind.h"
#include "style/motion_dataset.h"
#include "style/reconstruction_memory.h"
#include "stylized_output.h"
#include "style/training.h"

namespace motionstyle::cli {
namespace {

struct ContactSummary {
  double fraction = 0.0;
  int segments = 0;
};

ContactSummary summarize(const Eigen::RowVectorXd& labels) {
  ContactSummary summary;
  if (labels.size() == 0) return summary;
  summary.fraction = labels.mean();
  for (Eigen::Index t = 0; t < labels.size(); ++t)
    if (labels[t] > 0.5 && (t == 0 || labels[t - 1] < 0.5)) ++summary.segments;
  return summary;
}

// The loss network that judges familiarity: --loss-network, else the shipped one when it is installed, else none.
struct LossNetwork {
  std::optional<nn::LossNetworkModel> model;
  std::string file;
  std::string problem;  // why the shipped loss network could not be used, if it could not
};

LossNetwork lossNetworkFor(const ParsedArgs& parsed) {
  LossNetwork loss;
  std::filesystem::path file;
  if (auto loss_network = parsed.value("loss-network")) {
    file = resolveNetworkArgument(*loss_network);
  } else if (auto resources = resourceDirectory()) {
    if (auto shipped = shippedNetworkFile(*resources, kShippedLossNetworkName)) file = *shipped;
  }
  if (file.empty()) return loss;
  FeatureOptions options;
  options.unit = lengthUnit(parsed);
  loss.file = file.string();
  try {
    loss.model = style::loadCompatibleLossNetwork(file, options);
  } catch (const InputError& error) {
    if (parsed.has("loss-network")) throw;  // the user's choice: their error
    loss.problem = error.what();  // the shipped one is broken: the clip's facts still count
  }
  return loss;
}

nlohmann::ordered_json describeClip(const std::string& path, const std::optional<std::string>& mapping_file,
                                    const std::optional<std::string>& unit, const LossNetwork& loss_network) {
  const Motion motion = readBvh(path);
  nlohmann::ordered_json info;
  info["file"] = path;
  int end_sites = 0;
  for (const Joint& joint : motion.skeleton.joints) end_sites += joint.end_site ? 1 : 0;
  info["joints"] = motion.skeleton.jointCount() - end_sites;
  info["end_sites"] = end_sites;
  info["channels"] = motion.skeleton.channelCount();
  info["frames"] = motion.frameCount();
  info["fps"] = motion.fps();
  info["duration_s"] = motion.durationSeconds();

  JointMapping mapping;
  try {
    mapping = mapping_file ? loadJointMapping(*mapping_file, motion.skeleton) : mapJoints(motion.skeleton, path);
  } catch (const InputError& error) {
    if (mapping_file) throw;  // the user's file (missing, malformed, not this rig): exit 2, as for cleanup
    info["mapping"] = {{"complete", false}, {"error", error.detail()}};
    return info;
  }
  nlohmann::ordered_json joints = nlohmann::ordered_json::object();
  for (int c = 0; c < kCanonicalJointCount; ++c)
    joints[std::string(canonicalJointName(static_cast<CanonicalJoint>(c)))] =
        motion.skeleton.joints[static_cast<size_t>(mapping.joints[static_cast<size_t>(c)])].name;
  info["mapping"] = {{"complete", true}, {"convention", mapping.convention}, {"joints", joints}};
  if (motion.frameCount() == 0) return info;  // a skeleton only: the up axis and the rest need motion

  FeatureOptions options;
  options.unit = unit;
  const MotionFeatures features = extractFeatures(motion, mapping, options);
  const SpaceConvention& convention = features.anchor.convention;
  info["up_axis"] = convention.up_axis;
  info["unit"] = {{"name", convention.unit}, {"cm_per_unit", convention.cm_per_unit}, {"guessed", convention.unit_guessed}};
  info["skeletal_height_cm"] = skeletalHeight(motion.skeleton, mapping) * convention.cm_per_unit;
  info["rest_pose_frames"] = features.anchor.rest_pose_frames;
  nlohmann::ordered_json contacts = nlohmann::ordered_json::object();
  for (int label = 0; label < kContactCount; ++label) {
    const ContactSummary summary = summarize(features.contacts.row(label));
    contacts[std::string(contactLabelName(label))] = {{"fraction", summary.fraction}, {"segments", summary.segments}};
  }
  info["contacts"] = {{"fps", features.anchor.fps}, {"labels", contacts}};
  info["locomotion"] = style::locomotionKind(features.values, features.contacts);  // what stylize aims at
  if (!loss_network.problem.empty()) info["familiarity"] = {{"error", loss_network.problem}};
  if (loss_network.model) {
    const style::Familiarity familiarity = style::measureFamiliarity(*loss_network.model, features.values);
    info["familiarity"] = {{"loss_network", loss_network.file}};
    info["familiarity"].update(familiarityJson(familiarity, /*per_frame=*/false));
  }
  return info;
}

// The value of a string field as safe text, for the terminal.
std::string text(const nlohmann::ordered_json& value) { return safeText(value.get<std::string>()); }

void printText(const nlohmann::ordered_json& info) {
  std::printf("%s\n", text(info["file"]).c_str());
  std::printf("  joints       %d (+%d end sites), %d channels\n", info["joints"].get<int>(), info["end_sites"].get<int>(),
              info["channels"].get<int>());
  std::printf("  frames       %d at %.4g fps (%.2f s)\n", info["frames"].get<int>(), info["fps"].get<double>(),
              info["duration_s"].get<double>());
  const auto& mapping = info["mapping"];
  if (!mapping["complete"].get<bool>()) {
    std::printf("  mapping      INCOMPLETE: %s\n", text(mapping["error"]).c_str());
    return;
  }
  if (!info.contains("up_axis")) {
    std::printf("  mapping      complete (%s)\n  motion       none (Frames: 0, a skeleton only): the up axis, unit, "
                "contacts and familiarity need frames\n", text(mapping["convention"]).c_str());
    return;
  }
  std::printf("  up axis      %s (detected)\n", text(info["up_axis"]).c_str());
  const auto& unit = info["unit"];
  std::printf("  unit         %s, 1 unit = %.4g cm (%s)\n", text(unit["name"]).c_str(),
              unit["cm_per_unit"].get<double>(), unit["guessed"].get<bool>() ? "guessed from the skeleton's size; override with --unit" : "given");
  std::printf("  skeletal height %.1f cm (hip-knee-ankle + hips-spine-chest-neck-head)\n", info["skeletal_height_cm"].get<double>());
  std::printf("  mapping      complete (%s):", text(mapping["convention"]).c_str());
  int column = 0;
  for (const auto& [canonical, joint] : mapping["joints"].items()) {
    std::printf("%s%s=%s", column++ % 4 == 0 ? "\n               " : "  ", canonical.c_str(), text(joint).c_str());
  }
  if (info["rest_pose_frames"].get<int>() > 0)
    std::printf("\n  rest pose    frame 0 is the rig's rest pose, not motion: stylizing and clean-up see the motion"
                "\n               continued over it and write it back as it is");
  std::printf("\n  contacts     at %.4g fps:", info["contacts"]["fps"].get<double>());
  for (const auto& [name, summary] : info["contacts"]["labels"].items())
    std::printf(" %s %.0f%% (%d)", name.c_str(), 100.0 * summary["fraction"].get<double>(), summary["segments"].get<int>());
  std::printf("\n  locomotion   %s (read from its contacts and turning: the style clip stylize aims at; --kind "
              "sets another)\n", style::locomotionKindText(info["locomotion"].get<std::string>()).c_str());
  if (info.contains("familiarity") && info["familiarity"].contains("error"))
    std::printf("  familiarity  unknown: %s\n", text(info["familiarity"]["error"]).c_str());
  else if (info.contains("familiarity"))
    std::printf("  familiarity  %s (worst second %.1f cm; loss network %s)\n",
                text(info["familiarity"]["summary"]).c_str(),
                info["familiarity"]["worst_second_cm"].get<double>(),
                text(info["familiarity"]["loss_network"]).c_str());
}

// Whether the file starts with `magic`: a network file "MSTYLNET" (core/nn/NETWORK_FORMAT.md), a
// reconstruction memory "MSRMEMORY" (style/reconstruction_memory.h); anything else is read as BVH.
bool startsWith(const std::string& path, std::string_view magic) {
  std::ifstream in(path, std::ios::binary);
  std::string head(magic.size(), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  return in.gcount() == static_cast<std::streamsize>(head.size()) && head == magic;
}
bool isNetworkFile(const std::string& path) { return startsWith(path, "MSTYLNET"); }
bool isMemoryFile(const std::string& path) { return startsWith(path, "MSRMEMORY"); }

std::string describeMemoryFile(const std::string& path) {
  const style::ReconstructionMemory memory = style::loadReconstructionMemory(path);  // validated
  char text[256];
  std::snprintf(text, sizeof text,
                "MotionStyle reconstruction memory (for adapt: what a loss network must go on reconstructing)\n"
                "  loss network: %d features, %d hidden units, width %d (encoder fingerprint %016llx)\n"
                "  remembers: %d clips, %.0f frames at 60 fps\n",
                memory.features, memory.hidden, memory.width, static_cast<unsigned long long>(memory.encoder_fingerprint),
                memory.clips, memory.frames);
  return std::string(text) + "  description: " + memory.description + "\n";
}

// --write-mapping: the automatic mapping of the clip's rig as a file to complete (mapping_file.h).
int writeMappingTemplate(const std::string& clip, const std::filesystem::path& out) {
  checkOutputPaths({{clip, "the clip"}}, {{out, "--write-mapping"}});
  const Skeleton skeleton = readBvh(clip).skeleton;
  const JointMapping guess = guessJointMapping(skeleton);
  writeFileAtomically(out, formatJointMappingTemplate(guess, skeleton, std::filesystem::path(clip).filename().string()));
  const std::string missing = guess.missingNames();
  std::cout << "wrote " << safeText(out.string()) << ": the automatic mapping found "
            << kCanonicalJointCount - static_cast<int>(guess.missing().size()) << " of " << kCanonicalJointCount
            << " joints" << (missing.empty() ? "" : "; fill in " + missing) << ", then pass it with --mapping\n";
  return 0;
}

}  // namespace

int runInfo(const Args& args) {
  const ParsedArgs parsed = parseArgs(args, {{"json", false}, {"mapping"}, {"unit"}, {"loss-network"}, {"write-mapping"}});
  if (parsed.positional.empty()) throw UsageError("info needs at least one FILE");
  if (const std::optional<std::string> out = parsed.value("write-mapping")) {
    if (parsed.positional.size() != 1 || parsed.has("json") || parsed.has("mapping"))
      throw UsageError("--write-mapping takes one clip, without --json or --mapping");
    return writeMappingTemplate(parsed.positional[0], *out);
  }
  const std::optional<std::string> unit = lengthUnit(parsed);  // a usage error before any file is read
  std::optional<LossNetwork> loss_network;  // loaded on the first clip (network files need none)
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  std::vector<std::string> files;  // a folder: every .bvh below it, as stylize and cleanup take them
  for (const std::string& argument : parsed.positional) {
    std::error_code error;
    if (!std::filesystem::is_directory(argument, error)) {
      files.push_back(argument);
      continue;
    }
    for (const std::filesystem::path& file : style::findBvhFiles({argument})) files.push_back(file.string());
  }
  for (const std::string& argument : files) {
    const std::string path = resolveNetworkArgument(argument).string();  // "elderly": a shipped network
    const bool network = isNetworkFile(path);
    if (network || isMemoryFile(path)) {
      const std::string description = network ? nn::describeNetworkFile(path) : describeMemoryFile(path);
      if (parsed.has("json"))
        all.push_back({{"file", safeText(path)}, {network ? "network" : "memory", safeLines(description)}});
      else
        std::cout << safeText(path) << "\n" << safeLines(description)
                  << (description.empty() || description.back() == '\n' ? "" : "\n");
      continue;
    }
    if (!loss_network) loss_network = lossNetworkFor(parsed);
    nlohmann::ordered_json info = describeClip(path, parsed.value("mapping"), unit, *loss_network);
    if (parsed.has("json"))
      all.push_back(std::move(info));
    else
      printText(info);
  }
  if (parsed.has("json"))  // "replace": a BVH joint name in Latin-1 becomes U+FFFD, not a type error
    std::cout << (all.size() == 1 ? all[0] : all).dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace)
              << "\n";
  return 0;
}

}  // namespace motionstyle::cli
