#include "nn/transformation_objective.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace motionstyle::nn {
namespace {

void requireRows(const char* what, Eigen::Index rows, Eigen::Index cols, Eigen::Index want_rows,
                 Eigen::Index want_cols) {
  if (rows != want_rows || cols != want_cols)
    throw std::invalid_argument(std::string("StyleBatch: ") + what + " is " + std::to_string(rows) +
                                " x " + std::to_string(cols) + ", expected " + std::to_string(want_rows) +
                                " x " + std::to_string(want_cols));
}

// Computes every term on y = T(I) (and h = L(y)); adds weighted gradients when the pointers are set.
template <typename S>
ObjectiveTerms lossTerms(const Mat<S>& output, const Mat<S>& hidden, const StyleBatch<S>& batch,
                         const FeatureStatistics& normalisation, const LossWeights& w, Mat<S>* grad_output,
                         Mat<S>* grad_hidden) {
  const int pooled = evenFrames(batch.frames) / 2;
  ObjectiveTerms terms;
  terms.content = static_cast<double>(
      contentLoss(hidden, batch.content_hidden, static_cast<S>(w.content), grad_hidden));
  terms.style = static_cast<double>(
      styleLoss(hidden, pooled, batch.style_grams, static_cast<S>(w.style), grad_hidden));
  terms.foot = static_cast<double>(footContactLoss(output, batch.frames, batch.contacts, normalisation,
                                                   static_cast<S>(w.foot), grad_output));
  terms.bone = static_cast<double>(boneLengthLoss(output, batch.frames, batch.bone_lengths, normalisation,
                                                  static_cast<S>(w.bone), grad_output));
  terms.trajectory = static_cast<double>(
      trajectoryLoss(output, batch.content, normalisation, static_cast<S>(w.trajectory), grad_output));
  terms.total = w.content * terms.content + w.style * terms.style + w.foot * terms.foot +
                w.bone * terms.bone + w.trajectory * terms.trajectory;
  return terms;
}

}  // namespace

void LossWeights::validate() const {
  for (double v : {content, style, foot, bone, trajectory})
    if (!std::isfinite(v) || v < 0.0)
      throw std::invalid_argument("LossWeights: every weight must be finite and >= 0");
}

template <typename S>
void StyleBatch<S>::validate(int features, int hidden) const {
  if (frames < 1) throw std::invalid_argument("StyleBatch: frames must be >= 1");
  if (content.rows() != features || content.cols() == 0 || content.cols() % frames != 0)
    throw std::invalid_argument("StyleBatch: content must be " + std::to_string(features) +
                                " x (windows * frames)");
  const Eigen::Index b = windows();
  requireRows("contacts", contacts.rows(), contacts.cols(), kContactCount, content.cols());
  requireRows("bone_lengths", bone_lengths.rows(), bone_lengths.cols(), kBoneCount, b);
  requireRows("content_hidden", content_hidden.rows(), content_hidden.cols(), hidden,
              b * (evenFrames(frames) / 2));
  if (style_grams.size() != 1 && style_grams.size() != static_cast<std::size_t>(b))
    throw std::invalid_argument("StyleBatch: need 1 or one-per-window style Gram matrices");
  for (const Mat<S>& g : style_grams) requireRows("style Gram", g.rows(), g.cols(), hidden, hidden);
}

template <typename S>
Mat<S> contentHidden(const LossNetwork<S>& loss_network, const Mat<S>& content, int frames) {
  return loss_network.encode(content, frames);
}

template <typename S>
Mat<S> styleGram(const LossNetwork<S>& loss_network, const Mat<S>& style_clip) {
  const int frames = static_cast<int>(style_clip.cols());
  return gramMatrix<S>(loss_network.encode(style_clip, frames));
}

template <typename S>
ObjectiveTerms accumulateObjective(TransformationNetwork<S>& transformation, LossNetwork<S>& loss_network,
                                   const StyleBatch<S>& batch, const FeatureStatistics& normalisation,
                                   const LossWeights& weights) {
  weights.validate();
  batch.validate(transformation.shape().features, loss_network.shape().hidden);
  const Mat<S> output = transformation.forward(batch.content, batch.frames);
  const Mat<S> hidden = loss_network.encodeForward(output, batch.frames);
  Mat<S> grad_output = Mat<S>::Zero(output.rows(), output.cols());
  Mat<S> grad_hidden = Mat<S>::Zero(hidden.rows(), hidden.cols());
  const ObjectiveTerms terms =
      lossTerms(output, hidden, batch, normalisation, weights, &grad_output, &grad_hidden);
  grad_output += loss_network.encodeBackward(grad_hidden);
  transformation.backward(grad_output);
  return terms;
}

template <typename S>
ObjectiveTerms evaluateObjective(const TransformationNetwork<S>& transformation, const LossNetwork<S>& loss_network,
                                 const StyleBatch<S>& batch, const FeatureStatistics& normalisation,
                                 const LossWeights& weights) {
  weights.validate();
  batch.validate(transformation.shape().features, loss_network.shape().hidden);
  const Mat<S> output = transformation.apply(batch.content, batch.frames);
  const Mat<S> hidden = loss_network.encode(output, batch.frames);
  return lossTerms<S>(output, hidden, batch, normalisation, weights, nullptr, nullptr);
}

#define MOTIONSTYLE_INSTANTIATE_STYLE_LOSS(S)                                                          \
  template struct StyleBatch<S>;                                                                       \
  template Mat<S> contentHidden<S>(const LossNetwork<S>&, const Mat<S>&, int);                         \
  template Mat<S> styleGram<S>(const LossNetwork<S>&, const Mat<S>&);                                  \
  template ObjectiveTerms accumulateObjective<S>(TransformationNetwork<S>&, LossNetwork<S>&, const StyleBatch<S>&, \
                                                 const FeatureStatistics&, const LossWeights&);            \
  template ObjectiveTerms evaluateObjective<S>(const TransformationNetwork<S>&, const LossNetwork<S>&,           \
                                               const StyleBatch<S>&, const FeatureStatistics&, const LossWeights&);

MOTIONSTYLE_INSTANTIATE_STYLE_LOSS(float)
MOTIONSTYLE_INSTANTIATE_STYLE_LOSS(double)
#undef MOTIONSTYLE_INSTANTIATE_STYLE_LOSS

}  // namespace motionstyle::nn
