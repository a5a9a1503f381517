#include "nn/init.h"

#include <cmath>

namespace motionstyle::nn {

double symmetricUniform(std::mt19937& rng) {
  return static_cast<double>(rng()) / 2147483648.0 - 1.0;
}

template <typename S>
void initialiseConv(Conv1d<S>& conv, InitScheme scheme, std::mt19937& rng) {
  const double fan_in = static_cast<double>(conv.inChannels()) * conv.width();
  const double fan_out = static_cast<double>(conv.outChannels()) * conv.width();
  const double limit = scheme == InitScheme::HeUniform ? std::sqrt(6.0 / fan_in)
                                                       : std::sqrt(6.0 / (fan_in + fan_out));
  Mat<S>& w = conv.weight.value;
  for (Eigen::Index i = 0; i < w.size(); ++i) w.data()[i] = static_cast<S>(limit * symmetricUniform(rng));
  if (conv.hasBias()) conv.bias.value.setZero();
}

template void initialiseConv<float>(Conv1d<float>&, InitScheme, std::mt19937&);
template void initialiseConv<double>(Conv1d<double>&, InitScheme, std::mt19937&);

}  // namespace motionstyle::nn
