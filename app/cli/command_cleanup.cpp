// motionstyle-cli cleanup IN.bvh --out OUT.bvh: the IK clean-up on a clip as it is (its own canonical
// joint positions are the targets): feet locked during contact, bone lengths exact, feet on the floor.
// Contacts come from --contacts FILE, else from the tracks saved beside the clip
// (IN.bvh.contacts.json, e.g. edited in the app), else are detected from height and speed.
// The solve and the metrics run at IN's own rate; --fps N resamples the cleaned clip for export only.
// Bad input is exit 2 before any solve: no frames (Frames: 0), a skeleton without height
// (requireMeasurableRestPose), --fps beyond 100x IN's rate, an unknown --unit.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "cli_args.h"
#include "commands.h"
#include "common/atomic_file.h"
#include "common/errors.h"
#include "common/output_paths.h"
#include "features/foot_contacts.h"
#include "features/representation.h"
#include "ik/cleanup.h"
#include "ik/contact_file.h"
#include "ik/metrics.h"
#include "mapping/mapping_file.h"
#include "motion/kinematics.h"
#include "motion/resample.h"
#include "stylized_output.h"

namespace motionstyle::cli {
namespace {

ClipMetrics measure(const Motion& motion, const JointMapping& mapping, const Eigen::MatrixXi& contacts,
                    const Eigen::MatrixXd* targets, const SpaceConvention& convention, double floor) {
  const Eigen::MatrixXd world = worldPositions(motion);
  MetricsInput input(world, mapping.joints, skeletonBones(motion.skeleton));
  input.contacts = contacts;
  if (targets) input.targets = *targets;
  input.up = convention.fileUp();
  input.floor_height = floor;
  input.cm_per_unit = convention.cm_per_unit;
  input.fps = motion.fps();
  return computeMetrics(input);
}

}  // namespace

int runCleanup(const Args& args) {
  const ParsedArgs parsed = parseArgs(args, {{"out"}, {"contacts"}, {"metrics"}, {"unit"}, {"mapping"}, {"fps"}, {"time-limit"}});
  if (parsed.positional.size() != 1) throw UsageError("cleanup needs exactly one input clip IN.bvh");
  const std::filesystem::path input_file = parsed.positional[0];
  const std::filesystem::path output = parsed.required("out");
  const double output_fps = parsed.number("fps", 0.0, kOutputFpsRange);  // 0: IN's own rate
  const std::optional<std::string> unit = lengthUnit(parsed);

  std::vector<NamedPath> inputs = {{input_file, "the input clip"}, {contactTracksPath(input_file), "the clip's contact tracks"}};
  if (auto contacts = parsed.value("contacts")) inputs.push_back({*contacts, "--contacts"});
  if (auto mapping = parsed.value("mapping")) inputs.push_back({*mapping, "--mapping"});
  std::vector<NamedPath> outputs = {{output, "--out"}};
  if (auto metrics = parsed.value("metrics")) outputs.push_back({*metrics, "--metrics"});
  checkOutputPaths(inputs, outputs);

  const Motion motion = readBvh(input_file, /*minimum_frames=*/1);
  if (output_fps > 0.0) requireResampleableTo(motion, output_fps);
  const JointMapping mapping = mapJoints(motion.skeleton, input_file.string(),
                                         parsed.value("mapping") ? std::optional<std::filesystem::path>(*parsed.value("mapping"))
                                                                 : std::nullopt);
  const Eigen::MatrixXd world = worldPositions(motion);
  requireMeasurableRestPose(motion, mapping);
  const SpaceConvention convention = detectSpaceConvention(motion.skeleton, world, mapping, unit);
  const Eigen::Vector3d up = convention.fileUp();
  const std::array<int, kContactCount> feet = contactJoints(mapping);
  const double floor = estimateFloorHeight(world, feet, up);

  Eigen::MatrixXi contacts;
  std::optional<std::filesystem::path> tracks_file;
  if (auto given = parsed.value("contacts")) tracks_file = *given;
  else if (std::filesystem::exists(contactTracksPath(input_file))) tracks_file = contactTracksPath(input_file);
  if (tracks_file) {
    const ContactTracks tracks = loadContactTracks(*tracks_file);
    if (tracks.labels.rows() != motion.frameCount())
      throw InputError(tracks_file->string(), 0,
                       "contact tracks have " + std::to_string(tracks.labels.rows()) + " frames, the clip " +
                           std::to_string(motion.frameCount()));
    contacts = tracks.labels;
    std::cout << "contacts from " << tracks_file->string() << "\n";
  } else {
    contacts = detectContacts(world, feet, up, floor, motion.fps(), restPoseBodyHeight(motion.skeleton, up));
  }

  const Eigen::MatrixXd targets = canonicalJointPositions(motion, mapping);
  CleanupReport report;
  const CleanupInput input(motion, mapping, targets, contacts, up, floor, convention.cm_per_unit);
  CleanupOptions options;
  options.max_total_seconds = timeLimitOption(parsed);
  const Motion cleaned = cleanupMotion(input, options, &report);
  const bool resample = output_fps > 0.0 && std::abs(output_fps - cleaned.fps()) > 1e-6 * output_fps;
  const Motion exported = resample ? resampleMotion(cleaned, output_fps) : cleaned;
  AtomicFileBatch files;  // the clip and its metrics: both or neither
  files.stage(output, formatBvh(exported));

  const ClipMetrics before = measure(motion, mapping, contacts, nullptr, convention, floor);
  const ClipMetrics after = measure(cleaned, mapping, contacts, &targets, convention, floor);
  if (auto metrics_file = parsed.value("metrics")) {
    nlohmann::ordered_json json;
    json["input"] = nlohmann::json::parse(metricsToJson(before));
    json["cleaned"] = nlohmann::json::parse(metricsToJson(after));
    json["cleanup"] = {{"seconds", report.seconds}, {"iterations", report.total_iterations}, {"warnings", report.warnings}};
    files.stage(*metrics_file, json.dump(2) + "\n");
  }
  files.commit();
  for (const std::string& warning : report.warnings) std::cout << "warning: " << warning << "\n";
  std::printf("wrote %s: %d frames at %.4g fps in %.2f s\n  foot skate %.2f -> %.2f cm/s, floor penetration %.2f -> %.2f cm, "
              "residual %.2f cm, bone error %.1e cm\n",
              output.c_str(), exported.frameCount(), exported.fps(), report.seconds, before.foot_skate_cm_s,
              after.foot_skate_cm_s, before.penetration_max_cm, after.penetration_max_cm, after.residual_mean_cm,
              after.bone_error_max_cm);
  return 0;
}

}  // namespace motionstyle::cli
