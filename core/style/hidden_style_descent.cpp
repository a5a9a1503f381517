#include "style/hidden_style_descent.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "nn/compute_pool.h"
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

// `start`, once the shapes and weights are checked.
nn::Mat<float> checkedStart(nn::Mat<float> start, const nn::Mat<float>& content_hidden, const nn::Mat<float>& style_gram,
                            double content_weight, double style_weight) {
  if (start.rows() < 1 || start.cols() < 1 || content_hidden.rows() != start.rows() ||
      content_hidden.cols() != start.cols() || style_gram.rows() != start.rows() || style_gram.cols() != start.rows())
    throw std::invalid_argument("HiddenStyleDescent: start and content hidden x frames, the Gram hidden x hidden");
  if (!std::isfinite(content_weight) || !std::isfinite(style_weight) || content_weight < 0 || style_weight < 0 ||
      content_weight + style_weight <= 0)
    throw std::invalid_argument("HiddenStyleDescent: weights finite, >= 0 and not both 0");
  return start;
}

// Columns per partial Gram matrix: the partials are summed in column order, so the result does not
// depend on the thread count.
constexpr int kGramChunkColumns = 64;

}  // namespace

HiddenStyleDescent::HiddenStyleDescent(nn::Mat<float> start, nn::Mat<float> content_hidden, nn::Mat<float> style_gram,
                                       double content_weight, double style_weight, double learning_rate)
    : hidden_(startingAt(checkedStart(std::move(start), content_hidden, style_gram, content_weight, style_weight))),
      content_hidden_(std::move(content_hidden)),
      style_gram_(std::move(style_gram)),
      content_weight_(static_cast<float>(content_weight)),
      style_weight_(static_cast<float>(style_weight)),
      optimizer_({&hidden_}, nn::AdamOptions{learning_rate}) {}

// Eq. 5 for one window, the whole of H (hidden x n), as nn::styleLoss with one Gram matrix: returns
// mean((H H^T / n - G)^2) and adds weight * 4 (H H^T / n - G) H / (n hidden^2) to grad. Split over the
// compute pool (nn::styleLoss splits by windows, and here there is one): the Gram matrix by chunks of
// columns, the gradient by columns; the buffers are kept between steps.
double HiddenStyleDescent::addStyleTerm() {
  const nn::Mat<float>& h = hidden_.value;
  const Eigen::Index hidden = h.rows();
  const int frames = static_cast<int>(h.cols());
  const int chunks = (frames + kGramChunkColumns - 1) / kGramChunkColumns;
  gram_parts_.resize(static_cast<std::size_t>(chunks));
  nn::computePool().run(chunks, [&](int k) {
    const int first = k * kGramChunkColumns;
    const auto columns = h.middleCols(first, std::min(kGramChunkColumns, frames - first));
    nn::Mat<float>& part = gram_parts_[static_cast<std::size_t>(k)];
    part.setZero(hidden, hidden);
    part.selfadjointView<Eigen::Lower>().rankUpdate(columns);  // the lower half: half the multiply-adds
  });
  gram_difference_ = gram_parts_[0];
  for (std::size_t k = 1; k < gram_parts_.size(); ++k) gram_difference_ += gram_parts_[k];
  gram_difference_.triangularView<Eigen::StrictlyUpper>() = gram_difference_.transpose().eval();
  gram_difference_ /= static_cast<float>(frames);
  gram_difference_ -= style_gram_;
  const float entries = static_cast<float>(hidden * hidden);
  const float scale = 4.0f * style_weight_ / (entries * static_cast<float>(frames));
  nn::computePool().parallelRanges(frames, 1, 32, [&](int begin, int end) {
    hidden_.grad.middleCols(begin, end - begin).noalias() += scale * (gram_difference_ * h.middleCols(begin, end - begin));
  });
  return static_cast<double>(gram_difference_.squaredNorm() / entries);
}

double HiddenStyleDescent::addTerms() {
  content_ = static_cast<double>(nn::meanSquaredError(hidden_.value, content_hidden_, content_weight_, &hidden_.grad));
  style_ = addStyleTerm();
  return static_cast<double>(content_weight_) * content_ + static_cast<double>(style_weight_) * style_;
}

double HiddenStyleDescent::step() {
  zeroGrad();
  const double value = addTerms();
  applyStep();
  return value;
}

}  // namespace motionstyle::style
