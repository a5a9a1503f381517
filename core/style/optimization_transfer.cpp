#include "style/optimization_transfer.h"

#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

#include "common/errors.h"
#include "nn/init.h"
#include "nn/layers.h"
#include "nn/losses.h"
#include "nn/transformation_objective.h"
#include "style/cancellation.h"
#include "style/hidden_style_descent.h"

namespace motionstyle::style {
namespace {

using Clock = std::chrono::steady_clock;

// decode(H) with the decoder's forward cache (for the constraint pass) and its input gradient.
class Decoder {
 public:
  Decoder(const nn::LossNetwork<float>& network, int frames) : network_(network), frames_(frames) {}

  nn::Mat<float> forward(const nn::Mat<float>& hidden) {
    nn::Mat<float> shifted = nn::AverageDepool2<float>::apply(hidden);
    shifted.colwise() -= network_.encoder.bias.value.col(0);
    return nn::cropToFrames(network_.decoder.forward(shifted, nn::evenFrames(frames_)), frames_);
  }
  nn::Mat<float> backward(const nn::Mat<float>& grad_output) {
    const nn::Mat<float> grad_shifted =
        network_.decoder.backward(nn::uncropGradient(grad_output, frames_), nn::Gradients::InputOnly);
    return nn::AverageDepool2<float>::backward(grad_shifted);  // b0 is a constant here
  }

 private:
  nn::LossNetwork<float> network_;  // a copy: forward() caches inside the decoder
  int frames_;
};

}  // namespace

void OptimizationOptions::setIterations(int stage_one) {
  const OptimizationOptions defaults;
  iterations = stage_one;
  constraint_iterations = std::max(1, static_cast<int>(static_cast<long long>(stage_one) * defaults.constraint_iterations /
                                                       defaults.iterations));
}

void OptimizationOptions::validate() const {
  if (iterations < 0 || constraint_iterations < 0) throw std::invalid_argument("iterations must be >= 0");
  if (!std::isfinite(learning_rate) || learning_rate <= 0) throw std::invalid_argument("learning rate must be > 0");
  for (double w : {content_weight, style_weight, foot_weight, bone_weight, trajectory_weight})
    if (!std::isfinite(w) || w < 0) throw std::invalid_argument("optimisation weights must be finite and >= 0");
  if (content_weight + style_weight <= 0) throw std::invalid_argument("content and style weights cannot both be 0");
}

OptimizationResult optimizeStyleTransfer(const nn::LossNetworkModel& loss_network, const Eigen::MatrixXd& content,
                                         const Eigen::MatrixXd& content_contacts, const Eigen::MatrixXd& style,
                                         const std::string& style_name, const OptimizationOptions& options,
                                         const OptimizationCallbacks& callbacks) {
  options.validate();
  const auto started = Clock::now();
  const int frames = static_cast<int>(content.cols());
  if (content.rows() != kFeatureCount || frames < 1 || content_contacts.rows() != kContactCount ||
      content_contacts.cols() != frames || style.rows() != kFeatureCount)
    throw std::invalid_argument("optimizeStyleTransfer: content 66 x frames, contacts 4 x frames, style 66 x frames");
  const int width = loss_network.network.shape().width;
  if (style.cols() < width)
    throw InputError(style_name, 0, "the style clip is too short: " + std::to_string(style.cols()) +
                                        " frames at 60 fps, the loss network's filter needs at least " +
                                        std::to_string(width));
  if (!content.allFinite() || !style.allFinite()) throw std::invalid_argument("optimizeStyleTransfer: non-finite input");

  const FeatureStatistics& norm = loss_network.normalisation;
  const nn::LossNetwork<float>& network = loss_network.network;
  const nn::Mat<float> content_n = norm.normalized(content);
  const nn::Mat<float> content_hidden = network.encode(content_n, frames);
  nn::Mat<float> style_gram = nn::styleGram(network, norm.normalized(style));
  const double c = options.content_weight / (options.content_weight + options.style_weight);
  const double s = options.style_weight / (options.content_weight + options.style_weight);

  nn::Mat<float> start;
  if (options.start_from_noise) {
    std::mt19937 rng(options.seed);
    nn::Mat<float> noise(content_n.rows(), content_n.cols());
    // Uniform with unit variance (sqrt(3) * U(-1, 1)): "noise scaled by the data's std around its mean"
    // in normalised units, from the portable draws of nn/init.h.
    for (Eigen::Index i = 0; i < noise.size(); ++i)
      noise.data()[i] = static_cast<float>(std::sqrt(3.0) * nn::symmetricUniform(rng));
    start = network.encode(noise, frames);
  } else {
    start = content_hidden;
  }
  HiddenStyleDescent descent(std::move(start), content_hidden, std::move(style_gram), c, s, options.learning_rate);

  OptimizationResult result;
  OptimizationProgress progress;
  const auto report = [&](const char* stage, int iteration, int iterations) {
    progress.stage = stage;
    progress.iteration = iteration;
    progress.iterations = iterations;
    progress.content = descent.content();
    progress.style = descent.style();
    progress.elapsed_seconds = std::chrono::duration<double>(Clock::now() - started).count();
    if (callbacks.progress) callbacks.progress(progress);
  };

  try {
    for (int i = 0; i < options.iterations; ++i) {
      throwIfCancelled(callbacks.cancel);
      progress.total = descent.step();
      report("style", i + 1, options.iterations);
    }
    Decoder decoder(network, frames);
    const nn::Mat<float> contacts = content_contacts.cast<float>();
    const nn::Mat<float> bones = canonicalBoneLengths(content).tail(nn::kBoneCount).cast<float>();
    nn::Parameter<float>& hidden = descent.hidden();
    for (int i = 0; i < options.constraint_iterations; ++i) {
      throwIfCancelled(callbacks.cancel);
      descent.zeroGrad();
      const nn::Mat<float> output = decoder.forward(hidden.value);
      nn::Mat<float> grad_output = nn::Mat<float>::Zero(output.rows(), output.cols());
      progress.foot = static_cast<double>(
          nn::footContactLoss(output, frames, contacts, norm, static_cast<float>(options.foot_weight), &grad_output));
      progress.bone = static_cast<double>(
          nn::boneLengthLoss(output, frames, bones, norm, static_cast<float>(options.bone_weight), &grad_output));
      progress.trajectory = static_cast<double>(
          nn::trajectoryLoss(output, content_n, norm, static_cast<float>(options.trajectory_weight), &grad_output));
      hidden.grad += decoder.backward(grad_output);
      progress.total = descent.addTerms() + options.foot_weight * progress.foot + options.bone_weight * progress.bone +
                       options.trajectory_weight * progress.trajectory;
      descent.applyStep();
      report("constraints", i + 1, options.constraint_iterations);
    }
  } catch (const OperationCancelled&) {
    result.cancelled = true;
    result.seconds = std::chrono::duration<double>(Clock::now() - started).count();
    return result;
  }
  if (!descent.value().allFinite()) throw std::runtime_error("the optimisation diverged (non-finite hidden units)");

  result.clip.features = norm.denormalized(Decoder(network, frames).forward(descent.value()));
  applyPathMode(result.clip.features, content, options.path);
  enforceBoneLengths(result.clip.features, referenceProportions());
  result.clip.path = options.path;
  result.clip.contacts = content_contacts;
  result.final_terms = progress;
  result.seconds = std::chrono::duration<double>(Clock::now() - started).count();
  return result;
}

OptimizationResult optimizeStyleTransfer(const nn::LossNetworkModel& loss_network, const MotionFeatures& content,
                                         const MotionFeatures& style, const std::string& style_name,
                                         const OptimizationOptions& options, const OptimizationCallbacks& callbacks) {
  OptimizationResult result = optimizeStyleTransfer(loss_network, content.values, content.contacts, style.values,
                                                    style_name, options, callbacks);
  if (result.cancelled) return result;
  result.clip.anchor = content.anchor;
  result.clip.fps = content.anchor.fps;
  result.clip.world_positions = canonicalWorldPositions(result.clip.features, result.clip.anchor);
  return result;
}

}  // namespace motionstyle::style
