#pragma once
// LossNetworkTrainingJob: trainLossNetwork (training.h) as motionstyle-cli train-loss-network runs it:
// a new loss network (eq. 1-3), a warm start (settings.init) or a resumed run (settings.resume). The
// job shape of every long operation (plain inputs, validate(), run() with callbacks and a cancel flag,
// a typed Result apart from the inputs).

#include <filesystem>
#include <memory>

#include "nn/network_file.h"
#include "style/training.h"

namespace motionstyle::style {

struct LossNetworkTrainingJob {
  LossNetworkTrainingConfig config;  // settings.output and the checkpoint must be writable

  void validate() const { config.validate(); }  // std::invalid_argument naming the bad field

  // The run's account (status, epochs, history, training and held-out files, seconds: training.h)
  // with the network as a shared, immutable model.
  struct Result : TrainingResult {
    // Completed: the trained network (also written to settings.output). Cancelled: the weights after
    // the last completed step (the checkpoint file holds those of the last completed epoch).
    std::shared_ptr<const nn::LossNetworkModel> model;
    std::filesystem::path checkpoint;  // this run's checkpoint (absent when no epoch ended)
  };

  // Validates and trains. Throws what trainLossNetwork throws: InputError (unreadable data, a
  // checkpoint of another shape), WriteError, TrainingDiverged (naming the kept checkpoint).
  Result run(const TrainingCallbacks& callbacks = {}) const;
};

}  // namespace motionstyle::style
