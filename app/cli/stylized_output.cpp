#include "stylized_output.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "common/atomic_file.h"
#include "features/foot_contacts.h"
#include "features/representation.h"
#include "features/rest_pose_frames.h"
#include "features/root_path.h"
#include "ik/contact_file.h"
#include "ik/metrics.h"
#include "motion/kinematics.h"
#include "motion/resample.h"
#include "style/position_clip.h"
#include "style/stylize_cleanup_job.h"
#include "style/stylized_cleanup.h"

namespace motionstyle::cli {

std::vector<OptionSpec> outputOptionSpecs() {
  return {{"no-cleanup", false}, {"metrics"}, {"fps"}, {"path"}, {"time-limit"}};
}

double timeLimitOption(const ParsedArgs& parsed) {
  if (!parsed.has("time-limit")) return std::numeric_limits<double>::infinity();
  const double seconds = parsed.number("time-limit", 0.0);
  if (!(seconds > 0.0 && std::isfinite(seconds))) throw UsageError("--time-limit must be a positive number of seconds");
  return seconds;
}

nlohmann::ordered_json familiarityJson(const style::Familiarity& familiarity, bool per_frame) {
  nlohmann::ordered_json json;
  json["mean_cm"] = familiarity.mean_cm;
  json["worst_second_cm"] = familiarity.worst_second_cm;
  json["level"] = style::familiarityName(familiarity.level);
  json["summary"] = style::familiaritySummary(familiarity);
  if (per_frame) json["per_frame_cm"] = familiarity.per_frame_cm;
  return json;
}

std::vector<NamedPath> outputPaths(const OutputOptions& options, const std::filesystem::path& output) {
  std::vector<NamedPath> paths = {{output, "--out"}};
  if (options.metrics) paths.push_back({*options.metrics, "--metrics"});
  return paths;
}

OutputOptions outputOptions(const ParsedArgs& parsed) {
  OutputOptions options;
  options.cleanup = !parsed.has("no-cleanup");
  if (auto metrics = parsed.value("metrics")) options.metrics = *metrics;
  options.fps = parsed.number("fps", 0.0, kOutputFpsRange);
  options.time_limit_seconds = timeLimitOption(parsed);
  if (auto path = parsed.value("path")) {
    const std::optional<style::PathMode> mode = style::parsePathMode(*path);
    if (!mode) throw UsageError("--path must be content or style, not '" + *path + "'");
    options.path = *mode;
  }
  return options;
}

void writeStylizedOutput(const std::filesystem::path& content_file, const style::StylizedClip& stylized,
                         const OutputOptions& options, const std::filesystem::path& output, std::ostream& log,
                         const style::Familiarity* familiarity) {
  if (familiarity) log << "familiarity: " << style::familiaritySummary(*familiarity) << "\n";
  if (!options.cleanup) {
    Motion positions = style::canonicalPositionsMotion(stylized.world_positions, stylized.fps, output.string());
    if (options.fps > 0.0) positions = resampleMotion(positions, options.fps);
    AtomicFileBatch outputs;  // the clip and its metrics: both or neither
    outputs.stage(output, formatBvh(positions));
    if (options.metrics) {
      MetricsInput raw(stylized.world_positions, identityCanonicalJoints());
      raw.contacts = (stylized.contacts.transpose().array() > 0.5).cast<int>().matrix();
      raw.up = stylized.anchor.convention.fileUp();
      raw.floor_height = style::fileFloorHeight(stylized.anchor);
      raw.cm_per_unit = stylized.anchor.convention.cm_per_unit;
      raw.fps = stylized.fps;
      nlohmann::ordered_json json;
      json["raw"] = nlohmann::json::parse(metricsToJson(computeMetrics(raw)));
      if (familiarity) json["familiarity"] = familiarityJson(*familiarity, /*per_frame=*/true);
      for (const auto& [key, value] : options.extra_metrics.items()) json[key] = value;
      outputs.stage(*options.metrics, json.dump(2) + "\n");
    }
    outputs.commit();
    log << "wrote " << output.string() << ": " << positions.frameCount() << " frames at " << positions.fps()
        << " fps (raw positions of the 21 canonical joints; no clean-up)\n";
    return;
  }
  style::StylizeCleanupJob job;  // the clean-up the app and the filmstrip run
  job.content = readBvh(content_file, /*minimum_frames=*/1);
  const Motion& content = job.content;
  if (options.fps > 0.0) requireResampleableTo(content, options.fps);
  job.mapping = mapJoints(content.skeleton, content_file.string());
  job.stylized = stylized;
  // The user's contact edits saved beside the clip (the app's Save Contact Tracks) rule the locks, as
  // in the app and in cleanup: read against the contacts detected as they detect them.
  const std::filesystem::path tracks_file = contactTracksPath(content_file);
  if (std::filesystem::exists(tracks_file)) {
    const ContactLabels detected =
        detectClipGround(content, job.mapping, leadingRestPoseFrames(content, job.mapping), stylized.anchor.convention.unit).contacts;
    job.contact_overrides = contactOverridesFromTracks(loadContactTracks(tracks_file), detected, content.fps(), tracks_file);
    log << "contacts from " << tracks_file.string() << "\n";
  }
  job.options.max_total_seconds = options.time_limit_seconds;
  job.options.threads = options.cleanup_threads;
  job.output_fps = options.fps;
  const style::StylizeCleanupResult cleaned = job.run();
  AtomicFileBatch outputs;  // the clip and its metrics: both or neither
  outputs.stage(output, formatBvh(cleaned.cleaned));
  if (options.metrics) {
    nlohmann::ordered_json json;
    json["raw"] = nlohmann::json::parse(metricsToJson(cleaned.raw_metrics));
    json["cleaned"] = nlohmann::json::parse(metricsToJson(cleaned.cleaned_metrics));
    const RootPathComparison path = compareClipPaths(content, cleaned.cleaned, job.mapping, stylized.anchor.convention);
    json["path"] = {{"mode", style::pathModeName(stylized.path)},
                    {"distance_ratio", path.distance_ratio},
                    {"end_error_fraction", path.end_error_fraction}};
    json["cleanup"] = {{"seconds", cleaned.report.seconds},
                       {"iterations", cleaned.report.total_iterations},
                       {"warnings", warningTexts(cleaned.report)}};
    if (familiarity) json["familiarity"] = familiarityJson(*familiarity, /*per_frame=*/true);
    for (const auto& [key, value] : options.extra_metrics.items()) json[key] = value;
    outputs.stage(*options.metrics, json.dump(2) + "\n");
  }
  outputs.commit();
  for (const CleanupWarning& warning : cleaned.report.warnings) log << "warning: " << warning.text << "\n";
  char figures[256];
  std::snprintf(figures, sizeof figures,
                "foot skate %.2f -> %.2f cm/s, floor penetration %.2f -> %.2f cm, bone error %.3f -> %.1e cm",
                cleaned.raw_metrics.foot_skate_cm_s, cleaned.cleaned_metrics.foot_skate_cm_s,
                cleaned.raw_metrics.penetration_max_cm, cleaned.cleaned_metrics.penetration_max_cm,
                cleaned.raw_metrics.bone_error_mean_cm, cleaned.cleaned_metrics.bone_error_max_cm);
  log << "wrote " << output.string() << ": " << cleaned.cleaned.frameCount() << " frames at " << cleaned.cleaned.fps()
      << " fps on the input's skeleton (" << content.skeleton.jointCount() << " joints), cleaned in "
      << cleaned.report.seconds << " s\n  " << figures << "\n";
}

}  // namespace motionstyle::cli
