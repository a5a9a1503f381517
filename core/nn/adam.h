#pragma once
// Adam (Kingma & Ba 2014) with bias correction, over a list of Parameters (tensor.h):
//   m = b1 m + (1 - b1) g;  v = b2 v + (1 - b2) g^2
//   theta -= lr * (m / (1 - b1^t)) / (sqrt(v / (1 - b2^t)) + eps)
// step() reads the accumulated gradients and does not clear them: call zeroGrad() before the next
// accumulation (llm.c convention). The state (moments and step count) can be read and restored, so a
// training checkpoint continues exactly where it stopped.

#include <vector>

#include "nn/tensor.h"

namespace motionstyle::nn {

struct AdamOptions {
  double learning_rate = 1e-3;
  double beta1 = 0.9;
  double beta2 = 0.999;
  double epsilon = 1e-8;

  // Throws std::invalid_argument unless lr > 0, 0 <= beta < 1 and eps > 0 (all finite).
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

 private:
  std::vector<Parameter<S>*> parameters_;
  std::vector<Mat<S>> first_moment_;
  std::vector<Mat<S>> second_moment_;
  AdamOptions options_;
  long steps_ = 0;
};

}  // namespace motionstyle::nn
