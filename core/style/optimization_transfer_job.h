#pragma once
// OptimizationTransferJob: the optimisation method (optimization_transfer.h) from files, as the CLI's
// `transfer` and the app's Optimise tab run it: load the content clip and the style clip, optimise,
// and measure how much style was added (evaluation.h's distances). The job shape of every long
// operation (plain inputs, validate(), run() with callbacks and a cancel flag, a typed Result).

#include <filesystem>
#include <optional>

#include "nn/network_file.h"
#include "style/evaluation.h"
#include "style/motion_dataset.h"
#include "style/optimization_transfer.h"

namespace motionstyle::style {

struct OptimizationTransferJob {
  nn::LossNetworkModel loss_network;
  std::filesystem::path content;  // BVH
  std::filesystem::path style;    // BVH, at least the loss network's filter width long
  OptimizationOptions options;
  DatasetOptions dataset;         // how both clips are read (unit)

  void validate() const;  // options.validate(), and both files named: std::invalid_argument

  struct Result {
    bool cancelled = false;
    std::optional<StylizedClip> clip;  // absent when cancelled
    StyleDistances distances;          // content -> result against the style clip (not when cancelled)
    double seconds = 0.0;
  };
  // Throws InputError for a clip that cannot be read or is too short.
  Result run(const OptimizationCallbacks& callbacks = {}) const;
};

}  // namespace motionstyle::style
