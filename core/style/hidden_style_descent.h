#pragma once
// Adam on the loss network's hidden units H (hidden x pooled frames) of eq. 10's content and style
// terms, the objective both the optimisation method (optimization_transfer.h, stage 1) and the style
// refinement (style_refinement.h) descend:
//   E(H) = c * mean((H - H_content)^2) + s * mean((Gram(H) - G)^2)
// (eq. 4 with H_content = L(C); eq. 5 with Gram as nn::gramMatrix, G the style clip's). No network
// pass per step: only H's Gram matrix, so a step costs hidden^2 x frames / 2 multiply-adds for the Gram
// matrix (symmetric: its lower half) and hidden^2 x frames for the gradient, both split over the cores.

#include <vector>

#include "nn/adam.h"
#include "nn/tensor.h"

namespace motionstyle::style {

class HiddenStyleDescent {
 public:
  // start and content_hidden: hidden x pooled frames (the same shape); style_gram: hidden x hidden;
  // weights c, s >= 0 (not both 0) and learning_rate > 0. Throws std::invalid_argument otherwise.
  HiddenStyleDescent(nn::Mat<float> start, nn::Mat<float> content_hidden, nn::Mat<float> style_gram,
                     double content_weight, double style_weight, double learning_rate);
  HiddenStyleDescent(const HiddenStyleDescent&) = delete;  // the optimiser points at hidden_
  HiddenStyleDescent& operator=(const HiddenStyleDescent&) = delete;

  // Adds E's gradient at the current H into hidden().grad and returns E; content() and style() then
  // hold the unweighted terms. A caller with further terms (the optimisation's constraint pass) calls
  // zeroGrad(), adds their gradients and this one, then applyStep().
  double addTerms();
  void zeroGrad() { optimizer_.zeroGrad(); }
  void applyStep() { optimizer_.step(); }
  // zeroGrad(), addTerms(), applyStep(): one plain step; returns E before it.
  double step();

  nn::Parameter<float>& hidden() { return hidden_; }
  const nn::Mat<float>& value() const { return hidden_.value; }
  double content() const { return content_; }
  double style() const { return style_; }

 private:
  double addStyleTerm();  // eq. 5's value; adds its gradient

  nn::Parameter<float> hidden_;
  nn::Mat<float> content_hidden_;
  nn::Mat<float> style_gram_;
  float content_weight_, style_weight_;
  nn::Adam<float> optimizer_;
  double content_ = 0, style_ = 0;
  std::vector<nn::Mat<float>> gram_parts_;  // scratch: the Gram matrix's partial sums by columns
  nn::Mat<float> gram_difference_;          // scratch: Gram(H) - G
};

}  // namespace motionstyle::style
