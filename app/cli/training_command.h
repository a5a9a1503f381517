#pragma once
// The part train-loss-network and train-style share once their options are parsed: Ctrl-C handling (the first
// SIGINT cancels cleanly, keeping the checkpoint), the progress bar with ETA and loss terms, log lines,
// the outcome report (held-out files, output or checkpoint) and the divergence message.

#include "style/loss_network_training_job.h"
#include "style/style_training_job.h"

namespace motionstyle::cli {

// Runs the job (the same core job the app runs) and reports. Returns the exit code: 0 done, 130 cancelled by Ctrl-C, 1 diverged (the last good
// checkpoint is kept and named). Other errors propagate (InputError, WriteError, std::invalid_argument).
int runTrainingWithProgress(const style::LossNetworkTrainingJob& job);
int runTrainingWithProgress(const style::StyleTrainingJob& job);

}  // namespace motionstyle::cli
