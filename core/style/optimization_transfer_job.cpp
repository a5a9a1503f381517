#include "style/optimization_transfer_job.h"

#include <chrono>
#include <stdexcept>

#include "style/cancellation.h"

namespace motionstyle::style {

void OptimizationTransferJob::validate() const {
  options.validate();
  if (content.empty()) throw std::invalid_argument("no content clip");
  if (style.empty()) throw std::invalid_argument("no style clip");
}

OptimizationTransferJob::Result OptimizationTransferJob::run(const OptimizationCallbacks& callbacks) const {
  validate();
  const auto started = std::chrono::steady_clock::now();
  Result result;
  const MotionClip content_clip = loadMotionClip(content, dataset);
  const MotionClip style_clip = loadMotionClip(style, styleClipOptions(dataset, loss_network.network.shape().width));
  if (cancelRequested(callbacks.cancel)) {
    result.cancelled = true;
    return result;
  }
  OptimizationResult optimised =
      optimizeStyleTransfer(loss_network, content_clip.features, style_clip.features, style.string(), options, callbacks);
  result.cancelled = optimised.cancelled;
  if (!optimised.cancelled) {
    result.distances = measureStyleDistances(
        loss_network.network, loss_network.normalisation, content_clip.features.values, optimised.clip.features,
        styleGramOf(loss_network.network, loss_network.normalisation, style_clip.features.values));
    result.clip = std::move(optimised.clip);
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return result;
}

}  // namespace motionstyle::style
