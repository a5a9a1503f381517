#pragma once
// The convolution of conv1d.h as plain loops (the definition the fast paths are checked against), and
// random convolutions for the tests.

#include <random>

#include "gradient_check.h"
#include "nn/conv1d.h"

namespace motionstyle::nn::test {

// y[o, t] = b[o] + sum_{c,k} W(o, k*in + c) x[c, t + k - K/2], zero outside each window.
inline MatD naiveConv(const Conv1d<double>& conv, const MatD& x, int frames) {
  const int pad = conv.width() / 2;
  MatD y = MatD::Zero(conv.outChannels(), x.cols());
  for (Eigen::Index start = 0; start < x.cols(); start += frames)
    for (int t = 0; t < frames; ++t)
      for (int o = 0; o < conv.outChannels(); ++o) {
        double sum = conv.hasBias() ? conv.bias.value(o, 0) : 0.0;
        for (int k = 0; k < conv.width(); ++k) {
          const int source = t + k - pad;
          if (source < 0 || source >= frames) continue;
          for (int c = 0; c < conv.inChannels(); ++c)
            sum += conv.weight.value(o, k * conv.inChannels() + c) * x(c, start + source);
        }
        y(o, start + t) = sum;
      }
  return y;
}

inline Conv1d<double> randomConv(int in, int out, int width, bool bias, std::mt19937& rng) {
  Conv1d<double> conv("test", in, out, width, bias);
  conv.weight.value = randomMatrix(out, in * width, rng);
  if (bias) conv.bias.value = randomMatrix(out, 1, rng);
  return conv;
}

// dx, dW and db of `conv` (with its algorithm as set) on a random x of `windows` windows of `frames`
// against finite differences of sum(conv(x) .* r) for a random r; `samples` entries of x and W are
// checked (0: all, as checkGradient), every entry of b. `trial` names the case in failures.
inline void expectConvGradientsMatch(Conv1d<double>& conv, int frames, int windows, int samples, std::mt19937& rng,
                                     int trial) {
  MatD x = randomMatrix(conv.inChannels(), windows * frames, rng);
  const MatD r = randomMatrix(conv.outChannels(), windows * frames, rng);
  auto loss = [&] { return conv.apply(x, frames).cwiseProduct(r).sum(); };
  conv.zeroGrad();
  conv.forward(x, frames);
  const MatD dx = conv.backward(r, Gradients::All);
  EXPECT_LT(checkGradient(x, dx, loss, samples, rng).max_error, kGradientTolerance) << "dx trial " << trial;
  const MatD dw = conv.weight.grad;
  EXPECT_LT(checkGradient(conv.weight.value, dw, loss, samples, rng).max_error, kGradientTolerance) << trial;
  const MatD db = conv.bias.grad;
  EXPECT_LT(checkGradient(conv.bias.value, db, loss, 0, rng).max_error, kGradientTolerance) << trial;
}

}  // namespace motionstyle::nn::test
