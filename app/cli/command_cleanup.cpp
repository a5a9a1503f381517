// motionstyle-cli cleanup IN.bvh --out OUT.bvh (or several clips and folders --out FOLDER, batch.h):
// the IK clean-up on a clip as it is (its own canonical
// joint positions are the targets): feet locked during contact, bone lengths exact, feet on the floor.
// Contacts come from --contacts FILE, else from the tracks saved beside the clip
// (IN.bvh.contacts.json, e.g. edited in the app), else are detected from height and speed.
// The solve and the metrics run at IN's own rate; --fps N resamples the cleaned clip for export only.
// Bad input is exit 2 before any solve: no frames (Frames: 0), a skeleton without height
// (requireMeasurableRestPose), --fps beyond 100x IN's rate, an unknown --unit.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>
#include <nlohmann/json.hpp>

#include "bvh/bvh_reader.h"
#include "batch.h"
#include "bvh/bvh_writer.h"
#include "cli_args.h"
#include "commands.h"
#include "common/atomic_file.h"
#include "common/errors.h"
#include "common/output_paths.h"
#include "features/foot_contacts.h"
#include "features/representation.h"
#include "features/rest_pose_frames.h"
#include "ik/cleanup.h"
#include "ik/contact_file.h"
#include "ik/metrics.h"
#include "mapping/mapping_file.h"
#include "motion/kinematics.h"
#include "motion/resample.h"
#include "stylized_output.h"

namespace motionstyle::cli {
namespace {

// The settings shared by every block's metrics (positions of every joint of `skeleton`).
MetricsInput metricsBlock(const Eigen::MatrixXd& world, const JointMapping& mapping, const std::vector<BoneReference>& bones,
                          const SpaceConvention& convention, double floor, double fps) {
  MetricsInput input(world, mapping.joints, bones);
  input.up = convention.fileUp();
  input.floor_height = floor;
  input.cm_per_unit = convention.cm_per_unit;
  input.fps = fps;
  return input;
}

// The input clip's metrics, a block of frames at a time (its world positions are never all held).
ClipMetrics measureInput(const Motion& motion, const JointMapping& mapping, const Eigen::MatrixXi& contacts,
                         const SpaceConvention& convention, double floor) {
  const std::vector<BoneReference> bones = skeletonBones(motion.skeleton);
  MetricsAccumulator metrics(/*keep_tracks=*/false);
  for (int first = 0; first < motion.frameCount(); first += kMotionBlockFrames) {
    const int count = std::min(kMotionBlockFrames, motion.frameCount() - first);
    const Eigen::MatrixXd world = worldPositions(motion.skeleton, localPoses(motion, first, count));
    MetricsInput block = metricsBlock(world, mapping, bones, convention, floor, motion.fps());
    block.contacts = contacts.middleRows(first, count);
    metrics.add(block);
  }
  return metrics.finish();
}

// One clip's clean-up: what the command reads and writes (all checked by the caller before).
struct CleanupRequest {
  std::filesystem::path input;
  std::filesystem::path output;
  std::optional<std::filesystem::path> metrics;
  std::optional<std::filesystem::path> contacts;  // --contacts, else IN.bvh.contacts.json when present
  std::optional<std::filesystem::path> mapping;
  std::optional<std::string> unit;
  double output_fps = 0.0;  // 0: IN's own rate
  double time_limit_seconds = 0.0;
  int cleanup_threads = 0;  // CleanupOptions::threads (0: every hardware thread)
};

// Cleans up one clip and writes it (and its metrics) atomically; returns the report lines.
std::string cleanUpFile(const CleanupRequest& request) {
  const std::filesystem::path& input_file = request.input;
  const std::filesystem::path& output = request.output;
  const double output_fps = request.output_fps;
  const std::optional<std::string>& unit = request.unit;
  std::ostringstream log;
  Motion motion = readBvh(input_file, /*minimum_frames=*/1);
  if (output_fps > 0.0) requireResampleableTo(motion, output_fps);
  const JointMapping mapping = mapJoints(motion.skeleton, input_file.string(), request.mapping);
  requireMeasurableRestPose(motion, mapping);
  // A leading rest-pose frame (CMU's T-pose frame 0) is solved as the motion's first frame and written
  // back as it was (rest_pose_frames.h). Replaced in place: a long clip is not copied.
  const int rest_pose_frames = leadingRestPoseFrames(motion, mapping);
  Motion rest_pose;  // the rest-pose frames as they were
  rest_pose.skeleton = motion.skeleton;
  rest_pose.frame_time = motion.frame_time;
  rest_pose.values = motion.values.topRows(rest_pose_frames);
  replaceRestPoseFrames(motion, rest_pose_frames);
  if (rest_pose_frames > 0) log << "frame 0 is the rig's rest pose, not motion: solved as the motion continued, written as it was\n";
  // The clip's own canonical joints are the targets, and all the planning needs (up axis, floor,
  // contacts): the world positions of every joint are only ever computed a block at a time.
  Eigen::MatrixXd targets = canonicalJointPositions(motion, mapping);
  FileSpaceGround ground = detectFileSpaceGround(motion, mapping, targets, unit);
  const SpaceConvention& convention = ground.convention;
  const Eigen::Vector3d up = ground.up;
  const double floor = ground.floor_height;

  Eigen::MatrixXi contacts = std::move(ground.contacts);
  std::optional<std::filesystem::path> tracks_file = request.contacts;
  if (!tracks_file && std::filesystem::exists(contactTracksPath(input_file))) tracks_file = contactTracksPath(input_file);
  if (tracks_file) {
    const ContactTracks tracks = loadContactTracks(*tracks_file);
    if (tracks.labels.rows() != motion.frameCount())
      throw InputError(tracks_file->string(), 0,
                       "contact tracks have " + std::to_string(tracks.labels.rows()) + " frames, the clip " +
                           std::to_string(motion.frameCount()));
    contacts = tracks.labels;
    log << "contacts from " << tracks_file->string() << "\n";
  }
  const ClipMetrics before = measureInput(motion, mapping, contacts, convention, floor);

  CleanupReport report;
  const CleanupInput input(motion, mapping, std::move(targets), contacts, up, floor, convention.cm_per_unit);
  CleanupOptions options;
  options.max_total_seconds = request.time_limit_seconds;
  options.threads = request.cleanup_threads;
  const bool resample = output_fps > 0.0 && !sameFrameRate(motion.fps(), output_fps);
  const std::vector<BoneReference> bones = skeletonBones(motion.skeleton);
  MetricsAccumulator after(/*keep_tracks=*/false);
  auto measureBlock = [&](const CleanedBlock& block) {
    MetricsInput metrics = metricsBlock(block.world, mapping, bones, convention, floor, motion.fps());
    metrics.contacts = contacts.middleRows(block.first_frame, block.values.rows());
    metrics.targets = input.targets.middleRows(block.first_frame, block.values.rows());
    after.add(metrics);
  };
  AtomicFileBatch files;  // the clip and its metrics: both or neither
  int exported_frames = motion.frameCount();
  double exported_fps = motion.fps();
  if (resample) {  // resampling needs the whole cleaned clip
    Motion cleaned = motion;
    cleanupMotionInBlocks(input, options, [&](const CleanedBlock& block) {
      cleaned.values.middleRows(block.first_frame, block.values.rows()) = block.values;
      measureBlock(block);
    }, &report);
    Motion exported = resampleMotion(cleaned, output_fps);
    restoreRestPoseFrames(exported, rest_pose, rest_pose_frames);
    exported_frames = exported.frameCount();
    exported_fps = exported.fps();
    files.stage(output, formatBvh(exported));
  } else {  // solved, measured and written a block at a time
    files.stage(output, [&](std::ostream& out) {
      BvhStreamWriter writer(out, motion.skeleton, motion.frameCount(), motion.frame_time);
      cleanupMotionInBlocks(input, options, [&](const CleanedBlock& block) {
        if (block.first_frame < rest_pose_frames) {
          MatrixRowMajor values = block.values;
          const int rows = std::min<int>(rest_pose_frames - block.first_frame, static_cast<int>(values.rows()));
          values.topRows(rows) = rest_pose.values.middleRows(block.first_frame, rows);
          writer.writeFrames(values);
        } else {
          writer.writeFrames(block.values);
        }
        measureBlock(block);
      }, &report);
      writer.finish();
    });
  }
  const ClipMetrics cleaned_metrics = after.finish();
  if (const auto& metrics_file = request.metrics) {
    nlohmann::ordered_json json;
    json["input"] = nlohmann::json::parse(metricsToJson(before));
    json["cleaned"] = nlohmann::json::parse(metricsToJson(cleaned_metrics));
    json["cleanup"] = {{"seconds", report.seconds}, {"iterations", report.total_iterations}, {"warnings", warningTexts(report)}};
    files.stage(*metrics_file, json.dump(2) + "\n");
  }
  files.commit();
  for (const CleanupWarning& warning : report.warnings) log << "warning: " << warning.text << "\n";
  char figures[512];
  std::snprintf(figures, sizeof figures,
                "wrote %s: %d frames at %.4g fps in %.2f s\n  foot skate %.2f -> %.2f cm/s, floor penetration %.2f -> "
                "%.2f cm, residual %.2f cm, bone error %.1e cm",
                output.c_str(), exported_frames, exported_fps, report.seconds, before.foot_skate_cm_s,
                cleaned_metrics.foot_skate_cm_s, before.penetration_max_cm, cleaned_metrics.penetration_max_cm,
                cleaned_metrics.residual_mean_cm, cleaned_metrics.bone_error_max_cm);
  log << figures;
  return log.str();
}

}  // namespace

int runCleanup(const Args& args) {
  const ParsedArgs parsed =
      parseArgs(args, {{"out"}, {"contacts"}, {"metrics"}, {"unit"}, {"mapping"}, {"fps"}, {"time-limit"}, {"jobs"}});
  if (parsed.positional.empty()) throw UsageError("cleanup needs an input clip IN.bvh (or several, or folders)");
  CleanupRequest request;
  request.output_fps = parsed.number("fps", 0.0, kOutputFpsRange);
  request.unit = lengthUnit(parsed);
  request.time_limit_seconds = timeLimitOption(parsed);
  if (auto mapping = parsed.value("mapping")) request.mapping = std::filesystem::path(*mapping);
  if (auto contacts = parsed.value("contacts")) request.contacts = std::filesystem::path(*contacts);
  const std::filesystem::path out = parsed.required("out");
  std::optional<std::filesystem::path> metrics;
  if (auto value = parsed.value("metrics")) metrics = std::filesystem::path(*value);

  if (isBatch(parsed.positional)) {
    if (request.contacts) throw UsageError("--contacts names one clip's tracks: not with several clips");
    const std::vector<BatchItem> items = batchItems(parsed.positional, out, metrics);
    std::vector<NamedPath> extra;
    if (request.mapping) extra.push_back({*request.mapping, "--mapping"});
    for (const BatchItem& item : items) extra.push_back({contactTracksPath(item.input), "the clip's contact tracks"});
    prepareBatchOutputs(items, extra);
    request.cleanup_threads = 1;  // --jobs says how many cores: one per clip
    return runBatch(items, jobsOption(parsed), [&](const BatchItem& item) {
      CleanupRequest one = request;
      one.input = item.input;
      one.output = item.output;
      one.metrics = item.metrics;
      return cleanUpFile(one);
    }, "cleanup", std::cout);
  }
  request.input = parsed.positional[0];
  request.output = out;
  request.metrics = metrics;
  std::vector<NamedPath> inputs = {{request.input, "the input clip"}, {contactTracksPath(request.input), "the clip's contact tracks"}};
  if (request.contacts) inputs.push_back({*request.contacts, "--contacts"});
  if (request.mapping) inputs.push_back({*request.mapping, "--mapping"});
  std::vector<NamedPath> outputs = {{out, "--out"}};
  if (metrics) outputs.push_back({*metrics, "--metrics"});
  checkOutputPaths(inputs, outputs);
  std::cout << cleanUpFile(request) << "\n";
  return 0;
}

}  // namespace motionstyle::cli
