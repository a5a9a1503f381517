#include "style/stylize_cleanup_job.h"

#include <chrono>
#include <stdexcept>

#include "features/feature_layout.h"
#include "style/cancellation.h"
#include "style/stylized_cleanup.h"

namespace motionstyle::style {

void StylizeCleanupJob::validate() const {
  if (!stylized && !stylizer) throw std::invalid_argument("no style network and no stylized clip to clean up");
  if (!(strength >= 0.0 && strength <= 1.0)) throw std::invalid_argument("the strength must be in [0, 1]");
  if (!(output_fps >= 0.0)) throw std::invalid_argument("the output rate must be 0 (the content's) or positive");
  if (contact_overrides.size() > 0 &&
      (contact_overrides.rows() != content.frameCount() || contact_overrides.cols() != kContactCount))
    throw std::invalid_argument("the contact overrides must be content frames x 4");
}

StylizeCleanupResult StylizeCleanupJob::run(const std::atomic<bool>* cancel) const {
  validate();
  const auto start = std::chrono::steady_clock::now();
  StylizeCleanupResult result;
  if (stylized) {
    result.stylized = *stylized;
  } else {
    const MotionFeatures features = extractFeatures(content, mapping);
    throwIfCancelled(cancel);
    if (!memory) {
      result.stylized = stylizer->stylize(features, strength, path);
    } else {
      if (memory->stylizer != stylizer || memory->features.rows() != features.values.rows() ||
          memory->features.cols() != features.values.cols() || memory->features != features.values) {
        memory->stylizer = nullptr;  // an exception below leaves no stale pairing
        memory->network_output = stylizer->networkOutput(features.values);
        memory->features = features.values;
        memory->stylizer = stylizer;
      }
      result.stylized = stylizer->stylize(features, memory->network_output, strength, path);
    }
  }
  throwIfCancelled(cancel);
  StylizedCleanup cleanup = cleanUpStylizedClip(content, mapping, result.stylized, options, output_fps, contact_overrides,
                                                CleanupControl{cancel, memory ? &memory->cleanup : nullptr});
  throwIfCancelled(cancel);
  result.cleaned = std::move(cleanup.motion);
  result.report = std::move(cleanup.report);
  result.raw_metrics = std::move(cleanup.raw);
  result.cleaned_metrics = std::move(cleanup.cleaned);
  result.contacts = std::move(cleanup.contacts);
  result.cleanup_fps = cleanup.fps;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace motionstyle::style
