#pragma once
// The transformation network's training objective, eq. 10:
//   Loss = c * content + s * style + f * foot + b * bone + r * trajectory
// with each term as defined in losses.h, evaluated on the output T(I) of the transformation network:
// content and style through the FROZEN loss network L (its encoder), foot / bone / trajectory on the
// de-normalised frames T(I) themselves.
//
// A training loop (not here) builds StyleBatch values: per content window its contacts and bone
// lengths, L(I) computed ONCE per content clip (contentHidden), and the style Gram matrices computed
// ONCE per style clip (styleGram). accumulateObjective then runs forward + backward.

#include <vector>

#include "nn/loss_network.h"
#include "nn/losses.h"
#include "nn/transformation_network.h"

namespace motionstyle::nn {

// Per-term user weights (eq. 10). Content 1 is the paper's value; style 100 is the paper's s = 0.01
// rescaled to OUR Gram (gramMatrix divides by the frame count: the paper's squared Gram difference is
// ~120^2 times ours for a 240-frame window). The constraint terms are in cm^2 (foot, bone) and
// (cm/frame)^2 (trajectory): trajectory 0.01 lets a style change the stride, and the output keeps
// the content's path anyway (path_mode.h); foot and bone 0.03 keep feet planted and bones whole
// without holding the style back. The measurements behind each value are in docs/decisions.md.
struct LossWeights {
  double content = 1.0;
  double style = 100.0;
  double foot = 0.03;
  double bone = 0.03;
  double trajectory = 0.01;

  // Throws std::invalid_argument unless every weight is finite and >= 0.
  void validate() const;
  bool operator==(const LossWeights&) const = default;
};

struct ObjectiveTerms {  // unweighted terms and the weighted total
  double content = 0;
  double style = 0;
  double foot = 0;
  double bone = 0;
  double trajectory = 0;
  double total = 0;
};

template <typename S>
struct StyleBatch {
  int frames = 0;                   // T, frames per window (>= 1)
  Mat<S> content;                   // I: features x (B*T), normalised
  Mat<S> contacts;                  // kContactCount x (B*T), 0/1 labels of the content
  Mat<S> bone_lengths;              // kBoneCount x B, cm: the content clip's own bone lengths
  Mat<S> content_hidden;            // L(I): hidden x (B * evenFrames(T)/2)  (contentHidden)
  std::vector<Mat<S>> style_grams;  // 1 (shared) or B matrices hidden x hidden  (styleGram)

  int windows() const { return frames > 0 ? static_cast<int>(content.cols() / frames) : 0; }
  // Throws std::invalid_argument on any inconsistent shape.
  void validate(int features, int hidden) const;
};

// L(I) for a content batch: the content target of eq. 4 (compute once per clip).
template <typename S>
Mat<S> contentHidden(const LossNetwork<S>& loss_network, const Mat<S>& content, int frames);

// Gram(L(S)) of a whole style clip (features x frames, one window of any length): eq. 5's target.
template <typename S>
Mat<S> styleGram(const LossNetwork<S>& loss_network, const Mat<S>& style_clip);

// Forward T(I), eq. 10, backward: ADDS into the transformation network's parameter gradients. The loss
// network's weights are neither changed nor given gradients (only its caches are used).
template <typename S>
ObjectiveTerms accumulateObjective(TransformationNetwork<S>& transformation, LossNetwork<S>& loss_network,
                                   const StyleBatch<S>& batch, const FeatureStatistics& normalisation,
                                   const LossWeights& weights);

// The same value without gradients (validation).
template <typename S>
ObjectiveTerms evaluateObjective(const TransformationNetwork<S>& transformation, const LossNetwork<S>& loss_network,
                                 const StyleBatch<S>& batch, const FeatureStatistics& normalisation,
                                 const LossWeights& weights);

}  // namespace motionstyle::nn
