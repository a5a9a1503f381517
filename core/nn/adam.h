#pragma once
// Adam (Kingma & Ba 2014) with bias correction, over a list of Parameters (tensor.h):
//   m = b1 m + (1 - b1) g;  v = b2 v + (1 - b2) g^2
//   theta -= lr * (m / (1 - b1^t)) / (sqrt(v / (1 - b2^t)) + eps)
// step() reads the accumulated gradients and does not clear them: call zeroGrad() before the next
// accumulation (llm.c convention).
//
// Optional outlier clipping (gradient_clip = k > 0): after clip_warmup_steps steps, a parameter
// tensor's gradient whose norm exceeds k x its expected norm sqrt(sum v^), v^ = v / (1 - b2^(t-1)) being
// Adam's own running estimate of E[g^2] before this step, is scaled down to k x that norm before it
// enters the moments. Ordinary batches sit near the expected norm; one batch of extreme windows (the
// Bandai data has spins whose turning velocity is 75 standard deviations out) would otherwise inflate
// m and v at once and throw the network off (the loss network's loss went from 0.04 to 14-55 in one
// epoch). Stateless beyond the moments, so a restored optimiser clips exactly as the original.
//
// The state (moments and step count) can be read and restored, so a training checkpoint continues
// exactly where it stopped.

#include <vector>

#include "nn/tensor.h"

namespace motionstyle::nn {

struct AdamOptions {
  double learning_rate = 1e-3;
  double beta1 = 0.9;
  double beta2 = 0.999;
  double epsilon = 1e-8;
  double gradient_clip = 0.0;   // k (see above); 0 = off
  long clip_warmup_steps = 20;  // steps before clipping starts (v^ needs a few batches)

  // Throws std::invalid_argument unless lr > 0, 0 <= beta < 1, eps > 0, gradient_clip >= 0 (all
  // finite) and clip_warmup_steps >= 0.
  void validate() const;
};

template <typename S>
class Adam {
 public:
  // The parameters must outlive the optimiser; their shapes must not change.
  Adam(std::vector<Parameter<S>*> parameters, AdamOptions options = {});

  void step();
  void zeroGrad();

  long stepCount() const { return steps_; }
  const AdamOptions& options() const { return options_; }
  // One first and one second moment per parameter, in the parameters' order and shapes.
  const std::vector<Mat<S>>& firstMoments() const { return first_moment_; }
  const std::vector<Mat<S>>& secondMoments() const { return second_moment_; }
  // Continues from a saved state: the next step() is step `steps + 1` with these moments. Throws
  // std::invalid_argument when steps < 0 or the moments' count or shapes differ from the parameters'.
  void restore(long steps, std::vector<Mat<S>> first, std::vector<Mat<S>> second);
  // For learning-rate schedules; validated.
  void setLearningRate(double learning_rate);
  // How many parameter tensors the last step() clipped (0 without clipping).
  int clippedInLastStep() const { return clipped_in_last_step_; }

 private:
  std::vector<Parameter<S>*> parameters_;
  std::vector<Mat<S>> first_moment_;
  std::vector<Mat<S>> second_moment_;
  AdamOptions options_;
  long steps_ = 0;
  int clipped_in_last_step_ = 0;
};

}  // namespace motionstyle::nn
