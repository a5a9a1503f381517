#pragma once
// Deterministic weight initialisation. The uniform draws come straight from std::mt19937's 32-bit
// outputs (not std::uniform_real_distribution, whose algorithm differs between standard libraries),
// so the same seed gives bit-identical weights everywhere.

#include <cstdint>
#include <random>

#include "nn/conv1d.h"

namespace motionstyle::nn {

enum class InitScheme {
  HeUniform,     // U(-a, a), a = sqrt(6 / fan_in): for a convolution followed by a ReLU
  GlorotUniform  // U(-a, a), a = sqrt(6 / (fan_in + fan_out)): for a linear output layer
};

// fan_in = in * width, fan_out = out * width. The bias (if any) is set to zero.
template <typename S>
void initialiseConv(Conv1d<S>& conv, InitScheme scheme, std::mt19937& rng);

// Uniform in [-1, 1) from one 32-bit draw.
double symmetricUniform(std::mt19937& rng);

}  // namespace motionstyle::nn
