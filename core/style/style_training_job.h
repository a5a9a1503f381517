#pragma once
// StyleTrainingJob: trainStyleNetwork (training.h) as motionstyle-cli train-style and the app run it:
// a new network, a warm start (Retrain) or a resumed run, with an optional live preview of each
// snapshot on one content clip, and a cancelled run's network of its last completed epoch kept as the
// result. The job shape of every long
// operation (plain inputs, validate(), run() with callbacks and a cancel flag, a typed Result).

#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

#include "nn/network_file.h"
#include "style/stylizer.h"
#include "style/training.h"

namespace motionstyle::style {

struct StyleTrainingJob {
  StyleTrainingConfig config;                 // settings.checkpoint must name a writable file
  std::filesystem::path preview_content;      // a BVH stylized with each snapshot; empty = no preview
  double preview_interval_seconds = 1.0;      // at most one preview per this many seconds (a quick
                                              // run's epoch takes about 1.3 s)

  void validate() const { config.validate(); }  // std::invalid_argument naming the bad field

  // The run's account (status, epochs, history, training and held-out files, seconds: training.h)
  // with the network as a shared, immutable model.
  struct Result : TrainingResult {
    // Completed: the trained network. Cancelled: the network of the last completed epoch (the same as
    // the checkpoint file), or null when no epoch completed.
    std::shared_ptr<const nn::StyleModel> model;
    std::vector<int> pairing;          // per training clip: index into config.styles (or stored targets)
    std::filesystem::path checkpoint;  // this run's checkpoint (absent when no epoch ended)
  };
  // The snapshot of `epoch` applied to preview_content at strength 1; called on the training thread.
  using PreviewCallback = std::function<void(std::shared_ptr<const StylizedClip> clip, int epoch)>;

  // Validates and trains. A preview clip that cannot be read only loses the preview (said through
  // callbacks.log). Throws what trainStyleNetwork throws: InputError, WriteError, TrainingDiverged.
  Result run(const TrainingCallbacks& callbacks = {}, const PreviewCallback& preview = {}) const;
};

}  // namespace motionstyle::style
