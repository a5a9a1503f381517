#pragma once
// Stylize: the transformation network T, then the manifold projection through the loss network L
// (decode(encode(.)), paper "Manifold Projection"), over a whole clip of any length at once: the
// networks are fully convolutional, so there is no 240-frame limit and there are no seams. Between
// encode and decode the style refinement (style_refinement.h) finishes T's work on this clip; its
// Gram matrix is the whole clip's, so with it every frame depends on the whole clip. Runs on the
// float32 fast path (nn/fast_stylizer.h).
//
// Strength s in [0, 1] blends in the representation's own units (cm, cm/frame, rad/frame):
//   result = content + s * F(L(T(content)) - content),   F = removeFrameAlternation ([1 2 1] / 4 in time)
// so s = 0 returns the content's features exactly (bit for bit) and s = 1 the fully styled motion.
// F: the projection's depooling repeats each hidden frame, so the decoded change alternates between
// even and odd frames (each bone by about 1 cm, where the content's move 0.1-0.7 cm per frame); the
// clip's own proportions and the bone lengths turn that into sliding feet (docs/decisions.md, "The
// network's change, without its frame alternation"). F removes exactly that frequency.
//
// The output is at the representation's rate (60 fps), with the CONTENT's foot contacts: the paper's
// foot loss teaches T to respect them, the contact projection (contact_projection.h) plants them on the
// manifold when contacts are given, and the IK clean-up locks them. Its root path and timing are the
// content's unless PathMode::Style lets the style change the pace (path_mode.h), and its bones have the
// reference lengths exactly (enforceBoneLengths: every target is reachable by the character's limbs),
// set so that the content's contacts keep the feet where the projection planted them.

#include <Eigen/Core>
#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "features/representation.h"
#include "nn/fast_stylizer.h"
#include "nn/network_file.h"
#include "style/contact_projection.h"
#include "style/path_mode.h"
#include "style/style_refinement.h"

namespace motionstyle::style {

// A stylized clip: the targets for the output step (IK clean-up, or the positions-only BVH).
struct StylizedClip {
  Eigen::MatrixXd features;         // 66 x frames, representation units (feature_layout.h)
  Eigen::MatrixXd contacts;         // 4 x frames, 0/1, the content's labels
  Eigen::MatrixXd world_positions;  // frames x 63: the 21 canonical joints in the content clip's FILE
                                    // space (file units and axes), canonicalWorldPositions()
  FeatureAnchor anchor;             // the content's: maps features back to file space
  double fps = kDefaultFeatureFps;  // frames per second of all of the above
  PathMode path = PathMode::Content;  // whose root path the features follow
  std::string kind;  // the locomotion kind whose style target the refinement aimed at (locomotion_kind.h);
                     // "" where none ran (no refinement steps, or no stored targets)

  int frameCount() const { return static_cast<int>(features.cols()); }
};

constexpr double kMaxPhysicalFeature = 1e4;

class Stylizer {
 public:
  // Throws std::invalid_argument if the model is inconsistent (feature counts, normalisation).
  // source_name names the network in errors (its file, where there is one).
  // `refinement` finishes T's output per clip (style_refinement.h); it needs the network's stored
  // style targets and is skipped for a network without them (files before format 3).
  // `contact_projection` plants the contacts given to networkOutput / stylizeFeatures.
  explicit Stylizer(nn::StyleModel model, std::string source_name = "the style network",
                    StyleRefinement refinement = {}, ContactProjection contact_projection = {});

  const nn::StyleModel& model() const { return model_; }
  const StyleRefinement& refinement() const { return refinement_; }
  const ContactProjection& contactProjection() const { return contact_projection_; }
  // The most refinement steps networkOutput runs (fewer once converged): refinement().iterations, or 0
  // for a network without stored style targets.
  int refinementSteps() const { return model_.style_targets.empty() ? 0 : refinement_.iterations; }
  // The locomotion kind whose style target the refinement aims at on this clip: `kind`, the caller's
  // choice for it (the app's Aim at, stylize --kind), else read from the clip (locomotionKind; contacts
  // 4 x frames or 0 x 0). The target is the one labelled with it (styleTargetFor), else the nearest to
  // T's output. Every call below that takes a `kind` aims at aimedKind(features, contacts, kind).
  // Throws std::invalid_argument for a kind that is neither "" nor one of kLocomotionKinds, else as
  // locomotionKind.
  std::string aimedKind(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts,
                        const std::string& kind = {}) const;

  // The clip in the reference rig and proportions: its stances held there only (stylize also holds
  // them in the clip's own rig, where the user sees them; it is what eval measures).
  // features: 66 x frames (frames >= 1) in representation units. Returns the same shape and units.
  // contacts: the content's foot contacts (4 x frames, 0/1), planted under `path`'s root path by the
  // contact projection, or empty (0 x 0) for none.
  // Throws std::invalid_argument for a strength outside [0, 1] or NaN, or a wrong shape (the features
  // come from extractFeatures, already validated); InputError naming source_name when the output is
  // not physical: a value that is not finite or beyond kMaxPhysicalFeature (reference cm, or cm per
  // frame; a body is 170 cm) - only damaged weights produce one, and the clean-up cannot mend it.
  // Thread-safe: concurrent calls run on copies of the prepared networks (which share their kernel
  // spectra), made the first time a call finds every copy busy, and kept for later calls.
  Eigen::MatrixXd stylizeFeatures(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts, double strength,
                                  PathMode path = PathMode::Content, const std::string& kind = {}) const;

  // The whole clip: features, contacts and world positions in the clip's file space. With strength > 0
  // its stances are held once more in the clip's own rig (holdStancesInOwnRig, representation.h), so
  // its features are stylizeFeatures' but for the planted feet; strength 0 is the content exactly.
  StylizedClip stylize(const MotionFeatures& content, double strength, PathMode path = PathMode::Content,
                       const std::string& kind = {}) const;

  // stylizeFeatures in its two halves, for callers that change only the strength (live edits):
  // networkOutput(x, c, p) = L(T(x)) in representation units (refined, contacts c planted under path p),
  // independent of the strength, and finishFeatures, the blend by strength, the path mode and the bone
  // lengths (keeping the feet planted where c says so: enforceBoneLengths with contacts), which
  // stylizeFeatures(x, c, s, p) == finishFeatures(x, c, networkOutput(x, c, p), s, p) (bit for bit).
  // Same throws as stylizeFeatures; finishFeatures also when network_output's or the contacts' shape is
  // not the features'. `cancel`: OperationCancelled when it is set before a refinement step, so that a
  // dropped job stops within a few ms instead of finishing the network.
  Eigen::MatrixXd networkOutput(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts, PathMode path,
                                const std::string& kind = {}, const std::atomic<bool>* cancel = nullptr) const;
  Eigen::MatrixXd finishFeatures(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts,
                                 const Eigen::MatrixXd& network_output, double strength,
                                 PathMode path = PathMode::Content) const;
  StylizedClip stylize(const MotionFeatures& content, const Eigen::MatrixXd& network_output, double strength,
                       PathMode path = PathMode::Content, const std::string& kind = {}) const;

  // L(x) = decode(encode(x)) through this network's own loss network (the projection alone), with the
  // kernels prepared once (a fresh projectFeatures() prepares them on every call: 0.1 s, more than a
  // short clip's whole stylize). What measureFamiliarity(const Stylizer&, ...) reads. Thread-safe.
  Eigen::MatrixXd projectFeatures(const Eigen::MatrixXd& features) const;

  // Drops the prepared copies kept for later calls (each holds its scratch: about 18 MB after a
  // 600-frame clip); the next call makes one again from the prototype (a copy of its weights, a few
  // ms). For a network that may not run again soon (the app's look-ahead). Thread-safe.
  void releaseIdleNetworks() const;

  // Its loss network's prepared projection, shared with every Stylizer (and sharedProjection caller)
  // of a loss network with the same weights while any holds it: two Stylizers of one loss network
  // have the same one, so comparing it tells them apart without comparing weights again. Never run it.
  const std::shared_ptr<const nn::FastStylizer>& sharedLossProjection() const { return projection_; }

 private:
  // The clip of `features` (finished for `content` at `strength`): strength 0 is exactly the content;
  // any other output has its stances held where it lands (holdStancesInOwnRig) and names its kind.
  StylizedClip clipOf(const MotionFeatures& content, Eigen::MatrixXd features, double strength, PathMode path,
                      const std::string& kind) const;

  nn::StyleModel model_;
  std::string source_name_;
  StyleRefinement refinement_;
  ContactProjection contact_projection_;
  // Runs `run` on an idle prepared network, made from prototype_ when every one is busy, and puts it
  // back. Why not one network behind a lock: a batch's workers waited for each other's clips (its
  // speed-up on 2 cores, docs/decisions.md).
  template <typename Run>
  auto withNetwork(Run run) const;

  std::shared_ptr<const nn::FastStylizer> projection_;  // its loss network's, shared (sharedProjection); never run
  std::unique_ptr<const nn::FastStylizer> prototype_;   // prepared once, never run: copied
  std::shared_ptr<const ContactPlanter> planter_;       // its loss network's, shared (sharedContactPlanter)
  mutable std::mutex mutex_;                           // guards idle_
  mutable std::vector<std::unique_ptr<nn::FastStylizer>> idle_;
};

// The prepared projection (nn::FastStylizer(loss_network)) of `loss_network`, one per process for
// every caller with a loss network of the same weights (nn::sameWeights) while any of them holds it:
// Stylizers of networks trained against one loss network share its kernel spectra. Thread-safe.
std::shared_ptr<const nn::FastStylizer> sharedProjection(const nn::LossNetwork<float>& loss_network);

// The contact projection's operators (contact_projection.h) for `loss_network`, shared the same way.
std::shared_ptr<const ContactPlanter> sharedContactPlanter(const nn::LossNetwork<float>& loss_network);

// L(x) = decode(encode(x)) of a clip in representation units (66 x frames): the loss network's
// reconstruction, used by eval and as the "projection only" preview. float32 fast path.
Eigen::MatrixXd projectFeatures(const nn::LossNetworkModel& loss_network, const Eigen::MatrixXd& features);
// The same on a projection prepared before (nn::FastStylizer(loss_network), or a copy of
// sharedProjection's) with that loss network's normalisation: no layer set up again (the line above
// prepares them at every call, about 0.1 s). Not thread-safe for one `projection` (its scratch).
Eigen::MatrixXd projectFeatures(nn::FastStylizer& projection, const FeatureStatistics& normalisation,
                                const Eigen::MatrixXd& features);

}  // namespace motionstyle::style
