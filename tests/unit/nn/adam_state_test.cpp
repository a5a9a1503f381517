// nn::Adam's state (moments, step count) as a checkpoint sees it: a mismatched state is refused, and an
// optimiser restored from another's state continues bit for bit as the original would have.

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "nn/adam.h"
#include "nn/init.h"

namespace motionstyle::nn {
namespace {

Mat<float> randomMatrix(Eigen::Index rows, Eigen::Index cols, std::mt19937& rng) {
  Mat<float> m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = static_cast<float>(symmetricUniform(rng));
  return m;
}

TEST(AdamStateInvalid, RestoreRefusesAStateThatDoesNotFit) {
  Parameter<float> p;
  p.resize(3, 2);
  Adam<float> adam({&p}, {0.01});
  const Mat<float> ok = Mat<float>::Zero(3, 2);
  EXPECT_THROW(adam.restore(-1, {ok}, {ok}), std::invalid_argument);
  EXPECT_THROW(adam.restore(1, {}, {}), std::invalid_argument);
  EXPECT_THROW(adam.restore(1, {Mat<float>::Zero(2, 3)}, {ok}), std::invalid_argument);
  EXPECT_THROW(adam.restore(1, {ok}, {Mat<float>::Zero(3, 3)}), std::invalid_argument);
  EXPECT_EQ(adam.stepCount(), 0);  // unchanged after a refusal
  EXPECT_NO_THROW(adam.restore(4, {ok}, {ok}));
  EXPECT_EQ(adam.stepCount(), 4);
}

TEST(AdamState, RestoredOptimiserContinuesBitForBit) {
  std::mt19937 rng(4);
  Parameter<float> a, b;
  a.resize(7, 5);
  a.value = randomMatrix(7, 5, rng);
  std::vector<Mat<float>> gradients;
  for (int step = 0; step < 20; ++step) gradients.push_back(randomMatrix(7, 5, rng));

  Adam<float> uninterrupted({&a}, {0.01});
  for (int step = 0; step < 20; ++step) {
    a.grad = gradients[static_cast<std::size_t>(step)];
    uninterrupted.step();
    if (step == 9) {  // the "checkpoint": the weights and the optimiser state after 10 steps
      b = a;
      Adam<float> resumed({&b}, {0.01});
      resumed.restore(uninterrupted.stepCount(), uninterrupted.firstMoments(), uninterrupted.secondMoments());
      for (int later = 10; later < 20; ++later) {
        b.grad = gradients[static_cast<std::size_t>(later)];
        resumed.step();
      }
      EXPECT_EQ(resumed.stepCount(), 20);
    }
  }
  EXPECT_EQ(a.value, b.value);
  ASSERT_EQ(uninterrupted.firstMoments().size(), 1u);
  EXPECT_NE(uninterrupted.firstMoments()[0], Mat<float>::Zero(7, 5));
}

}  // namespace
}  // namespace motionstyle::nn
