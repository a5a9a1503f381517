#include "style/style_training_job.h"

#include <chrono>
#include <exception>
#include <optional>
#include <utility>

#include "style/cancellation.h"
#include "style/motion_dataset.h"

namespace motionstyle::style {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

}  // namespace

StyleTrainingJob::Result StyleTrainingJob::run(const TrainingCallbacks& callbacks, const PreviewCallback& preview) const {
  validate();
  const auto started = Clock::now();
  const auto log = [&](const std::string& text) {
    if (callbacks.log) callbacks.log(text);
  };
  std::optional<MotionClip> preview_clip;
  if (preview && !preview_content.empty()) {
    try {
      preview_clip = loadMotionClip(preview_content, config.settings.dataset);
    } catch (const std::exception& error) {
      log(std::string("no live preview: ") + error.what());
    }
  }
  std::shared_ptr<const nn::StyleModel> last_snapshot;
  double last_preview = -1e9;
  TrainingCallbacks inner = callbacks;
  inner.style_snapshot = [&](const nn::StyleModel& model) {
    last_snapshot = std::make_shared<const nn::StyleModel>(model);
    if (callbacks.style_snapshot) callbacks.style_snapshot(model);
    const double now = secondsSince(started);
    if (!preview_clip || now - last_preview < preview_interval_seconds || cancelRequested(callbacks.cancel)) return;
    last_preview = now;
    // Between epochs the compute pool is free and a stylize takes milliseconds per thousand frames.
    try {
      const Stylizer stylizer(model);
      preview(std::make_shared<const StylizedClip>(stylizer.stylize(preview_clip->features, 1.0)),
              model.metadata.training.epochs);
    } catch (const std::exception& error) {
      log(std::string("live preview failed: ") + error.what());
      preview_clip.reset();
    }
  };

  StyleTrainingResult trained = trainStyleNetwork(config, inner);
  Result result;
  result.pairing = std::move(trained.pairing);
  result.checkpoint = config.settings.checkpointPath();
  if (trained.status == TrainingStatus::Completed)
    result.model = std::make_shared<const nn::StyleModel>(std::move(trained.model));
  else
    result.model = last_snapshot;  // the weights after the last completed epoch = the checkpoint
  static_cast<TrainingResult&>(result) = std::move(static_cast<TrainingResult&>(trained));
  return result;
}

}  // namespace motionstyle::style
