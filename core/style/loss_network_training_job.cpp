#include "style/loss_network_training_job.h"

#include <utility>

namespace motionstyle::style {

LossNetworkTrainingJob::Result LossNetworkTrainingJob::run(const TrainingCallbacks& callbacks) const {
  validate();
  LossNetworkTrainingResult trained = trainLossNetwork(config, callbacks);
  Result result;
  result.model = std::make_shared<const nn::LossNetworkModel>(std::move(trained.model));
  result.checkpoint = config.settings.checkpointPath();
  static_cast<TrainingResult&>(result) = std::move(static_cast<TrainingResult&>(trained));
  return result;
}

}  // namespace motionstyle::style
