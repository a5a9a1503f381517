#pragma once
// The transformation network T (paper, "Transformation Network"): three temporal convolutions,
//   Conv(features -> hidden, width) ReLU, Conv(hidden -> hidden, width) ReLU, Conv(hidden -> features, width)
// default 66 -> 128 -> 128 -> 66, width 25, all with biases. Input and output are normalised frames,
// features x (B*frames) (tensor.h); fully convolutional, so any length works.
//
// Residual option: output = input + T(input). The paper trains the plain form from scratch; the
// residual form starts at "output = content" instead of "output = noise", so the content and motion
// constraint terms start near zero. See TransformationShape::residual for the default and why.

#include <cstdint>
#include <vector>

#include "features/feature_layout.h"
#include "nn/conv1d.h"
#include "nn/layers.h"

namespace motionstyle::nn {

struct TransformationShape {
  int features = kFeatureCount;
  int hidden = 128;
  int width = 25;
  // Default ON, from `bench_nn --residual-experiment` (synthetic 21-joint chain motion with fixed bone
  // lengths, targets from the content as in real training; same seeds, 200 Adam steps, lr 1e-3):
  // validation total 0.0128 residual vs 0.162 plain (style weight 0.01) and 0.0157 vs 0.168 (style
  // weight 1): the plain net spends its first steps re-learning the identity and keeps a content
  // error of ~0.1, the residual one starts there. Costs one addition per value. The paper's form is
  // residual = false.
  bool residual = true;
  bool operator==(const TransformationShape&) const = default;
};

template <typename S>
class TransformationNetwork {
 public:
  explicit TransformationNetwork(const TransformationShape& shape = {});

  // He-uniform for the two ReLU layers, Glorot-uniform for the output layer, zero biases. With
  // `residual` the output layer is scaled by 0.1 so the network starts close to the identity map.
  void initialise(std::uint32_t seed);
  const TransformationShape& shape() const { return shape_; }

  Mat<S> apply(const Mat<S>& x, int frames) const;  // inference, no caches
  Mat<S> forward(const Mat<S>& x, int frames);      // caches for backward
  // Adds into every parameter's gradient. The input gradient is not computed (the input is data).
  void backward(const Mat<S>& grad_output);

  std::vector<Parameter<S>*> parameters();
  void zeroGrad();

  Conv1d<S> conv1;
  Conv1d<S> conv2;
  Conv1d<S> conv3;

 private:
  TransformationShape shape_;
  Relu<S> relu1_;
  Relu<S> relu2_;
};

}  // namespace motionstyle::nn
