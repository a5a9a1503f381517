#pragma once
// The least content distance at which a set of clips reaches a mean style ratio, measured where
// eval_generalisation measures both (style/evaluation.h): in the style network's loss network's
// hidden units H = enc(C), content distance mean((H' - H)^2), style distance mean((Gram(H') - G_s)^2),
// style ratio = style distance at H' / style distance at H.
//
// Two frontiers:
//   - FrontierSpace::HiddenUnits: H' free of everything else a stylized clip must be (the encoding of a
//     motion, its bones, contacts and kept path), so no method reaches a lower content distance at the
//     same ratio: what a goal that asks for both figures can ask of any method;
//   - FrontierSpace::Motions: H' = enc(X) for a motion X (normalised features, its bones, contacts and
//     path free): what an optimisation of the output motion itself, through the encoder, reaches (a
//     local optimum from the content, so an upper bound of the least).
// Per clip, H' minimises the Lagrangian
//   mean((H' - H)^2) + lambda_i * mean((Gram(H') - G_s)^2),  lambda_i = mu / style_before_i,
// by L-BFGS from H (from X = the content); one mu for every clip of a set is the allocation of style over the clips that
// minimises the mean content distance at the mean ratio it reaches (the ratio is linear in each clip's
// style distance). mu is found by the secant method on log mu against log mean ratio.
// Why: issue 12 asks other studios' clips for both a style ratio within 1.25x and a content distance
// within 2x of Bandai's; this says whether any method can (docs/decisions.md, "The least content
// distance at a style ratio").

#include <Eigen/Core>
#include <vector>

#include "nn/loss_network.h"

namespace motionstyle::bench {

enum class FrontierSpace { HiddenUnits, Motions };

struct FrontierClip {
  Eigen::MatrixXd hidden;      // enc(C): hidden units x pooled frames
  Eigen::MatrixXd style_gram;  // G_s: hidden x hidden (nn::gramMatrix of the paired style clip)
  Eigen::MatrixXd features;    // C normalised (features x frames): FrontierSpace::Motions' start
  const nn::LossNetwork<float>* encoder = nullptr;  // enc, for FrontierSpace::Motions
};

struct FrontierPoint {
  double mu = 0.0;
  double mean_style_ratio = 1.0;
  double mean_content_distance = 0.0;
  int solves = 0;  // L-BFGS solves over the set
};

// The point of the frontier whose mean style ratio is `wanted_ratio` (within 0.5 %, or the closest of at
// most 14 secant steps). Throws std::invalid_argument for no clips, a clip whose shapes disagree or
// that already sits at its style (style distance 0), no encoder or features for FrontierSpace::Motions,
// or a wanted ratio outside (0, 1).
FrontierPoint leastContentAtStyleRatio(const std::vector<FrontierClip>& clips, double wanted_ratio,
                                       FrontierSpace space = FrontierSpace::HiddenUnits);

}  // namespace motionstyle::bench
