#include "style/evaluation_job.h"

#include <stdexcept>

#include "style/cancellation.h"

namespace motionstyle::style {

void EvaluationJob::validate() const {
  if (clips.empty()) throw std::invalid_argument("no clips to evaluate");
  if (styles.empty()) throw std::invalid_argument("no style clip to measure against");
  refinement.validate();
}

EvaluationReport EvaluationJob::run(const std::atomic<bool>* cancel) const {
  validate();
  const DatasetOptions style_options = styleClipOptions(dataset, network.loss_network.shape().width);
  std::vector<MotionClip> style_clips;
  for (const StyleSource& source : styles) style_clips.push_back(loadMotionClip(source.file, style_options));
  const std::vector<MotionClip> content = loadMotionClips(clips, dataset);
  std::vector<std::string> labels;
  for (const MotionClip& clip : content) labels.push_back(clip.labels.content);
  const std::vector<int> pairing = pairStyles(labels, styles);
  throwIfCancelled(cancel);
  return evaluateStyleNetwork(loss_network, network, content, style_clips, pairing, path, refinement);
}

}  // namespace motionstyle::style
