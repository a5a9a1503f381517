#include "style/stylizer.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/errors.h"
#include "features/signal_filters.h"
#include "style/cancellation.h"
#include "style/locomotion_kind.h"
#include "style/training_windows.h"

namespace motionstyle::style {
namespace {

void requireFeatures(const Eigen::MatrixXd& features, const char* what) {
  if (features.rows() != kFeatureCount || features.cols() < 1)
    throw std::invalid_argument(std::string(what) + ": expected 66 x frames (frames >= 1), got " +
                                std::to_string(features.rows()) + " x " + std::to_string(features.cols()));
}

// Contacts are empty (none) or 4 x the features' frames.
void requireContacts(const Eigen::MatrixXd& contacts, const Eigen::MatrixXd& features, const char* what) {
  if (contacts.size() > 0 && (contacts.rows() != kContactCount || contacts.cols() != features.cols()))
    throw std::invalid_argument(std::string(what) + ": the contacts must be 4 x the features' frames");
}

// Frames of the first and last pose added at each end before the networks run (then cropped): the
// convolutions see a clip's edges as the training windows had them (cutWindow's padding, standing
// poses) instead of the zero padding of a bare convolution. It covers the receptive field of the
// transformation network and the projection together; without it the edges of short clips were
// reconstructed far worse (other studios' 1-3 s clips: 1.72 -> 1.42 cm; docs/decisions.md).
constexpr int kEdgePaddingFrames = 64;

Eigen::MatrixXd padEdges(const Eigen::MatrixXd& features) {
  const int frames = static_cast<int>(features.cols());
  return cutWindow(features, {0, frames}, frames + 2 * kEdgePaddingFrames, /*zero_velocities=*/true);
}

Eigen::MatrixXd cropEdges(const Eigen::MatrixXd& padded) {
  return padded.middleCols(kEdgePaddingFrames, padded.cols() - 2 * kEdgePaddingFrames);
}

}  // namespace

Stylizer::Stylizer(nn::StyleModel model, std::string source_name, StyleRefinement refinement,
                   ContactProjection contact_projection)
    : model_(std::move(model)), source_name_(std::move(source_name)), refinement_(refinement),
      contact_projection_(contact_projection) {
  model_.normalisation.validate();
  refinement_.validate();
  contact_projection_.validate();
  if (model_.transformation.shape().features != kFeatureCount || model_.loss_network.shape().features != kFeatureCount)
    throw std::invalid_argument("Stylizer: the networks must take 66 features");
  projection_ = sharedProjection(model_.loss_network);
  planter_ = sharedContactPlanter(model_.loss_network);
  prototype_ = std::make_unique<const nn::FastStylizer>(model_.transformation, *projection_);
}

template <typename Run>
auto Stylizer::withNetwork(Run run) const {
  std::unique_ptr<nn::FastStylizer> network;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!idle_.empty()) {
      network = std::move(idle_.back());
      idle_.pop_back();
    }
  }
  if (!network) network = std::make_unique<nn::FastStylizer>(*prototype_);
  auto result = run(*network);
  const std::lock_guard<std::mutex> lock(mutex_);
  idle_.push_back(std::move(network));
  return result;
}

void Stylizer::releaseIdleNetworks() const {
  std::vector<std::unique_ptr<nn::FastStylizer>> released;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    released.swap(idle_);
  }  // freed outside the lock
}

Eigen::MatrixXd Stylizer::networkOutput(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts, PathMode path,
                                        const std::string& kind, const std::atomic<bool>* cancel) const {
  requireFeatures(features, "Stylizer::networkOutput");
  requireContacts(contacts, features, "Stylizer::networkOutput");
  const bool plant = contacts.size() > 0 && contact_projection_.iterations > 0;
  const bool refine = refinementSteps() > 0;
  requireKindOrNone(kind, "the kind to aim at");
  const std::string aimed = refine ? aimedKind(features, contacts, kind) : std::string();
  const nn::Mat<float> input = model_.normalisation.normalized(padEdges(features));
  const nn::Mat<float> styled = withNetwork([&](nn::FastStylizer& network) {
    if (!refine && !plant) return network.stylize(input);
    // The clip's own pooled columns, between the edges' padding.
    const Eigen::Index first = kEdgePaddingFrames / 2, count = (features.cols() + 1) / 2;
    nn::Mat<float> content_hidden;
    if (refine) content_hidden = network.encode(input).middleCols(first, count);
    nn::Mat<float> styled_padded;
    network.stylize(input, styled_padded, [&](nn::Mat<float>& hidden) {
      if (refine) {
        nn::Mat<float> clip = hidden.middleCols(first, count);
        const std::vector<float> share = transformationShare(features, count);
        for (Eigen::Index k = 0; k < count; ++k)
          if (share[static_cast<std::size_t>(k)] < 1.0f)
            clip.col(k) = content_hidden.col(k) + share[static_cast<std::size_t>(k)] * (clip.col(k) - content_hidden.col(k));
        int target = styleTargetFor(model_.style_targets, aimed);
        if (target < 0) target = nearestStyleTarget(model_.style_targets, clip);
        refineHiddenUnits(clip, content_hidden, model_.style_targets[static_cast<std::size_t>(target)].gram,
                          refinement_, cancel);
        hidden.middleCols(first, count) = clip;
      }
      if (plant) {
        throwIfCancelled(cancel);
        planter_->plant(hidden, model_.normalisation, features, contacts, kEdgePaddingFrames, path,
                        contact_projection_);
      }
    });
    return styled_padded;
  });
  return cropEdges(model_.normalisation.denormalized(styled));
}

Eigen::MatrixXd Stylizer::finishFeatures(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts,
                                         const Eigen::MatrixXd& network_output, double strength, PathMode path) const {
  requireFeatures(features, "Stylizer::finishFeatures");
  if (network_output.rows() != features.rows() || network_output.cols() != features.cols())
    throw std::invalid_argument("Stylizer::finishFeatures: the network output is not the features' shape");
  requireContacts(contacts, features, "Stylizer::finishFeatures");
  if (!(strength >= 0.0 && strength <= 1.0)) throw std::invalid_argument("stylize strength must be in [0, 1]");
  if (strength == 0.0) return features;  // exactly the content
  Eigen::MatrixXd change = network_output - features;
  removeFrameAlternation(change);
  Eigen::MatrixXd result = features + strength * change;
  applyPathMode(result, features, path);
  enforceBoneLengths(result, referenceProportions(), contacts);
  if (!result.allFinite() || result.cwiseAbs().maxCoeff() > kMaxPhysicalFeature)
    throw InputError(source_name_, 0,
                     "the network's output is not physical (a joint 100 m away, or not a number): its weights are "
                     "damaged");
  return result;
}

Eigen::MatrixXd Stylizer::stylizeFeatures(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts,
                                          double strength, PathMode path, const std::string& kind) const {
  requireFeatures(features, "Stylizer::stylizeFeatures");
  if (!(strength >= 0.0 && strength <= 1.0)) throw std::invalid_argument("stylize strength must be in [0, 1]");
  if (strength == 0.0) return features;  // exactly the content, no network run
  return finishFeatures(features, contacts, networkOutput(features, contacts, path, kind), strength, path);
}

std::string Stylizer::aimedKind(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts,
                                const std::string& kind) const {
  requireKindOrNone(kind, "the kind to aim at");
  return kind.empty() ? locomotionKind(features, contacts) : kind;
}

StylizedClip Stylizer::clipOf(const MotionFeatures& content, Eigen::MatrixXd features, double strength,
                              PathMode path, const std::string& kind) const {
  StylizedClip clip;
  clip.features = std::move(features);
  if (strength > 0.0) holdStancesInOwnRig(clip.features, content);
  clip.path = path;
  clip.contacts = content.contacts;
  clip.anchor = content.anchor;
  clip.fps = content.anchor.fps;
  clip.world_positions = canonicalWorldPositions(clip.features, clip.anchor);
  if (strength > 0.0 && refinementSteps() > 0) clip.kind = aimedKind(content.values, content.contacts, kind);
  return clip;
}

StylizedClip Stylizer::stylize(const MotionFeatures& content, double strength, PathMode path,
                               const std::string& kind) const {
  return clipOf(content, stylizeFeatures(content.values, content.contacts, strength, path, kind), strength, path,
                kind);
}

StylizedClip Stylizer::stylize(const MotionFeatures& content, const Eigen::MatrixXd& network_output, double strength,
                               PathMode path, const std::string& kind) const {
  return clipOf(content, finishFeatures(content.values, content.contacts, network_output, strength, path), strength,
                path, kind);
}

Eigen::MatrixXd Stylizer::projectFeatures(const Eigen::MatrixXd& features) const {
  requireFeatures(features, "Stylizer::projectFeatures");
  const nn::Mat<float> input = model_.normalisation.normalized(padEdges(features));
  const nn::Mat<float> projected = withNetwork([&](nn::FastStylizer& network) { return network.project(input); });
  return cropEdges(model_.normalisation.denormalized(projected));
}

namespace {

// One Prepared(loss_network) per process for every caller with a loss network of the same weights while
// any of them holds it.
template <typename Prepared>
std::shared_ptr<const Prepared> sharedFor(const nn::LossNetwork<float>& loss_network) {
  struct Entry {
    nn::LossNetwork<float> network;  // to recognise it (sameWeights)
    std::weak_ptr<const Prepared> prepared;
  };
  static std::mutex mutex;
  static std::vector<Entry> entries;
  const std::lock_guard<std::mutex> lock(mutex);
  std::erase_if(entries, [](const Entry& entry) { return entry.prepared.expired(); });
  for (const Entry& entry : entries)
    if (nn::sameWeights(entry.network, loss_network))
      if (std::shared_ptr<const Prepared> prepared = entry.prepared.lock()) return prepared;
  auto prepared = std::make_shared<const Prepared>(loss_network);
  entries.push_back({loss_network, prepared});
  return prepared;
}

}  // namespace

std::shared_ptr<const nn::FastStylizer> sharedProjection(const nn::LossNetwork<float>& loss_network) {
  return sharedFor<nn::FastStylizer>(loss_network);
}

std::shared_ptr<const ContactPlanter> sharedContactPlanter(const nn::LossNetwork<float>& loss_network) {
  return sharedFor<ContactPlanter>(loss_network);
}

Eigen::MatrixXd projectFeatures(const nn::LossNetworkModel& loss_network, const Eigen::MatrixXd& features) {
  requireFeatures(features, "projectFeatures");
  nn::FastStylizer fast(loss_network.network);
  return projectFeatures(fast, loss_network.normalisation, features);
}

Eigen::MatrixXd projectFeatures(nn::FastStylizer& projection, const FeatureStatistics& normalisation,
                                const Eigen::MatrixXd& features) {
  requireFeatures(features, "projectFeatures");
  return cropEdges(normalisation.denormalized(projection.project(normalisation.normalized(padEdges(features)))));
}

}  // namespace motionstyle::style
