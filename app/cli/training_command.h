#pragma once
// The part train-ae and train-style share once their options are parsed: Ctrl-C handling (the first
// SIGINT cancels cleanly, keeping the checkpoint), the progress bar with ETA and loss terms, log lines,
// the outcome report (held-out files, output or checkpoint) and the divergence message.

#include "style/training.h"

namespace motionstyle::cli {

// Trains and reports. Returns the exit code: 0 done, 130 cancelled by Ctrl-C, 1 diverged (the last good
// checkpoint is kept and named). Other errors propagate (InputError, WriteError, std::invalid_argument).
int runTrainingWithProgress(const style::AutoencoderTrainingConfig& config);
int runTrainingWithProgress(const style::StyleTrainingConfig& config);

}  // namespace motionstyle::cli
