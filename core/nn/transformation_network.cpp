#include "nn/transformation_network.h"

#include <random>

#include "nn/init.h"

namespace motionstyle::nn {

template <typename S>
TransformationNetwork<S>::TransformationNetwork(const TransformationShape& shape)
    : conv1("transform1", shape.features, shape.hidden, shape.width, true),
      conv2("transform2", shape.hidden, shape.hidden, shape.width, true),
      conv3("transform3", shape.hidden, shape.features, shape.width, true),
      shape_(shape) {}

template <typename S>
void TransformationNetwork<S>::initialise(std::uint32_t seed) {
  std::mt19937 rng(seed);
  initialiseConv(conv1, InitScheme::HeUniform, rng);
  initialiseConv(conv2, InitScheme::HeUniform, rng);
  initialiseConv(conv3, InitScheme::GlorotUniform, rng);
  // A residual network starts as (nearly) the identity: the losses start small, so the first steps do not
  // fill Adam's second moments with huge gradients that then hold every later step back (docs/decisions.md).
  if (shape_.residual) conv3.weight.value *= S(0.001);
}

template <typename S>
Mat<S> TransformationNetwork<S>::apply(const Mat<S>& x, int frames) const {
  checkBatch("TransformationNetwork::apply", x.rows(), x.cols(), shape_.features, frames);
  Mat<S> y = conv3.apply(Relu<S>::apply(conv2.apply(Relu<S>::apply(conv1.apply(x, frames)), frames)), frames);
  if (shape_.residual) y += x;
  return y;
}

template <typename S>
Mat<S> TransformationNetwork<S>::forward(const Mat<S>& x, int frames) {
  checkBatch("TransformationNetwork::forward", x.rows(), x.cols(), shape_.features, frames);
  Mat<S> y = conv3.forward(relu2_.forward(conv2.forward(relu1_.forward(conv1.forward(x, frames)), frames)), frames);
  if (shape_.residual) y += x;
  return y;
}

template <typename S>
void TransformationNetwork<S>::backward(const Mat<S>& grad_output) {
  // The residual path x -> y ends at the (data) input, so it adds nothing to parameter gradients.
  const Mat<S> g2 = relu2_.backward(conv3.backward(grad_output, Gradients::All));
  const Mat<S> g1 = relu1_.backward(conv2.backward(g2, Gradients::All));
  conv1.backward(g1, Gradients::ParametersOnly);
}

template <typename S>
std::vector<Parameter<S>*> TransformationNetwork<S>::parameters() {
  return {&conv1.weight, &conv1.bias, &conv2.weight, &conv2.bias, &conv3.weight, &conv3.bias};
}

template <typename S>
void TransformationNetwork<S>::zeroGrad() {
  conv1.zeroGrad();
  conv2.zeroGrad();
  conv3.zeroGrad();
}

template class TransformationNetwork<float>;
template class TransformationNetwork<double>;

}  // namespace motionstyle::nn
