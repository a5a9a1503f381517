#pragma once
// EvaluationJob: motionstyle-cli eval's report (evaluation.h) from files: the evaluated clips (files
// or folders) are read, each is paired with a style clip by its content label (style_pairing.h), and
// evaluateStyleNetwork measures the network on them. The job shape of every long operation (plain
// inputs, validate(), run() with a cancel flag, a typed result).

#include <atomic>
#include <filesystem>
#include <vector>

#include "nn/network_file.h"
#include "style/evaluation.h"
#include "style/motion_dataset.h"
#include "style/path_mode.h"
#include "style/style_pairing.h"

namespace motionstyle::style {

struct EvaluationJob {
  nn::LossNetworkModel loss_network;          // judges the reconstruction figures (familiarity)
  nn::StyleModel network;                     // the style network evaluated; its own loss network
                                              // measures the distances
  std::vector<std::filesystem::path> clips;   // content clips, files or folders (recursively)
  std::vector<StyleSource> styles;            // the style clips and their pairing, at least one
  DatasetOptions dataset;                     // how the clips are read (unit)
  PathMode path = PathMode::Content;          // whose root path the judged output follows
  StyleRefinement refinement;                 // as stylize runs the network (style_refinement.h)

  // std::invalid_argument: no clip or no style clip.
  void validate() const;

  // Validates, reads and pairs the clips, evaluates. The report names no files (the caller fills
  // loss_network_file and network_file). Throws InputError for a clip that cannot be read or a
  // label no style clip pairs with, OperationCancelled when `cancel` is seen before the evaluation.
  EvaluationReport run(const std::atomic<bool>* cancel = nullptr) const;
};

}  // namespace motionstyle::style
