// eval_generalisation: how the loss network and the style networks hold on clips of studios, actors
// and rigs they never trained on, against the same figures on held-out Bandai clips (issue 12's
// goals). Prints tables; --json FILE writes every figure.
//
//   eval_generalisation [--models DIR] [--loss-network FILE] [--styles elderly,sad,...] [--data BANDAI_ROOT]
//                       [--fixtures SHARED_FIXTURES] [--samples DIR] [--no-cleanup] [--per-joint]
//                       [--path content|style] [--probes] [--frontier] [--json FILE]
//                       [--refine STEPS] [--refine-rate LR] [--refine-content C] [--refine-style S]
//
// Clip sets:
//   bandai-ae-heldout     every 10th file of dataset-1 then dataset-2 (train_models.sh's train-loss-network split)
//   bandai-style-heldout  every 5th dataset-2 normal-style walk, run or turn (train_models.sh's train-style split)
//   bandai-styled-heldout the walks, runs and turns of bandai-ae-heldout in a style other than normal: clips
//                         with a style of their own, as CMU 131_01 and the zombie have (never T's content, nor
//                         the loss network's); a network skips the clips of its own style
//   other-studios         the two samples (CMU 131_01 trimmed, the zombie) and ../shared/fixtures/
//                         cmu_walks/*.bvh as published (frame 0 a rest pose, which the features replace:
//                         features/rest_pose_frames.h)
// The networks run as `stylize` runs them, with the style refinement's defaults (style_refinement.h)
// unless the --refine* options change them (--refine 0: the network's output as it is).
// Per network and clip: style distance ratio and content distance (eval's definitions), the gait
// signature added (gait_signature.h: a style judge apart from the loss network), familiarity
// (style/familiarity.h), and unless --no-cleanup the IK clean-up's residual (its worst: where, in the
// JSON), skate, "unreachable" warnings and the clips warned of a contact held under the style's lift
// ("held"), and the cleaned output's root path against the content's
// (features/root_path.h). --frontier adds, per network, the least content distance at which any method
// could bring the Bandai clips to their measured mean style ratio and the other studios' clips to the
// same ratio and to 1.25x it (style_content_frontier.h: issue 12's two goals against each other).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bvh/bvh_reader.h"
#include "common/resource_paths.h"
#include "features/root_path.h"
#include "mapping/canonical_joints.h"
#include "mapping/joint_mapping.h"
#include "style/evaluation.h"
#include "style/familiarity.h"
#include "style/motion_dataset.h"
#include "style/stylized_cleanup.h"
#include "style/stylizer.h"
#include "style/training.h"
#include "gait_signature.h"
#include "style_content_frontier.h"

namespace fs = std::filesystem;
using namespace motionstyle;

namespace {

struct EvalClip {
  style::MotionClip clip;
  Motion motion;
  JointMapping mapping;
  std::string label;  // the content label the style clip is paired by
};

struct ClipSet {
  std::string name;
  std::vector<EvalClip> clips;
};

EvalClip loadClip(const fs::path& file, const std::string& label) {
  EvalClip e;
  e.motion = readBvh(file);
  e.mapping = mapJoints(e.motion.skeleton, file.string());
  e.clip = style::makeMotionClip(e.motion, e.mapping, file);
  e.label = label.empty() ? e.clip.labels.content : label;
  return e;
}

std::string otherStudioLabel(const std::string& stem) {
  static const std::map<std::string, std::string> labels = {
      {"07_01", "walk"}, {"08_10", "walk"}, {"09_01", "run"}, {"127_07", "run"}, {"35_23", "run"},
      {"cmu_131_01_walk", "walk"}, {"zombie_walk", "walk"}};
  const auto it = labels.find(stem);
  return it == labels.end() ? "walk" : it->second;
}

// The other studios' plain walks and runs; the rest (CMU 131_01 "Michael Jackson styled", the zombie,
// the obstacle-course run 127_07) carry a style or a character of their own.
bool isPlainOtherStudioClip(const std::string& file) {
  for (const char* plain : {"07_01.bvh", "08_10.bvh", "09_01.bvh", "35_23.bvh"})
    if (file == plain) return true;
  return false;
}

std::vector<ClipSet> loadClipSets(const fs::path& data, const fs::path& fixtures, const fs::path& samples) {
  std::vector<ClipSet> sets;
  const fs::path d1 = data / "dataset-1" / "data", d2 = data / "dataset-2" / "data";
  if (fs::is_directory(d1) && fs::is_directory(d2)) {
    const auto locomotion = [](const style::ClipLabels& labels) {
      return labels.content == "walk" || labels.content == "run" || labels.content.rfind("walk-turn", 0) == 0;
    };
    ClipSet loss_network{"bandai-ae-heldout", {}}, styled{"bandai-styled-heldout", {}};
    for (const fs::path& f : style::splitHoldout(style::findBvhFiles({d1, d2}), 10).held_out) {
      loss_network.clips.push_back(loadClip(f, ""));
      const style::ClipLabels labels = style::parseClipLabels(f);
      if (locomotion(labels) && labels.style != "normal") styled.clips.push_back(loss_network.clips.back());
    }
    sets.push_back(std::move(loss_network));
    // train_models.sh's style content: the dataset-2 normal-style locomotion clips, every 5th held out.
    std::vector<fs::path> normal;
    for (const fs::path& f : style::findBvhFiles({d2})) {
      const style::ClipLabels labels = style::parseClipLabels(f);
      if (labels.style == "normal" && locomotion(labels)) normal.push_back(f);
    }
    ClipSet st{"bandai-style-heldout", {}};
    for (const fs::path& f : style::splitHoldout(normal, 5).held_out) st.clips.push_back(loadClip(f, ""));
    sets.push_back(std::move(st));
    sets.push_back(std::move(styled));
  } else {
    std::printf("note: no Bandai data at %s: Bandai sets skipped\n", data.string().c_str());
  }
  ClipSet other{"other-studios", {}};
  for (const char* name : {"cmu_131_01_walk.bvh", "zombie_walk.bvh"})
    if (fs::exists(samples / name)) other.clips.push_back(loadClip(samples / name, otherStudioLabel(fs::path(name).stem())));
  if (fs::is_directory(fixtures / "cmu_walks")) {
    std::vector<fs::path> walks;
    for (const auto& entry : fs::directory_iterator(fixtures / "cmu_walks"))
      if (entry.path().extension() == ".bvh") walks.push_back(entry.path());
    std::sort(walks.begin(), walks.end());
    for (const fs::path& f : walks) other.clips.push_back(loadClip(f, otherStudioLabel(f.stem().string())));
  }
  sets.push_back(std::move(other));
  return sets;
}

// Per-joint and per-clip reconstruction of the loss network.
nlohmann::json evaluateLossNetwork(const nn::LossNetworkModel& loss_network, const std::vector<ClipSet>& sets, bool per_joint) {
  nlohmann::json out = nlohmann::json::object();
  std::printf("\nloss network: reconstruction (mean joint error, reference cm) and familiarity\n");
  for (const ClipSet& set : sets) {
    Eigen::VectorXd joint_sum = Eigen::VectorXd::Zero(kCanonicalJointCount);
    double sum = 0.0, worst = 0.0, skate = 0.0, skate_content = 0.0;
    long frames = 0;
    nlohmann::json clips = nlohmann::json::array();
    std::map<std::string, int> levels;
    for (const EvalClip& e : set.clips) {
      const Eigen::MatrixXd& x = e.clip.features.values;
      const Eigen::MatrixXd y = style::projectFeatures(loss_network, x);
      for (int c = 0; c < kCanonicalJointCount; ++c)
        joint_sum[c] += (y.middleRows<3>(3 * c) - x.middleRows<3>(3 * c)).colwise().norm().sum();
      const style::Familiarity fam = style::measureFamiliarity(loss_network, x);
      // Foot skate (cm/s, by the content's contacts) of the projection and of the content itself.
      skate += style::footSkate(y, e.clip.features.contacts, e.clip.features.anchor) * static_cast<double>(x.cols());
      skate_content += style::footSkate(x, e.clip.features.contacts, e.clip.features.anchor) * static_cast<double>(x.cols());
      sum += fam.mean_cm * static_cast<double>(x.cols());
      frames += x.cols();
      worst = std::max(worst, fam.mean_cm);
      ++levels[style::familiarityName(fam.level)];
      clips.push_back({{"file", e.clip.file.filename().string()}, {"frames", x.cols()}, {"error_cm", fam.mean_cm},
                       {"worst_second_cm", fam.worst_second_cm}, {"level", style::familiarityName(fam.level)}});
      if (set.name == "other-studios")
        std::printf("  %-22s %-20s %5.2f cm (worst second %5.2f) %s\n", set.name.c_str(),
                    e.clip.file.filename().string().c_str(), fam.mean_cm, fam.worst_second_cm,
                    style::familiarityName(fam.level));
    }
    const double mean = frames > 0 ? sum / static_cast<double>(frames) : 0.0;
    const double projection_skate = frames > 0 ? skate / static_cast<double>(frames) : 0.0;
    const double content_skate = frames > 0 ? skate_content / static_cast<double>(frames) : 0.0;
    std::printf("  %-22s %3zu clips: mean %.2f cm, worst clip %.2f cm  (familiar %d, unusual %d, far %d); "
                "skate %.1f cm/s projected (content %.1f)\n",
                set.name.c_str(), set.clips.size(), mean, worst, levels["familiar"], levels["unusual"], levels["far"],
                projection_skate, content_skate);
    nlohmann::json joints = nlohmann::json::object();
    if (frames > 0) {
      static const char* names[kCanonicalJointCount] = {
          "Hips", "LHip", "LKnee", "LAnkle", "LToe", "RHip", "RKnee", "RAnkle", "RToe", "Spine", "Chest",
          "Neck", "Head", "LArm", "LElbow", "LWrist", "LHand", "RArm", "RElbow", "RWrist", "RHand"};
      if (per_joint) std::printf("    per joint:");
      for (int c = 0; c < kCanonicalJointCount; ++c) {
        const double j = joint_sum[c] / static_cast<double>(frames);
        joints[names[c]] = j;
        if (per_joint) std::printf(" %s %.1f", names[c], j);
      }
      if (per_joint) std::printf("\n");
    }
    out[set.name] = {{"mean_cm", mean}, {"worst_clip_cm", worst}, {"projection_skate_cm_s", projection_skate},
                     {"content_skate_cm_s", content_skate}, {"per_joint_cm", joints}, {"clips", clips}};
  }
  return out;
}

// Familiarity of other studios' clips and of variations that take them further from the training
// motion (played backwards, twice as fast, half as fast): what the thresholds are read against.
void printFamiliarityProbes(const nn::LossNetworkModel& loss_network, const ClipSet& other) {
  std::printf("\nfamiliarity probes (mean reconstruction error cm: as captured / backwards / x2 speed / x0.5 speed)\n");
  for (const EvalClip& e : other.clips) {
    std::vector<double> figures;
    for (int variant = 0; variant < 4; ++variant) {
      Motion motion = e.motion;
      if (variant == 1) motion.values = e.motion.values.colwise().reverse().eval();
      if (variant == 2) motion.frame_time = e.motion.frame_time / 2.0;
      if (variant == 3) motion.frame_time = e.motion.frame_time * 2.0;
      const MotionFeatures features = extractFeatures(motion, e.mapping);
      figures.push_back(style::measureFamiliarity(loss_network, features.values).mean_cm);
    }
    std::printf("  %-22s %5.2f %5.2f %5.2f %5.2f\n", e.clip.file.filename().string().c_str(), figures[0], figures[1],
                figures[2], figures[3]);
  }
}

fs::path findStyleClip(const std::string& name, const fs::path& data) {
  for (const char* part : {"dataset-1", "dataset-2"})
    if (fs::exists(data / part / "data" / name)) return data / part / "data" / name;
  return {};
}

// Issue 12's goal for the clean-up's worst residual per clip.
constexpr double kWorstResidualGoalCm = 8.0;

struct NetworkFigures {
  double style_ratio = 0, projection_ratio = 0, content_after = 0, familiarity = 0, network_distance = 0;
  double residual_mean = 0, residual_max = 0, skate = 0, cleaned_style_ratio = 0;
  double gait_share = 0, cleaned_gait_share = 0;  // gait_signature.h: of the output, of the cleaned clip
  // held_down: clips warned of a contact that holds a foot under the style's lift (ik/cleanup.h);
  // over_goal: clips whose worst residual is over kWorstResidualGoalCm
  int unreachable = 0, held_down = 0, cleaned = 0, over_goal = 0;
  double distance_ratio_min = 1e9, distance_ratio_max = 0, end_error_max = 0;
  int clips = 0;
};

nlohmann::json evaluateNetwork(const std::string& network, const nn::StyleModel& model,
                               const nn::LossNetworkModel& loss_network, const ClipSet& set,
                               const fs::path& data, bool cleanup, style::PathMode path, const CleanupOptions& cleanup_options,
                               const style::StyleRefinement& refinement, NetworkFigures& figures,
                               std::vector<bench::FrontierClip>* frontier) {
  // Style clips by label from the network's own metadata ("style_for_walk" -> file name).
  std::map<std::string, std::string> style_for;
  for (const auto& [key, value] : model.metadata.properties)
    if (key.rfind("style_for_", 0) == 0) style_for[key.substr(10)] = value;
  std::vector<style::MotionClip> styles;
  std::map<std::string, int> style_index;
  std::vector<style::MotionClip> clips;
  std::vector<int> pairing;
  std::vector<const EvalClip*> used;
  for (const EvalClip& e : set.clips) {
    if (e.clip.labels.style == network) continue;  // a clip already in the network's style
    std::string label = style_for.count(e.label) ? e.label : (style_for.count("walk") ? "walk" : "");
    if (label.empty() && !style_for.empty()) label = style_for.begin()->first;
    if (!style_index.count(label)) {
      const fs::path file = findStyleClip(style_for[label], data);
      if (file.empty()) continue;
      style_index[label] = static_cast<int>(styles.size());
      styles.push_back(style::loadMotionClip(file, style::styleClipOptions({}, model.loss_network.shape().width)));
    }
    clips.push_back(e.clip);
    pairing.push_back(style_index[label]);
    used.push_back(&e);
  }
  nlohmann::json out = nlohmann::json::object();
  if (clips.empty()) return out;
  const style::EvaluationReport report = style::evaluateStyleNetwork(loss_network, model, clips, styles, pairing, path, refinement);
  const style::Stylizer stylizer(model, "the style network", refinement);
  std::vector<nn::Mat<float>> style_grams;  // each style clip's, for the cleaned clips' style ratio
  std::vector<bench::GaitSignature> style_gaits;
  for (const style::MotionClip& style : styles) {
    style_grams.push_back(style::styleGramOf(model.loss_network, model.normalisation, style.features.values));
    style_gaits.push_back(bench::gaitSignature(style.features.values));
  }
  nlohmann::json per_clip = nlohmann::json::array();
  for (std::size_t i = 0; i < clips.size(); ++i) {
    const style::ClipEvaluation& ev = report.clips[i];
    const double ratio = ev.style_distance_before > 0 ? ev.style_distance_after / ev.style_distance_before : 0;
    const double proj = ev.style_distance_before > 0 ? ev.style_distance_projection / ev.style_distance_before : 0;
    nlohmann::json c = {{"file", clips[i].file.filename().string()}, {"frames", ev.frames}, {"style_ratio", ratio},
                        {"projection_ratio", proj}, {"content_distance", ev.content_distance_after},
                        {"style_distance_before", ev.style_distance_before}, {"style_distance_after", ev.style_distance_after},
                        {"familiarity_cm", ev.reconstruction_joint_error_cm},
                        {"network_path_distance_ratio", ev.network_path_distance_ratio}};
    figures.network_distance += ev.network_path_distance_ratio;
    figures.style_ratio += ratio;
    figures.projection_ratio += proj;
    figures.content_after += ev.content_distance_after;
    figures.familiarity += ev.reconstruction_joint_error_cm;
    ++figures.clips;
    if (frontier != nullptr) {
      const int frames = static_cast<int>(clips[i].features.values.cols());
      const nn::Mat<float> normalised = model.normalisation.normalized(clips[i].features.values);
      frontier->push_back({model.loss_network.encode(normalised, frames).cast<double>(),
                           style_grams[static_cast<std::size_t>(pairing[i])].cast<double>(),
                           normalised.cast<double>(), &model.loss_network});
    }
    const EvalClip& e = *used[i];
    const style::StylizedClip stylized = stylizer.stylize(e.clip.features, 1.0, path);
    const bench::GaitSignature content_gait = bench::gaitSignature(e.clip.features.values);
    const bench::GaitSignature& style_gait = style_gaits[static_cast<std::size_t>(pairing[i])];
    c["gait_share"] = bench::gaitSignatureShare(content_gait, style_gait, bench::gaitSignature(stylized.features));
    figures.gait_share += c["gait_share"].get<double>();
    if (cleanup) {
      const style::StylizedCleanup cleaned = style::cleanUpStylizedClip(e.motion, e.mapping, stylized, cleanup_options);
      int unreachable = 0;
      int held_down = 0;
      for (const std::string& w : warningTexts(cleaned.report)) {
        unreachable += w.find("unreachable") != std::string::npos;
        held_down += w.find("held down by its contact") != std::string::npos;
      }
      const RootPathComparison travelled =
          compareClipPaths(e.motion, cleaned.motion, e.mapping, e.clip.features.anchor.convention);
      // The style the user gets: the cleaned clip's features against the same style clip, measured in
      // the content's frame (its floor, proportions, girdle correction and height shift).
      style::DatasetOptions same_frame;
      same_frame.features.derived_from = e.clip.features.anchor;
      const Eigen::MatrixXd cleaned_features =
          style::makeMotionClip(cleaned.motion, e.mapping, e.clip.file, same_frame).features.values;
      const style::StyleDistances cleaned_distances = style::measureStyleDistances(
          model.loss_network, model.normalisation, e.clip.features.values, cleaned_features,
          style_grams[static_cast<std::size_t>(pairing[i])]);
      c["cleaned_style_ratio"] = cleaned_distances.styleRatio();
      c["cleaned_gait_share"] = bench::gaitSignatureShare(content_gait, style_gait, bench::gaitSignature(cleaned_features));
      figures.cleaned_gait_share += c["cleaned_gait_share"].get<double>();
      figures.cleaned_style_ratio += cleaned_distances.styleRatio();
      c["residual_mean_cm"] = cleaned.cleaned.residual_mean_cm;
      c["residual_max_cm"] = cleaned.cleaned.residual_max_cm;
      // Where: the clean-up's frame (its rate, stylized_cleanup.h) and the canonical joint.
      c["residual_max_frame"] = cleaned.cleaned.residual_max_frame;
      c["residual_max_seconds"] = cleaned.cleaned.residual_max_frame / cleaned.fps;
      c["residual_max_joint"] =
          std::string(canonicalJointName(static_cast<CanonicalJoint>(std::max(0, cleaned.cleaned.residual_max_joint))));
      c["skate_cm_s"] = cleaned.cleaned.foot_skate_cm_s;
      c["unreachable_warnings"] = unreachable;
      c["held_down_warnings"] = held_down;
      c["distance_ratio"] = travelled.distance_ratio;
      c["end_error_fraction"] = travelled.end_error_fraction;
      c["heading_error_deg"] = travelled.heading_error * 180.0 / 3.14159265358979;
      figures.residual_mean += cleaned.cleaned.residual_mean_cm;
      figures.residual_max = std::max(figures.residual_max, cleaned.cleaned.residual_max_cm);
      figures.over_goal += cleaned.cleaned.residual_max_cm > kWorstResidualGoalCm;
      figures.skate = std::max(figures.skate, cleaned.cleaned.foot_skate_cm_s);
      figures.unreachable += unreachable;
      figures.held_down += held_down > 0;
      figures.distance_ratio_min = std::min(figures.distance_ratio_min, travelled.distance_ratio);
      figures.distance_ratio_max = std::max(figures.distance_ratio_max, travelled.distance_ratio);
      figures.end_error_max = std::max(figures.end_error_max, travelled.end_error_fraction);
      ++figures.cleaned;
    }
    per_clip.push_back(c);
  }
  out["clips"] = per_clip;
  return out;
}

void printFigures(const std::string& network, const std::string& set, const NetworkFigures& f) {
  const double n = std::max(1, f.clips);
  std::printf("  %-10s %-22s style %.3f (proj %.3f) content %.3f gait %.2f fam %.2f net-path x%.2f", network.c_str(),
              set.c_str(), f.style_ratio / n, f.projection_ratio / n, f.content_after / n, f.gait_share / n,
              f.familiarity / n, f.network_distance / n);
  if (f.cleaned > 0)
    std::printf(" | cleaned style %.3f gait %.2f residual %.2f max %.1f (%d of %d clips over %.0f) skate %.2f unreach %d held %d"
                " | distance x%.2f-%.2f end %.0f%%",
                f.cleaned_style_ratio / f.cleaned, f.cleaned_gait_share / f.cleaned, f.residual_mean / f.cleaned,
                f.residual_max, f.over_goal, f.cleaned,
                kWorstResidualGoalCm, f.skate, f.unreachable, f.held_down, f.distance_ratio_min, f.distance_ratio_max,
                100.0 * f.end_error_max);
  std::printf("\n");
}

// The content distance matched by kind of clip: the other studios' plain clips against Bandai's
// normal-style ones, their clips with a style of their own against Bandai's clips in another style.
nlohmann::json printMatchedContent(const std::string& network, const nlohmann::json& sets) {
  const auto mean = [&](const char* set, int kind) {  // kind: 0 every clip, 1 plain, 2 the rest
    double sum = 0;
    int n = 0;
    if (!sets.contains(set) || !sets[set].contains("clips")) return 0.0;
    for (const nlohmann::json& c : sets[set]["clips"]) {
      const bool plain = isPlainOtherStudioClip(c["file"].get<std::string>());
      if (kind == 0 || (kind == 1) == plain) { sum += c["content_distance"].get<double>(); ++n; }
    }
    return n > 0 ? sum / n : 0.0;
  };
  const double normal = mean("bandai-style-heldout", 0), styled = mean("bandai-styled-heldout", 0);
  const double plain = mean("other-studios", 1), own = mean("other-studios", 2);
  if (normal <= 0 || styled <= 0 || plain <= 0 || own <= 0) return nullptr;
  std::printf("  %-10s content matched by kind: other studios' plain clips %.3f = %.2fx Bandai's normal %.3f; "
              "their styled clips %.3f = %.2fx Bandai's styled %.3f\n",
              network.c_str(), plain, plain / normal, normal, own, own / styled, styled);
  return {{"plain_over_bandai_normal", plain / normal}, {"styled_over_bandai_styled", own / styled}};
}

// Issue 12's style and content goals against the least content distance any method could reach
// (style_content_frontier.h): the Bandai clips at their measured mean style ratio, the other studios'
// at the same ratio and at kStyleRatioGoal times it, in the hidden units and in motions.
constexpr double kStyleRatioGoal = 1.25, kContentDistanceGoal = 2.0;

nlohmann::json printFrontier(const std::string& network, const std::map<std::string, NetworkFigures>& measured,
                             const std::map<std::string, std::vector<bench::FrontierClip>>& clips) {
  const auto bandai = measured.find("bandai-style-heldout"), other = measured.find("other-studios");
  if (bandai == measured.end() || other == measured.end() || bandai->second.clips == 0 || other->second.clips == 0)
    return nullptr;
  const double bandai_ratio = bandai->second.style_ratio / bandai->second.clips;
  const double bandai_content = bandai->second.content_after / bandai->second.clips;
  nlohmann::json out = {{"bandai_style_ratio", bandai_ratio}, {"bandai_measured_content", bandai_content}};
  for (const bench::FrontierSpace space : {bench::FrontierSpace::HiddenUnits, bench::FrontierSpace::Motions}) {
    const char* name = space == bench::FrontierSpace::Motions ? "motions" : "hidden_units";
    const bench::FrontierPoint least_bandai =
        bench::leastContentAtStyleRatio(clips.at(bandai->first), bandai_ratio, space);
    const bench::FrontierPoint other_same =
        bench::leastContentAtStyleRatio(clips.at(other->first), bandai_ratio, space);
    const bench::FrontierPoint other_goal =
        bench::leastContentAtStyleRatio(clips.at(other->first), kStyleRatioGoal * bandai_ratio, space);
    const double least = least_bandai.mean_content_distance;
    std::printf("  %-10s least content in %-12s Bandai at %.3f: %.5f (measured %.5f = %.1fx); other studios at the "
                "same ratio %.5f = %.2fx Bandai's least; at %.3f (%.2fx): %.5f = %.2fx Bandai's least, %.2fx its "
                "measured (goal %.0fx)\n",
                network.c_str(), name, least_bandai.mean_style_ratio, least, bandai_content, bandai_content / least,
                other_same.mean_content_distance, other_same.mean_content_distance / least,
                other_goal.mean_style_ratio, kStyleRatioGoal, other_goal.mean_content_distance,
                other_goal.mean_content_distance / least, other_goal.mean_content_distance / bandai_content,
                kContentDistanceGoal);
    std::fflush(stdout);
    out[name] = {{"bandai_style_ratio", least_bandai.mean_style_ratio},
                 {"bandai_least_content", least},
                 {"other_least_content_same_ratio", other_same.mean_content_distance},
                 {"other_style_ratio_goal", other_goal.mean_style_ratio},
                 {"other_least_content_goal_ratio", other_goal.mean_content_distance}};
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path resources = resourceDirectory().value_or(fs::path("resources"));
  fs::path models = resources / "models";
  fs::path loss_network_file, json_file;
  fs::path data = fs::path(MOTIONSTYLE_SHARED_DATA_DIR) / "bandai";
  fs::path fixtures = fs::path(MOTIONSTYLE_SHARED_DATA_DIR).parent_path() / "fixtures";
  fs::path samples = resources / "samples";
  std::vector<std::string> styles = {"elderly", "exhausted", "angry", "proud", "youthful",
                                     "feminine", "masculine", "sad", "happy"};
  bool cleanup = true, per_joint = false, probes = false, frontier = false;
  style::PathMode path = style::PathMode::Content;
  CleanupOptions cleanup_options;
  style::StyleRefinement refinement;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto next = [&]() -> std::string {
      if (i + 1 >= argc) { std::fprintf(stderr, "%s needs a value\n", a.c_str()); std::exit(2); }
      return argv[++i];
    };
    if (a == "--models") models = next();
    else if (a == "--loss-network") loss_network_file = next();
    else if (a == "--data") data = next();
    else if (a == "--fixtures") fixtures = next();
    else if (a == "--samples") samples = next();
    else if (a == "--json") json_file = next();
    else if (a == "--no-cleanup") cleanup = false;
    else if (a == "--per-joint") per_joint = true;
    else if (a == "--probes") probes = true;
    else if (a == "--frontier") frontier = true;
    else if (a == "--refine") refinement.iterations = std::stoi(next());
    else if (a == "--refine-rate") refinement.learning_rate = std::stod(next());
    else if (a == "--refine-style") refinement.style_weight = std::stod(next());
    else if (a == "--refine-content") refinement.content_weight = std::stod(next());
    else if (a == "--hips-weight") cleanup_options.hips_weight = std::stod(next());
    else if (a == "--path") path = style::parsePathMode(next()).value_or(style::PathMode::Content);
    else if (a == "--styles") {
      styles.clear();
      std::string list = next(), item;
      for (char ch : list + ",") {
        if (ch == ',') { if (!item.empty()) styles.push_back(item); item.clear(); }
        else item += ch;
      }
    } else {
      std::fprintf(stderr, "unknown argument %s (see the top of eval_generalisation.cpp)\n", a.c_str());
      return 2;
    }
  }
  if (loss_network_file.empty()) loss_network_file = models / "loss_network.net";
  try {
    const std::vector<ClipSet> sets = loadClipSets(data, fixtures, samples);
    const nn::LossNetworkModel loss_network = style::loadCompatibleLossNetwork(loss_network_file);
    nlohmann::json json;
    json["loss_network"] = loss_network_file.string();
    json["reconstruction"] = evaluateLossNetwork(loss_network, sets, per_joint);
    if (probes) printFamiliarityProbes(loss_network, sets.back());
    if (!styles.empty()) std::printf("\nstyle networks (means over clips; clean-up: mean residual, worst residual cm, worst skate cm/s)\n");
    for (const std::string& name : styles) {
      const fs::path file = fs::exists(name) ? fs::path(name) : models / (name + ".net");
      const nn::StyleModel model = style::loadCompatibleStyleModel(file);
      std::map<std::string, NetworkFigures> measured;
      std::map<std::string, std::vector<bench::FrontierClip>> frontier_clips;
      for (const ClipSet& set : sets) {
        if (set.name == "bandai-ae-heldout") continue;
        NetworkFigures& figures = measured[set.name];
        json["networks"][name][set.name] = evaluateNetwork(name, model, loss_network, set, data, cleanup, path, cleanup_options,
                                                           refinement, figures, frontier ? &frontier_clips[set.name] : nullptr);
        printFigures(name, set.name, figures);
      }
      json["networks"][name]["matched_content"] = printMatchedContent(name, json["networks"][name]);
      if (frontier) json["networks"][name]["frontier"] = printFrontier(name, measured, frontier_clips);
    }
    if (!json_file.empty()) {
      std::ofstream(json_file) << json.dump(2) << "\n";
      std::printf("wrote %s\n", json_file.string().c_str());
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "eval_generalisation: %s\n", error.what());
    return 1;
  }
  return 0;
}
