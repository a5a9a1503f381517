#pragma once
// The optimisation method of Holden et al. 2016 (the paper's comparison, "Holden method"): no training,
// one style clip, an optimisation per content clip.
//
// Stage 1 (style), in the loss network's hidden units H (hidden x pooled frames):
//   minimise  s' * mean((Gram(H) - Gram(L(S)))^2) + c' * mean((H - L(C))^2),   s' + c' = 1
// (s, c renormalised as in the 2016 code; Gram as nn::gramMatrix, divided by the frame count) with
// Adam, `iterations` steps at `learning_rate`. The motion is decode(H) (eq. 2); no network pass is
// needed per iteration, only the Gram matrix.
// Stage 2 (constraints): `constraint_iterations` more Adam steps on H, now through the decoder, of
//   stage-1 objective + foot * eq. 7 + bone * eq. 8 + trajectory * eq. 9   on decode(H)
// with the content's contacts, bone lengths and root velocities as targets. The stage-1 terms stay in the
// objective so that the constraint pass trades against content and style rather than ignoring them
// (the 2016 code ran the constraint pass on the constraints alone).
//
// START: H = L(C), the content's own hidden units, instead of the 2016 code's noise: it starts at the
// content term's minimum and needs no seed (ends far closer to the content for the same style term:
// docs/decisions.md). OptimizationOptions::start_from_noise reproduces the 2016 start for comparison.
//
// Progress and cancellation as in training: `cancel` is polled every iteration (milliseconds each).

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>

#include "features/representation.h"
#include "nn/network_file.h"
#include "style/stylizer.h"

namespace motionstyle::style {

struct OptimizationOptions {
  int iterations = 250;           // stage 1
  double learning_rate = 0.01;    // Adam, stage 1 and 2
  double content_weight = 1.0;    // c, before renormalisation: how much of the content's hidden units stay
  // s, before renormalisation: how hard the Gram matrix is pulled to the style clip's. 30 (s' = 0.97)
  // adds as much style as the style networks do (the figures per weight: docs/decisions.md).
  double style_weight = 30.0;
  int constraint_iterations = 100;
  // Stage 2 only, added to stage 1's objective: planted feet stay planted (eq. 7), bones keep their
  // lengths (eq. 8), the root keeps the content's velocities (eq. 9).
  double foot_weight = 0.1;       // eq. 7, per cm^2
  double bone_weight = 0.1;       // eq. 8, per cm^2
  double trajectory_weight = 0.1; // eq. 9, per (cm/frame)^2
  bool start_from_noise = false;  // the 2016 start: N(0, 1) in normalised frames, encoded
  PathMode path = PathMode::Content;  // whose root path the result follows (path_mode.h)
  std::uint32_t seed = 1;         // for start_from_noise

  // Stage 1 gets `iterations`, stage 2 the defaults' share of them (100 per 250, at least 1): one knob
  // for a front end that offers one.
  void setIterations(int iterations);
  void validate() const;  // std::invalid_argument naming the field
};

struct OptimizationProgress {
  std::string stage;      // "style" or "constraints"
  int iteration = 0;      // 1-based within the stage
  int iterations = 0;     // of the stage
  double total = 0;       // weighted objective
  double content = 0, style = 0, foot = 0, bone = 0, trajectory = 0;  // unweighted terms
  double elapsed_seconds = 0;
};

struct OptimizationCallbacks {
  std::function<void(const OptimizationProgress&)> progress;
  const std::atomic<bool>* cancel = nullptr;
};

struct OptimizationResult {
  bool cancelled = false;
  StylizedClip clip;                  // empty when cancelled
  OptimizationProgress final_terms;   // of the last iteration
  double seconds = 0;
};

// Feature-level core: content and style are 66 x frames in representation units, content_contacts
// 4 x content frames; returns decode(H) in representation units. Throws InputError naming `style_name`
// for a style clip shorter than the filter width, std::invalid_argument for bad shapes.
OptimizationResult optimizeStyleTransfer(const nn::LossNetworkModel& loss_network, const Eigen::MatrixXd& content,
                                         const Eigen::MatrixXd& content_contacts, const Eigen::MatrixXd& style,
                                         const std::string& style_name, const OptimizationOptions& options = {},
                                         const OptimizationCallbacks& callbacks = {});

// The whole clip, with world positions in the content's file space (as Stylizer::stylize).
OptimizationResult optimizeStyleTransfer(const nn::LossNetworkModel& loss_network, const MotionFeatures& content,
                                         const MotionFeatures& style, const std::string& style_name,
                                         const OptimizationOptions& options = {},
                                         const OptimizationCallbacks& callbacks = {});

}  // namespace motionstyle::style
