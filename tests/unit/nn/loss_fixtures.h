#pragma once
// Shared random inputs for the loss and network tests: plausible normalisation statistics and frames.

#include <random>

#include "gradient_check.h"
#include "nn/losses.h"

namespace motionstyle::nn::test {

// Positions with a std of ~15 cm around a random mean, velocities ~1.5 cm/frame, turning ~0.03 rad.
inline FeatureStatistics randomNormalisation(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.5, 1.5);
  FeatureStatistics n;
  n.mean = randomMatrix(kFeatureCount, 1, rng, 30.0);
  n.std.resize(kFeatureCount);
  for (int f = 0; f < kFeatureCount; ++f) n.std(f) = 15.0 * u(rng);
  n.mean(kSidewaysVelocity) = 0.0;
  n.mean(kForwardVelocity) = 1.0;
  n.mean(kTurningVelocity) = 0.0;
  n.std(kSidewaysVelocity) = 1.5 * u(rng);
  n.std(kForwardVelocity) = 1.5 * u(rng);
  n.std(kTurningVelocity) = 0.03 * u(rng);
  return n;
}

inline MatD randomContacts(Eigen::Index cols, std::mt19937& rng) {
  MatD c(kContactCount, cols);
  for (Eigen::Index i = 0; i < c.size(); ++i) c.data()[i] = (rng() % 2 == 0) ? 1.0 : 0.0;
  return c;
}

inline MatD randomBoneLengths(int windows, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(5.0, 40.0);
  MatD l(kBoneCount, windows);
  for (Eigen::Index i = 0; i < l.size(); ++i) l.data()[i] = u(rng);
  return l;
}

}  // namespace motionstyle::nn::test
