#include "nn/loss_network.h"

#include <stdexcept>

#include "nn/init.h"
#include "nn/losses.h"

namespace motionstyle::nn {

template <typename S>
LossNetwork<S>::LossNetwork(const LossNetworkShape& shape)
    : encoder("encoder", shape.features, shape.hidden, shape.width, true),
      decoder("decoder", shape.hidden, shape.features, shape.width, false),
      shape_(shape) {}

template <typename S>
void LossNetwork<S>::initialise(std::uint32_t seed) {
  std::mt19937 rng(seed);
  initialiseConv(encoder, InitScheme::HeUniform, rng);
  initialiseConv(decoder, InitScheme::GlorotUniform, rng);
}

template <typename S>
void LossNetwork<S>::zeroGrad() {
  encoder.zeroGrad();
  decoder.zeroGrad();
}

template <typename S>
Mat<S> LossNetwork<S>::encode(const Mat<S>& x, int frames) const {
  checkBatch("LossNetwork::encode", x.rows(), x.cols(), shape_.features, frames);
  const int even = evenFrames(frames);
  return Relu<S>::apply(MaxPool2<S>::apply(encoder.apply(padToEvenFrames(x, frames), even), even));
}

template <typename S>
Mat<S> LossNetwork<S>::decode(const Mat<S>& hidden, int pooled_frames) const {
  checkBatch("LossNetwork::decode", hidden.rows(), hidden.cols(), shape_.hidden, pooled_frames);
  Mat<S> shifted = AverageDepool2<S>::apply(hidden);
  shifted.colwise() -= encoder.bias.value.col(0);  // eq. 2: the encoder's bias b0
  return decoder.apply(shifted, 2 * pooled_frames);
}

template <typename S>
Mat<S> LossNetwork<S>::project(const Mat<S>& x, int frames) const {
  return cropToFrames(decode(encode(x, frames), evenFrames(frames) / 2), frames);
}

template <typename S>
Mat<S> LossNetwork<S>::encodeForward(const Mat<S>& x, int frames) {
  checkBatch("LossNetwork::encodeForward", x.rows(), x.cols(), shape_.features, frames);
  frames_ = frames;
  const int even = evenFrames(frames);
  return relu_.forward(pool_.forward(encoder.forward(padToEvenFrames(x, frames), even), even));
}

template <typename S>
Mat<S> LossNetwork<S>::encodeBackward(const Mat<S>& grad_hidden) {
  if (frames_ == 0) throw std::logic_error("LossNetwork::encodeBackward before encodeForward");
  const Mat<S> grad_conv = pool_.backward(relu_.backward(grad_hidden));
  return foldEvenPaddingGradient(encoder.backward(grad_conv, Gradients::InputOnly), frames_);
}

template <typename S>
ReconstructionTerms LossNetwork<S>::accumulateReconstruction(const Mat<S>& x, int frames, S alpha,
                                                             S dropout_rate, std::mt19937* rng,
                                                             const ReconstructionFootTerm<S>& foot) {
  checkBatch("LossNetwork::accumulateReconstruction", x.rows(), x.cols(), shape_.features, frames);
  if (dropout_rate > S(0) && rng == nullptr)
    throw std::invalid_argument("LossNetwork::accumulateReconstruction: dropout needs an rng");
  const int even = evenFrames(frames);
  Mat<S> input = padToEvenFrames(x, frames);
  if (dropout_rate > S(0)) input = dropout_.forward(input, dropout_rate, *rng);

  // Forward: eq. 1 then eq. 2.
  const Mat<S> hidden = relu_.forward(pool_.forward(encoder.forward(input, even), even));
  SubtractSharedBias<S> subtract(&encoder.bias);
  const Mat<S> output = cropToFrames(decoder.forward(subtract.apply(AverageDepool2<S>::apply(hidden)), even), frames);

  // Eq. 3 and its gradient.
  ReconstructionTerms terms;
  Mat<S> grad_output = Mat<S>::Zero(output.rows(), output.cols());
  terms.mse = static_cast<double>(meanSquaredError(output, x, S(1), &grad_output));
  terms.sparsity = static_cast<double>(meanAbsoluteWeight<S>({&encoder.weight, &decoder.weight}, alpha));
  terms.total = terms.mse + static_cast<double>(alpha) * terms.sparsity;
  if (foot.weight > S(0)) {
    if (foot.contacts == nullptr || foot.normalisation == nullptr)
      throw std::invalid_argument("LossNetwork::accumulateReconstruction: the foot term needs contacts and statistics");
    terms.foot = static_cast<double>(footContactLoss(output, frames, *foot.contacts, *foot.normalisation, foot.weight, &grad_output));
    terms.total += static_cast<double>(foot.weight) * terms.foot;
  }

  // Backward: b0 collects its gradient from both the encoder and the decoder's subtraction.
  const Mat<S> grad_shifted = decoder.backward(uncropGradient(grad_output, frames), Gradients::All);
  const Mat<S> grad_hidden = AverageDepool2<S>::backward(subtract.backward(grad_shifted, true));
  encoder.backward(pool_.backward(relu_.backward(grad_hidden)), Gradients::ParametersOnly);
  return terms;
}

template <typename S>
bool sameWeights(const LossNetwork<S>& a, const LossNetwork<S>& b) {
  return a.shape() == b.shape() && a.encoder.weight.value == b.encoder.weight.value &&
         a.encoder.bias.value == b.encoder.bias.value && a.decoder.weight.value == b.decoder.weight.value;
}

template class LossNetwork<float>;
template class LossNetwork<double>;
template bool sameWeights(const LossNetwork<float>&, const LossNetwork<float>&);
template bool sameWeights(const LossNetwork<double>&, const LossNetwork<double>&);

}  // namespace motionstyle::nn
