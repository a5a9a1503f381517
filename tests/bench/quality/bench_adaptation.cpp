// bench_adaptation: "ten clips of a new studio adapted, with one style retrained" (issue 12), timed on
// this machine, with what it changes: the clips' familiarity before and after, the retrained style's
// style ratio and content distance (eq. 4) on them and on Bandai's held-out clips (issue 12's content
// goal: the new studio's over Bandai's), and what the loss network forgets (its Bandai held-out error).
//
//   bench_adaptation [--models DIR] [--style elderly] [--fixtures SHARED_FIXTURES] [--data BANDAI_ROOT]
//                    [--loss-epochs N] [--style-epochs N] [--loss-lr LR]
//                    [--memory shipped|off|bandai|FILE] [--memory-weight W] [--replay on] [--replay-ratio R]
//
// --memory: the shipped loss network's reconstruction memory (the default, as adapt uses it), none,
// one computed here from the Bandai training split, or a file; --replay on mixes the Bandai training
// split's clips in instead (or as well).
//
// The ten clips: the five ../shared/fixtures/cmu_walks clips as published (rest-pose frame 0 held) and
// ../shared/fixtures/cmu/131_01.bvh cut into five pieces: CMU's studio, skeleton and 120 fps, other
// actors than the networks trained on. Runs style::AdaptNetworksJob, the job the app's Adapt tab and
// the CLI run.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bvh/bvh_reader.h"
#include "common/resource_paths.h"
#include "mapping/joint_mapping.h"
#include "style/adaptation.h"
#include "style/evaluation.h"
#include "style/stylizer.h"
#include "nn/compute_pool.h"
#include "style/training.h"

namespace fs = std::filesystem;
using namespace motionstyle;

namespace {

style::MotionClip clipOf(const Motion& motion, const std::string& name) {
  return style::makeMotionClip(motion, mapJoints(motion.skeleton, name), name);
}

Motion framesOf(const Motion& motion, Eigen::Index first, Eigen::Index count) {
  Motion part = motion;
  part.values = motion.values.middleRows(first, count);
  return part;
}

std::vector<style::MotionClip> newStudioClips(const fs::path& fixtures) {
  std::vector<style::MotionClip> clips;
  std::vector<fs::path> walks;
  for (const auto& entry : fs::directory_iterator(fixtures / "cmu_walks"))
    if (entry.path().extension() == ".bvh") walks.push_back(entry.path());
  std::sort(walks.begin(), walks.end());
  for (const fs::path& file : walks) {
    const Motion motion = readBvh(file);
    clips.push_back(clipOf(motion, file.filename().string()));  // frame 0 a rest pose: the features replace it
  }
  const Motion long_clip = readBvh(fixtures / "cmu" / "131_01.bvh");
  const Eigen::Index piece = long_clip.values.rows() / 5;
  for (int i = 0; i < 5; ++i)
    clips.push_back(clipOf(framesOf(long_clip, i * piece, piece), "131_01_part" + std::to_string(i + 1) + ".bvh"));
  return clips;
}

double meanFamiliarity(const nn::LossNetworkModel& loss_network, const std::vector<style::MotionClip>& clips) {
  double sum = 0.0;
  for (const style::MotionClip& clip : clips) sum += style::measureFamiliarity(loss_network, clip.features.values).mean_cm;
  return clips.empty() ? 0.0 : sum / static_cast<double>(clips.size());
}

// The stylized clips' mean style ratio (against the network's walk target) and content distance (eq. 4,
// through the network's own encoder, which adapt keeps), as stylize runs it.
struct StyleFigures {
  double style_ratio = 0.0;
  double content_distance = 0.0;
};

StyleFigures meanStyleFigures(const nn::StyleModel& model, const std::vector<style::MotionClip>& clips) {
  const style::Stylizer stylizer(model);
  StyleFigures mean;
  for (const style::MotionClip& clip : clips) {
    const nn::StyleTarget& target = model.style_targets.back();  // the default (the walk)
    const style::StyleDistances distances =
        style::measureStyleDistances(model.loss_network, model.normalisation, clip.features.values,
                                     stylizer.stylize(clip.features, 1.0).features, target.gram);
    mean.style_ratio += distances.styleRatio();
    mean.content_distance += distances.content_after;
  }
  const double count = static_cast<double>(std::max<std::size_t>(clips.size(), 1));
  mean.style_ratio /= count;
  mean.content_distance /= count;
  return mean;
}

}  // namespace

int main(int argc, char** argv) {
  const fs::path resources = resourceDirectory().value_or(fs::path("resources"));
  fs::path models = resources / "models";
  fs::path fixtures = fs::path(MOTIONSTYLE_SHARED_DATA_DIR).parent_path() / "fixtures";
  fs::path data = fs::path(MOTIONSTYLE_SHARED_DATA_DIR) / "bandai";
  std::string style_name = "elderly";
  int loss_epochs = style::AdaptationSettings{}.epochs;
  int style_epochs = style::kDefaultStyleAdaptationEpochs;
  std::string memory_source = "shipped";
  double loss_lr = style::AdaptationSettings{}.learning_rate;
  double memory_weight = style::AdaptationSettings{}.memory_weight;
  bool replay = false;
  double replay_ratio = 1.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--models") models = v;
    else if (a == "--style") style_name = v;
    else if (a == "--fixtures") fixtures = v;
    else if (a == "--data") data = v;
    else if (a == "--loss-epochs") loss_epochs = std::stoi(v);
    else if (a == "--style-epochs") style_epochs = std::stoi(v);
    else if (a == "--memory") memory_source = v;
    else if (a == "--memory-weight") memory_weight = std::stod(v);
    else if (a == "--loss-lr") loss_lr = std::stod(v);
    else if (a == "--replay") replay = v == "on";
    else if (a == "--replay-ratio") replay_ratio = std::stod(v);
    else { std::fprintf(stderr, "unknown argument %s\n", a.c_str()); return 2; }
  }
  if (!fs::is_directory(fixtures / "cmu_walks") || !fs::exists(fixtures / "cmu" / "131_01.bvh")) {
    std::printf("skipped: the CMU fixtures are not at %s\n", fixtures.string().c_str());
    return 0;
  }
  try {
    const nn::StyleModel style_model = style::loadCompatibleStyleModel(models / (style_name + ".net"));
    style::AdaptNetworksJob job;
    job.loss.loss_network = {style_model.loss_network, style_model.normalisation, style_model.metadata};
    job.loss.loss_network_name = style_name + "'s loss network";
    job.loss.clips = newStudioClips(fixtures);
    job.loss.settings.epochs = loss_epochs;
    job.loss.settings.memory_weight = memory_weight;
    job.loss.settings.learning_rate = loss_lr;
    job.loss.settings.replay_ratio = replay_ratio;
    const fs::path d1 = data / "dataset-1" / "data", d2 = data / "dataset-2" / "data";
    if (replay)
      for (const fs::path& f : style::splitHoldout(style::findBvhFiles({d1, d2}), 10).training)
        job.loss.replay.push_back(style::loadMotionClip(f));
    if (memory_source == "bandai") {
      style::DatasetOptions as_trained;
      as_trained.features.canonical_rig = false;
      std::vector<style::MotionClip> original;
      for (const fs::path& f : style::splitHoldout(style::findBvhFiles({d1, d2}), 10).training)
        original.push_back(style::loadMotionClip(f, as_trained));
      const auto remember_start = std::chrono::steady_clock::now();
      job.loss.memory = style::rememberReconstruction(job.loss.loss_network, original, "Bandai training clips");
      std::printf("memory of %zu clips in %.1f s\n", original.size(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - remember_start).count());
    } else if (memory_source == "shipped") {
      job.loss.memory = style::findMatchingMemory(job.loss.loss_network, {});
    } else if (memory_source != "off") {
      job.loss.memory = style::loadReconstructionMemory(memory_source);
    }
    std::printf("reconstruction memory: %s; replay clips: %zu\n",
                job.loss.memory ? job.loss.memory->description.c_str() : "none", job.loss.replay.size());
    const fs::path scratch = fs::temp_directory_path() / ("motionstyle-bench-adaptation-" + std::to_string(::getpid()));
    fs::create_directories(scratch);
    job.loss.settings.output = scratch / "adapted.net";
    job.scratch = scratch;
    job.style_epochs = style_epochs;
    job.styles = {{style_name, style_model}};
    std::printf("adapting on %zu clips of CMU's studio, retraining %s (%d + %d epochs, %d threads)\n",
                job.loss.clips.size(), style_name.c_str(), loss_epochs, style_epochs, nn::computePool().threadCount());
    const auto started = std::chrono::steady_clock::now();
    const style::AdaptNetworksJob::Result result = job.run();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (result.status != style::TrainingStatus::Completed || result.styles.empty()) throw std::runtime_error("did not complete");
    std::printf("time: %.1f s for the whole action (goal: at most 180 s)\n", seconds);
    std::printf("familiarity of the ten clips: %.2f -> %.2f cm\n", result.loss.mean_before_cm, result.loss.mean_after_cm);
    const StyleFigures new_before = meanStyleFigures(style_model, job.loss.clips);
    const StyleFigures new_after = meanStyleFigures(result.styles.front().model, job.loss.clips);
    std::printf("%s style ratio on them: %.3f -> %.3f\n", style_name.c_str(), new_before.style_ratio,
                new_after.style_ratio);
    std::printf("%s content distance on them (eq. 4): %.4f -> %.4f\n", style_name.c_str(),
                new_before.content_distance, new_after.content_distance);
    if (fs::is_directory(d1) && fs::is_directory(d2)) {
      std::vector<style::MotionClip> held;
      for (const fs::path& f : style::splitHoldout(style::findBvhFiles({d1, d2}), 10).held_out) held.push_back(style::loadMotionClip(f));
      std::printf("forgetting: Bandai held-out familiarity %.2f -> %.2f cm (%zu clips)\n",
                  meanFamiliarity(job.loss.loss_network, held), meanFamiliarity(result.loss.model, held), held.size());
      // The retrained style on the Bandai clips its own training held out (train_models.sh's split:
      // every 5th normal-style dataset-2 walk, run and turn), against the same walk target.
      std::vector<fs::path> normal;
      for (const fs::path& f : style::findBvhFiles({d2})) {
        const std::string name = f.filename().string();
        for (const char* kind : {"walk_normal_", "run_normal_", "walk-turn-left_normal_", "walk-turn-right_normal_"})
          if (name.rfind(std::string("dataset-2_") + kind, 0) == 0) normal.push_back(f);
      }
      std::vector<style::MotionClip> style_held;
      for (const fs::path& f : style::splitHoldout(normal, 5).held_out) style_held.push_back(style::loadMotionClip(f));
      const StyleFigures held_before = meanStyleFigures(style_model, style_held);
      const StyleFigures held_after = meanStyleFigures(result.styles.front().model, style_held);
      std::printf("forgetting: %s style ratio on Bandai held-out %.3f -> %.3f (%zu clips)\n", style_name.c_str(),
                  held_before.style_ratio, held_after.style_ratio, style_held.size());
      // Issue 12's content goal (a new studio's content distance at most 2x Bandai's), before adapting
      // and after, each network against its own Bandai figure.
      std::printf("forgetting: %s content distance on Bandai held-out %.4f -> %.4f\n", style_name.c_str(),
                  held_before.content_distance, held_after.content_distance);
      std::printf("the ten clips' content distance over Bandai's: %.2fx -> %.2fx (goal: at most 2x)\n",
                  new_before.content_distance / held_before.content_distance,
                  new_after.content_distance / held_after.content_distance);
    }
    std::error_code ignored;
    fs::remove_all(scratch, ignored);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_adaptation: %s\n", error.what());
    return 1;
  }
  return 0;
}
