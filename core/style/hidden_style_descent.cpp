#include "style/hidden_style_descent.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "nn/losses.h"

namespace motionstyle::style {
namespace {

nn::Parameter<float> startingAt(nn::Mat<float> start) {
  nn::Parameter<float> hidden;
  hidden.name = "hidden";
  hidden.value = std::move(start);
  hidden.zeroGrad();
  return hidden;
}

void requireValid(const nn::Mat<float>& start, const nn::Mat<float>& content_hidden, const nn::Mat<float>& style_gram,
                  double content_weight, double style_weight) {
  if (start.rows() < 1 || start.cols() < 1 || content_hidden.rows() != start.rows() ||
      content_hidden.cols() != start.cols() || style_gram.rows() != start.rows() || style_gram.cols() != start.rows())
    throw std::invalid_argument("HiddenStyleDescent: start and content hidden x frames, the Gram hidden x hidden");
  if (!std::isfinite(content_weight) || !std::isfinite(style_weight) || content_weight < 0 || style_weight < 0 ||
      content_weight + style_weight <= 0)
    throw std::invalid_argument("HiddenStyleDescent: weights finite, >= 0 and not both 0");
}

}  // namespace

HiddenStyleDescent::HiddenStyleDescent(nn::Mat<float> start, nn::Mat<float> content_hidden, nn::Mat<float> style_gram,
                                       double content_weight, double style_weight, double learning_rate)
    : hidden_((requireValid(start, content_hidden, style_gram, content_weight, style_weight), startingAt(std::move(start)))),
      content_hidden_(std::move(content_hidden)),
      style_gram_{std::move(style_gram)},
      content_weight_(static_cast<float>(content_weight)),
      style_weight_(static_cast<float>(style_weight)),
      optimizer_({&hidden_}, nn::AdamOptions{learning_rate}) {}

double HiddenStyleDescent::addTerms() {
  const int frames = static_cast<int>(hidden_.value.cols());
  content_ = static_cast<double>(nn::meanSquaredError(hidden_.value, content_hidden_, content_weight_, &hidden_.grad));
  style_ = static_cast<double>(nn::styleLoss(hidden_.value, frames, style_gram_, style_weight_, &hidden_.grad));
  return static_cast<double>(content_weight_) * content_ + static_cast<double>(style_weight_) * style_;
}

double HiddenStyleDescent::step() {
  zeroGrad();
  const double value = addTerms();
  applyStep();
  return value;
}

}  // namespace motionstyle::style
