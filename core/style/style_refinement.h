#pragma once
// Style refinement: the transformation network T is an amortised solver of eq. 10, trained on one
// studio's clips; on a clip unlike them it stops short of the style. A few steps of the same
// objective's content and style terms on this clip's own hidden units (HiddenStyleDescent), from
// where T left them, finish the job:
//   H0 = encode(T(x)),  H = H0 - Adam steps on  c * mean((H - encode(x))^2) + s * mean((Gram(H) - G)^2),
//   output = decode(H)
// with c, s eq. 10's content and style weights (what T was trained on) and G the network's stored
// style target nearest to Gram(H0). Zero iterations give decode(H0), the network's output as it was. Why here and not in the
// training: augmenting one actor's content did not close the gap to other studios (docs/decisions.md).

#include <atomic>
#include <vector>

#include "nn/network_file.h"
#include "nn/tensor.h"

namespace motionstyle::style {

struct StyleRefinement {
  static constexpr int kMaxIterations = 10000;
  int iterations = 30;           // Adam steps; 0 = T's output as it is
  double learning_rate = 0.03;   // in normalised hidden units per step
  double content_weight = 1.0;   // eq. 10's c (nn::LossWeights)
  double style_weight = 100.0;   // eq. 10's s

  // Throws std::invalid_argument naming the field (iterations in [0, kMaxIterations]).
  void validate() const;
};

// The index of the target whose Gram matrix is nearest Gram(hidden) (mean squared difference);
// -1 when there are none. hidden: hidden x frames; every target hidden x hidden.
int nearestStyleTarget(const std::vector<nn::StyleTarget>& targets, const nn::Mat<float>& hidden);

// Refines `hidden` (hidden x frames, T's output encoded) in place toward `target` with content
// `content_hidden` (the same shape). Throws std::invalid_argument for mismatched shapes and
// OperationCancelled when `cancel` is set before a step (a step is about 1 ms on 500 frames).
void refineHiddenUnits(nn::Mat<float>& hidden, const nn::Mat<float>& content_hidden, const nn::Mat<float>& target,
                       const StyleRefinement& refinement, const std::atomic<bool>* cancel = nullptr);

}  // namespace motionstyle::style
