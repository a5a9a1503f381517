#include "style/stylizer.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace motionstyle::style {
namespace {

void requireFeatures(const Eigen::MatrixXd& features, const char* what) {
  if (features.rows() != kFeatureCount || features.cols() < 1)
    throw std::invalid_argument(std::string(what) + ": expected 66 x frames (frames >= 1), got " +
                                std::to_string(features.rows()) + " x " + std::to_string(features.cols()));
}

nn::Mat<float> normalised(const Eigen::MatrixXd& features, const nn::Normalisation& n) {
  return ((features.colwise() - n.mean).array().colwise() / n.std.array()).matrix().cast<float>();
}

Eigen::MatrixXd denormalised(const nn::Mat<float>& x, const nn::Normalisation& n) {
  return (x.cast<double>().array().colwise() * n.std.array()).matrix().colwise() + n.mean;
}

}  // namespace

Stylizer::Stylizer(nn::StyleModel model) : model_(std::move(model)) {
  model_.normalisation.validate();
  if (model_.transformer.shape().features != kFeatureCount || model_.loss_network.shape().features != kFeatureCount)
    throw std::invalid_argument("Stylizer: the networks must take 66 features");
  fast_ = std::make_unique<nn::FastStylizer>(model_.transformer, model_.loss_network);
}

Eigen::MatrixXd Stylizer::stylizeFeatures(const Eigen::MatrixXd& features, double strength) const {
  requireFeatures(features, "Stylizer::stylizeFeatures");
  if (!(strength >= 0.0 && strength <= 1.0)) throw std::invalid_argument("stylize strength must be in [0, 1]");
  if (strength == 0.0) return features;  // exactly the content, no network run
  nn::Mat<float> styled;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    styled = fast_->stylize(normalised(features, model_.normalisation));
  }
  const Eigen::MatrixXd projected = denormalised(styled, model_.normalisation);
  if (strength == 1.0) return projected;
  return features + strength * (projected - features);
}

StylizedClip Stylizer::stylize(const MotionFeatures& content, double strength) const {
  StylizedClip clip;
  clip.features = stylizeFeatures(content.values, strength);
  clip.contacts = content.contacts;
  clip.anchor = content.anchor;
  clip.fps = content.anchor.fps;
  clip.world_positions = canonicalWorldPositions(clip.features, clip.anchor);
  return clip;
}

Eigen::MatrixXd projectFeatures(const nn::AutoencoderModel& autoencoder, const Eigen::MatrixXd& features) {
  requireFeatures(features, "projectFeatures");
  nn::FastStylizer fast(autoencoder.network);
  return denormalised(fast.project(normalised(features, autoencoder.normalisation)), autoencoder.normalisation);
}

}  // namespace motionstyle::style
