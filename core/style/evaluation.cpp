#include "style/evaluation.h"

#include <array>
#include <chrono>
#include <nlohmann/json.hpp>

#include "features/root_path.h"
#include "ik/metrics.h"
#include "nn/losses.h"
#include "style/familiarity.h"
#include "nn/transformation_objective.h"
#include "style/stylizer.h"

namespace motionstyle::style {
namespace {

using Clock = std::chrono::steady_clock;

// The per-clip figures whose mean over clips is weighted by each clip's frames.
constexpr std::array<double ClipEvaluation::*, 13> kFrameWeighted = {
    &ClipEvaluation::reconstruction_mse,          &ClipEvaluation::reconstruction_joint_error_cm,
    &ClipEvaluation::content_distance_before,     &ClipEvaluation::content_distance_after,
    &ClipEvaluation::style_distance_before,       &ClipEvaluation::style_distance_after,
    &ClipEvaluation::style_distance_projection,   &ClipEvaluation::bone_error_cm_content,
    &ClipEvaluation::bone_error_cm_output,        &ClipEvaluation::foot_skate_cm_s_content,
    &ClipEvaluation::foot_skate_cm_s_output,      &ClipEvaluation::network_path_distance_ratio,
    &ClipEvaluation::network_path_end_error_fraction};

// The per-clip figures weighted by frames into `sum` (the times summed as they are).
void accumulate(ClipEvaluation& sum, const ClipEvaluation& clip) {
  const double w = clip.frames;
  sum.frames += clip.frames;
  for (double ClipEvaluation::*figure : kFrameWeighted) sum.*figure += w * clip.*figure;
  sum.stylize_seconds += clip.stylize_seconds;
}

nlohmann::json clipJson(const ClipEvaluation& c) {
  const auto ratio = [](double after, double before) { return before > 0 ? after / before : 0.0; };
  return {{"file", c.file},
          {"style_clip", c.style_clip},
          {"frames", c.frames},
          {"reconstruction", {{"mse_normalised", c.reconstruction_mse}, {"joint_error_cm", c.reconstruction_joint_error_cm}}},
          {"familiarity", familiarityName(familiarityLevel(c.reconstruction_joint_error_cm))},
          {"content_distance",
           {{"before", c.content_distance_before}, {"after", c.content_distance_after}}},
          {"style_distance",
           {{"before", c.style_distance_before},
            {"after", c.style_distance_after},
            {"ratio", ratio(c.style_distance_after, c.style_distance_before)},
            {"projection_only", c.style_distance_projection},
            {"projection_ratio", ratio(c.style_distance_projection, c.style_distance_before)}}},
          {"bone_error_cm", {{"content", c.bone_error_cm_content}, {"output", c.bone_error_cm_output}}},
          {"foot_skate_cm_s", {{"content", c.foot_skate_cm_s_content}, {"output", c.foot_skate_cm_s_output}}},
          {"network_path", {{"distance_ratio", c.network_path_distance_ratio},
                            {"end_error_fraction", c.network_path_end_error_fraction}}},
          {"stylize_seconds", c.stylize_seconds}};
}

}  // namespace

StyleDistances measureStyleDistances(const nn::LossNetwork<float>& encoder, const FeatureStatistics& normalisation,
                                     const Eigen::MatrixXd& content, const Eigen::MatrixXd& output,
                                     const nn::Mat<float>& style_gram) {
  const int frames = static_cast<int>(content.cols());
  const int pooled = nn::evenFrames(frames) / 2;
  const nn::Mat<float> h_content = encoder.encode(normalisation.normalized(content), frames);
  const nn::Mat<float> h_output = encoder.encode(normalisation.normalized(output), frames);
  const std::vector<nn::Mat<float>> gram = {style_gram};
  StyleDistances d;
  d.content_after = static_cast<double>(nn::meanSquaredError<float>(h_output, h_content, 0.0f, nullptr));
  d.style_before = static_cast<double>(nn::styleLoss<float>(h_content, pooled, gram, 0.0f, nullptr));
  d.style_after = static_cast<double>(nn::styleLoss<float>(h_output, pooled, gram, 0.0f, nullptr));
  return d;
}

nn::Mat<float> styleGramOf(const nn::LossNetwork<float>& encoder, const FeatureStatistics& normalisation,
                           const Eigen::MatrixXd& style) {
  return nn::styleGram(encoder, normalisation.normalized(style));
}

double boneLengthError(const Eigen::MatrixXd& features, const Eigen::VectorXd& bone_lengths) {
  if (features.cols() == 0) return 0.0;
  double sum = 0.0;
  for (int c = 1; c < kCanonicalJointCount; ++c) {
    const int parent = kCanonicalParent[static_cast<std::size_t>(c)];
    const Eigen::RowVectorXd lengths = (features.middleRows<3>(3 * c) - features.middleRows<3>(3 * parent)).colwise().norm();
    sum += (lengths.array() - bone_lengths[c - 1]).abs().sum();
  }
  return sum / (static_cast<double>(features.cols()) * nn::kBoneCount);
}

double footSkate(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts, const FeatureAnchor& anchor) {
  // The reference rig's 21 joints, Y-up, in cm: ik/metrics.h's skate (per foot, at its stiller joint).
  const Eigen::MatrixXd world = referenceWorldPositions(features, anchor);
  MetricsInput input(world, identityCanonicalJoints());
  input.contacts = (contacts.transpose().array() >= 0.5).cast<int>().matrix();
  input.fps = anchor.fps;
  return computeMetrics(input).foot_skate_cm_s;
}

EvaluationReport evaluateStyleNetwork(const nn::LossNetworkModel& loss_network, const nn::StyleModel& network,
                                      const std::vector<MotionClip>& clips, const std::vector<MotionClip>& styles,
                                      const std::vector<int>& pairing, PathMode path,
                                      const StyleRefinement& refinement) {
  if (pairing.size() != clips.size()) throw std::invalid_argument("evaluateStyleNetwork: one pairing per clip");
  const auto started = Clock::now();
  EvaluationReport report;
  report.loss_network_matches_network = nn::sameWeights(loss_network.network, network.loss_network);
  const Stylizer stylizer(network, "the style network", refinement);
  const nn::LossNetwork<float>& loss = network.loss_network;
  const FeatureStatistics& norm = network.normalisation;
  std::vector<nn::Mat<float>> style_grams;
  for (const MotionClip& style : styles) style_grams.push_back(styleGramOf(loss, norm, style.features.values));

  for (std::size_t i = 0; i < clips.size(); ++i) {
    const MotionClip& clip = clips[i];
    const Eigen::MatrixXd& content = clip.features.values;
    const int frames = clip.frameCount();
    ClipEvaluation e;
    e.file = clip.file.string();
    e.style_clip = styles.at(static_cast<std::size_t>(pairing[i])).file.filename().string();
    e.frames = frames;

    const Eigen::MatrixXd reconstructed = projectFeatures(loss_network, content);
    const nn::Mat<float> content_loss_network = loss_network.normalisation.normalized(content);
    e.reconstruction_mse = static_cast<double>(
        nn::meanSquaredError<float>(loss_network.normalisation.normalized(reconstructed), content_loss_network, 0.0f, nullptr));
    e.reconstruction_joint_error_cm = familiarityFromReconstruction(content, reconstructed).mean_cm;

    const auto t0 = Clock::now();
    // What the user gets (Stylizer::stylize: its stances held in the clip's own rig too).
    const Eigen::MatrixXd output = stylizer.stylize(clip.features, 1.0, path).features;
    e.stylize_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const Eigen::MatrixXd own = path == PathMode::Style ? output : stylizer.stylize(clip.features, 1.0, PathMode::Style).features;
    const RootPathComparison network_path = compareRootPaths(summariseRootPath(content), summariseRootPath(own));
    e.network_path_distance_ratio = network_path.distance_ratio;
    e.network_path_end_error_fraction = network_path.end_error_fraction;

    const nn::Mat<float>& gram = style_grams[static_cast<std::size_t>(pairing[i])];
    const Eigen::MatrixXd projected = projectFeatures({loss, norm, {}}, content);
    const StyleDistances after = measureStyleDistances(loss, norm, content, output, gram);
    const StyleDistances projection = measureStyleDistances(loss, norm, content, projected, gram);
    e.content_distance_before = projection.content_after;
    e.content_distance_after = after.content_after;
    e.style_distance_before = after.style_before;
    e.style_distance_after = after.style_after;
    e.style_distance_projection = projection.style_after;

    e.bone_error_cm_content = boneLengthError(content, clip.bone_lengths);
    e.bone_error_cm_output = boneLengthError(output, clip.bone_lengths);
    e.foot_skate_cm_s_content = footSkate(content, clip.features.contacts, clip.features.anchor);
    e.foot_skate_cm_s_output = footSkate(output, clip.features.contacts, clip.features.anchor);
    accumulate(report.mean, e);
    report.clips.push_back(std::move(e));
  }
  ClipEvaluation& mean = report.mean;
  mean.file = "mean";
  if (mean.frames > 0) {
    const double n = mean.frames;
    for (double ClipEvaluation::*figure : kFrameWeighted) mean.*figure /= n;
    report.stylize_frames_per_second = mean.stylize_seconds > 0 ? n / mean.stylize_seconds : 0.0;
  }
  report.seconds = std::chrono::duration<double>(Clock::now() - started).count();
  return report;
}

std::string evaluationJson(const EvaluationReport& report) {
  nlohmann::json json;
  json["format"] = "motionstyle-evaluation";
  json["version"] = 1;
  json["loss_network"] = report.loss_network_file;
  json["network"] = report.network_file;
  json["loss_network_matches_network"] = report.loss_network_matches_network;
  json["units"] = {{"distances", "unweighted eq. 4 / eq. 5 means (normalised hidden units)"},
                   {"lengths", "reference cm"},
                   {"foot_skate", "reference cm per second"}};
  nlohmann::json summary = clipJson(report.mean);
  summary.erase("file");
  summary.erase("style_clip");
  summary["clips"] = report.clips.size();
  summary["stylize_frames_per_second"] = report.stylize_frames_per_second;
  json["summary"] = summary;
  json["clips"] = nlohmann::json::array();
  for (const ClipEvaluation& clip : report.clips) json["clips"].push_back(clipJson(clip));
  json["seconds"] = report.seconds;
  return json.dump(2) + "\n";
}

}  // namespace motionstyle::style
