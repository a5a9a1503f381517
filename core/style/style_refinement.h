#pragma once
// Style refinement: the transformation network T is an amortised solver of eq. 10, trained on one
// studio's clips; on a clip unlike them it stops short of the style. A few steps of the same
// objective's content and style terms on this clip's own hidden units (HiddenStyleDescent), from
// where T left them, finish the job:
//   H0 = encode(T(x)) (where the content crouches, its own encode(x): transformationShare below),
//   H = H0 - Adam steps on  c * mean((H - encode(x))^2) + s * mean((Gram(H) - G)^2), until converged,
//   output = decode(H)
// with c, s eq. 10's content and style weights (what T was trained on) and G the network's stored
// style target of the clip's kind of locomotion (locomotion_kind.h: the one training paired such clips
// with), or the one nearest Gram(H0) for a network whose targets carry none of the kinds' labels.
// Zero iterations give decode(encode(T(x))), the network's output as it was, crouch or not. Why here
// and not in the training: augmenting one actor's content did not close the gap to other studios
// (docs/decisions.md).

#include <Eigen/Core>
#include <atomic>
#include <vector>

#include "nn/network_file.h"
#include "nn/tensor.h"

namespace motionstyle::style {

struct StyleRefinement {
  static constexpr int kMaxIterations = 10000;
  static constexpr int kConvergenceSteps = 10;  // the span converged_fraction is judged over
  // The most Adam steps; 0 = T's output as it is. The steps stop before that once kConvergenceSteps
  // steps lowered the objective by less than converged_fraction of it: a clip like T's training data
  // converges in 40-60 steps, one of another studio may still fall by 1-6 % per 10 steps at 120 (T
  // stops further short of the style there: docs/decisions.md, "The refinement run to convergence").
  int iterations = 120;
  double converged_fraction = 0.01;  // in [0, 1); 0 runs every step
  double learning_rate = 0.03;   // in normalised hidden units per step
  double content_weight = 1.0;   // eq. 10's c (nn::LossWeights)
  double style_weight = 100.0;   // eq. 10's s
  // (The target is each clip's: Stylizer::aimedKind, read from it or the caller's choice.)

  // Throws std::invalid_argument naming the field (iterations in [0, kMaxIterations], converged_fraction
  // in [0, 1)).
  void validate() const;
};

// The index of the target whose Gram matrix is nearest Gram(hidden) (mean squared difference);
// -1 when there are none. hidden: hidden x frames; every target hidden x hidden.
int nearestStyleTarget(const std::vector<nn::StyleTarget>& targets, const nn::Mat<float>& hidden);

// Where the refinement starts, per pooled column k (clip frames 2k and 2k + 1): T's share u_k of
//   H0_k = Hc_k + u_k (encode(T(x))_k - Hc_k),   Hc = encode(x)
// u = smoothstep((r - kCrouchedHipRatio) / (kUprightHipRatio - kCrouchedHipRatio)) clamped to [0, 1], r the
// content's hip height over the reference leg length (the mean of the column's two frames). Why: T
// learnt upright locomotion only and stands a kneeling or crouching character up (CMU 131_01's kneel,
// hips 0.51: T's output hips at 0.99); started from the content's own hidden units there, the
// refinement styles the kneel instead. No Bandai locomotion clip's hips go below 0.83 nor a plain CMU
// walk's or run's below 0.88, so they start where T left them (docs/decisions.md, "A kneel kept").
constexpr double kUprightHipRatio = 0.80;   // at and above: T's output (u = 1)
constexpr double kCrouchedHipRatio = 0.65;  // at and below: the content's (u = 0)

// u for `columns` pooled columns of a clip whose features (66 x frames) are `content`; a column past
// the clip's last frame reads that frame. Throws std::invalid_argument when content has not 66 rows or
// no frame, or columns < 0.
std::vector<float> transformationShare(const Eigen::MatrixXd& content, Eigen::Index columns);

// Refines `hidden` (hidden x frames, T's output encoded) in place toward `target` with content
// `content_hidden` (the same shape), until converged or refinement.iterations steps; returns the steps
// run. Throws std::invalid_argument for mismatched shapes and OperationCancelled when `cancel` is set
// before a step (a step is about 0.5 ms on 600 frames).
int refineHiddenUnits(nn::Mat<float>& hidden, const nn::Mat<float>& content_hidden, const nn::Mat<float>& target,
                       const StyleRefinement& refinement, const std::atomic<bool>* cancel = nullptr);

}  // namespace motionstyle::style
