#pragma once
// The loss network L: the paper's one-layer convolutional autoencoder of motion (Holden et al. 2016).
// Its encoder gives the features the content and style losses compare (eq. 4-6); its decoder maps
// hidden units back to motion (the projection of eq. 10). "Loss network" is the one name used for it
// in code, flags and docs; "autoencoder" only describes how it is trained (eq. 3).
//
//   encode (eq. 1):  H  = ReLU(MaxPool2(Conv(X; W0, b0)))          W0: hidden x (features*width)
//   decode (eq. 2):  X~ = Conv(AverageDepool2(H) - b0; W~0)         W~0: features x (hidden*width),
//                                                                    no bias; b0 is the ENCODER's bias
//   loss   (eq. 3):  mean((X~ - X)^2) + alpha * mean(|w| over W0 and W~0)
//
// X is normalised frames, features x (B*frames) (tensor.h). Default sizes: 66 features, 256 hidden
// units, width 25. Odd windows: repeated last frame in, cropped out (layers.h), so H has
// evenFrames(frames) / 2 columns per window and the reconstruction has the input's length.
// The L1 term regularises the weights only (not b0): a bias has no sparsity to encourage. It is a
// mean over weights, so alpha is independent of the layer sizes; see kDefaultSparsity.
// Training may drop input values (the 2016 code's dropout 0.25 makes the manifold denoising; off by
// default, see kDefaultInputDropout).

#include <cstdint>
#include <random>
#include <vector>

#include "features/feature_layout.h"
#include "nn/conv1d.h"
#include "nn/layers.h"
#include "nn/losses.h"

namespace motionstyle::nn {

struct LossNetworkShape {
  int features = kFeatureCount;
  int hidden = 256;
  int width = 25;
  bool operator==(const LossNetworkShape&) const = default;
};

// alpha for eq. 3 on the MEAN |w|, and the input dropout rate: both 0. The 2016 code's dropout 0.25
// made the network a denoiser that pulls every input toward its training motion, so it could not
// reconstruct other studios' clips (4.0 cm against 1.3 without; sparsity changed little); rig
// augmentation is the regulariser instead (docs/decisions.md).
constexpr double kDefaultSparsity = 0.0;
constexpr double kDefaultInputDropout = 0.0;

struct ReconstructionTerms {
  double mse = 0;        // mean squared reconstruction error, normalised units
  double sparsity = 0;   // mean |w| (unweighted)
  double foot = 0;       // eq. 7 on the reconstruction (unweighted, cm^2), when asked for
  double total = 0;      // mse + alpha * sparsity + foot weight * foot
};

// Optional for training: eq. 7 (losses.h, footContactLoss) on the RECONSTRUCTION with the input's
// contact labels, so that the manifold projection keeps planted feet planted (a plain MSE lets small
// errors of the feet and root velocities add up to sliding; the figures: docs/decisions.md).
template <typename S>
struct ReconstructionFootTerm {
  const Mat<S>* contacts = nullptr;            // kContactCount x (B*frames), 0/1
  const FeatureStatistics* normalisation = nullptr;
  S weight = S(0);                             // per cm^2; 0 = off
};

template <typename S>
class LossNetwork {
 public:
  explicit LossNetwork(const LossNetworkShape& shape = {});

  // He-uniform W0 (ReLU follows), Glorot-uniform W~0, b0 = 0; deterministic in `seed`.
  void initialise(std::uint32_t seed);
  const LossNetworkShape& shape() const { return shape_; }

  // Inference, no caches. encode: features x (B*frames) -> hidden x (B*evenFrames(frames)/2).
  Mat<S> encode(const Mat<S>& x, int frames) const;
  // decode: hidden x (B*pooled) -> features x (B*2*pooled).
  Mat<S> decode(const Mat<S>& hidden, int pooled_frames) const;
  // Manifold projection: decode(encode(x)) cropped back to `frames` per window.
  Mat<S> project(const Mat<S>& x, int frames) const;

  // The encoder as a differentiable function of its input with FROZEN weights (the loss network while
  // training the transformation network). encodeBackward returns dLoss/dx and touches no gradient.
  Mat<S> encodeForward(const Mat<S>& x, int frames);
  Mat<S> encodeBackward(const Mat<S>& grad_hidden);

  // One training pass of eq. 3 on x (normalised, features x (B*frames)): forward, loss, backward,
  // ADDING into the gradients of W0, b0 (through both eq. 1 and eq. 2) and W~0. dropout_rate in
  // [0, 1) applies inverted dropout to the input (rng required when > 0); the target is the clean x.
  ReconstructionTerms accumulateReconstruction(const Mat<S>& x, int frames, S alpha, S dropout_rate = S(0),
                                               std::mt19937* rng = nullptr, const ReconstructionFootTerm<S>& foot = {});

  std::vector<Parameter<S>*> parameters() { return {&encoder.weight, &encoder.bias, &decoder.weight}; }
  void zeroGrad();

  Conv1d<S> encoder;  // W0, b0
  Conv1d<S> decoder;  // W~0 (no bias)

 private:
  LossNetworkShape shape_;
  // Caches of encodeForward / accumulateReconstruction.
  MaxPool2<S> pool_;
  Relu<S> relu_;
  Dropout<S> dropout_;
  int frames_ = 0;
};

// The same loss network: equal shapes and bit-identical W0, b0 and W~0 (a style network embeds the
// loss network it was trained against; a stylize with another one's projection would be wrong).
template <typename S>
bool sameWeights(const LossNetwork<S>& a, const LossNetwork<S>& b);

}  // namespace motionstyle::nn
