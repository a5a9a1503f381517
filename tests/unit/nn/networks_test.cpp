// The two networks end to end, the full eq. 10 objective and Adam.

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "gradient_check.h"
#include "loss_fixtures.h"
#include "nn/adam.h"
#include "nn/compute_pool.h"
#include "nn/loss_network.h"
#include "nn/transformation_objective.h"
#include "nn/transformation_network.h"

namespace motionstyle::nn {
namespace {

using test::checkGradient;
using test::kGradientTolerance;
using test::MatD;
using test::randomMatrix;

StyleBatch<double> randomStyleBatch(const LossNetwork<double>& loss_network, int windows, int frames, std::mt19937& rng,
                                    bool per_window_style) {
  StyleBatch<double> batch;
  batch.frames = frames;
  batch.content = randomMatrix(loss_network.shape().features, static_cast<Eigen::Index>(windows) * frames, rng);
  batch.contacts = test::randomContacts(batch.content.cols(), rng);
  batch.bone_lengths = test::randomBoneLengths(windows, rng);
  batch.content_hidden = contentHidden(loss_network, batch.content, frames);
  const int styles = per_window_style ? windows : 1;
  for (int s = 0; s < styles; ++s)
    batch.style_grams.push_back(styleGram(loss_network, randomMatrix(loss_network.shape().features, 13 + s, rng)));
  return batch;
}

LossWeights testWeights() {
  LossWeights w;
  w.content = 1.0;
  w.style = 0.5;
  w.foot = 0.01;
  w.bone = 0.01;
  w.trajectory = 0.1;
  return w;
}

TEST(NetworksInvalid, MismatchedShapesThrow) {
  LossNetwork<double> loss_network({6, 8, 3});
  EXPECT_THROW(loss_network.encode(MatD::Zero(5, 8), 4), std::invalid_argument);
  EXPECT_THROW(loss_network.decode(MatD::Zero(7, 4), 2), std::invalid_argument);
  EXPECT_THROW(loss_network.encodeBackward(MatD::Zero(8, 2)), std::logic_error);
  std::mt19937 rng(1);
  EXPECT_THROW(loss_network.accumulateReconstruction(MatD::Zero(6, 8), 4, 0.1, 0.25, nullptr), std::invalid_argument);
  TransformationNetwork<double> t({6, 5, 3, false});
  EXPECT_THROW(t.apply(MatD::Zero(7, 8), 4), std::invalid_argument);

  LossNetwork<double> loss_net({kFeatureCount, 8, 3});
  loss_net.initialise(1);
  TransformationNetwork<double> tt({kFeatureCount, 5, 3, true});
  const FeatureStatistics norm = test::randomNormalisation(rng);
  StyleBatch<double> batch = randomStyleBatch(loss_net, 2, 4, rng, false);
  EXPECT_NO_THROW(evaluateObjective(tt, loss_net, batch, norm, LossWeights{}));
  auto broken = batch;
  broken.contacts = MatD::Zero(kContactCount, 7);
  EXPECT_THROW(accumulateObjective(tt, loss_net, broken, norm, LossWeights{}), std::invalid_argument);
  broken = batch;
  broken.bone_lengths = MatD::Zero(kBoneCount, 3);
  EXPECT_THROW(accumulateObjective(tt, loss_net, broken, norm, LossWeights{}), std::invalid_argument);
  broken = batch;
  broken.content_hidden = MatD::Zero(8, 3);
  EXPECT_THROW(accumulateObjective(tt, loss_net, broken, norm, LossWeights{}), std::invalid_argument);
  broken = batch;
  broken.style_grams.push_back(broken.style_grams[0]);
  broken.style_grams.push_back(broken.style_grams[0]);
  EXPECT_THROW(accumulateObjective(tt, loss_net, broken, norm, LossWeights{}), std::invalid_argument);
  LossWeights negative;
  negative.style = -1.0;
  EXPECT_THROW(accumulateObjective(tt, loss_net, batch, norm, negative), std::invalid_argument);
  AdamOptions bad;
  bad.beta1 = 1.0;
  std::vector<Parameter<double>*> none;
  EXPECT_THROW(Adam<double>(none, bad), std::invalid_argument);
}

TEST(LossNetwork, OutputHasTheInputLengthForOddAndEvenWindows) {
  LossNetwork<double> loss_network({5, 7, 5});
  loss_network.initialise(3);
  std::mt19937 rng(2);
  for (int frames : {1, 2, 3, 8, 9, 30, 31}) {
    const MatD x = randomMatrix(5, 2 * frames, rng);
    EXPECT_EQ(loss_network.encode(x, frames).cols(), 2 * evenFrames(frames) / 2);
    const MatD y = loss_network.project(x, frames);
    EXPECT_EQ(y.rows(), 5);
    EXPECT_EQ(y.cols(), 2 * frames);
  }
}

TEST(LossNetwork, OddWindowEqualsTheEvenWindowWithItsLastFrameRepeated) {
  LossNetwork<double> loss_network({4, 6, 5});
  loss_network.initialise(4);
  std::mt19937 rng(3);
  const MatD x = randomMatrix(4, 7, rng);
  MatD padded(4, 8);
  padded << x, x.col(6);
  EXPECT_LT((loss_network.project(x, 7) - loss_network.project(padded, 8).leftCols(7)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(LossNetworkGradient, ReconstructionLossWrtW0b0AndDecoderWeights) {
  std::mt19937 rng(4);
  struct Case {
    LossNetworkShape shape;
    int windows, frames, samples;
    double dropout;
  };
  for (const Case& c : {Case{{5, 6, 3}, 2, 6, 0, 0.0}, Case{{4, 7, 5}, 3, 5, 0, 0.25},
                        Case{{kFeatureCount, 256, 25}, 2, 9, 15, 0.25}}) {  // 15 random entries per
                                                                              // parameter: ~1 min under ASan
    LossNetwork<double> loss_network(c.shape);
    loss_network.initialise(5);
    loss_network.encoder.bias.value = randomMatrix(c.shape.hidden, 1, rng, 0.1);
    const MatD x = randomMatrix(c.shape.features, static_cast<Eigen::Index>(c.windows) * c.frames, rng);
    const double alpha = 0.1;
    auto run = [&](LossNetwork<double>& net) {
      std::mt19937 mask(77);  // the same dropout mask for the analytic and every numeric evaluation
      return net.accumulateReconstruction(x, c.frames, alpha, c.dropout, &mask).total;
    };
    loss_network.zeroGrad();
    run(loss_network);
    auto loss = [&] {
      LossNetwork<double> probe = loss_network;
      return run(probe);
    };
    for (Parameter<double>* p : loss_network.parameters()) {
      const MatD analytic = p->grad;
      const auto result = checkGradient(p->value, analytic, loss, c.samples, rng);
      EXPECT_LT(result.max_error, kGradientTolerance) << p->name << " hidden " << c.shape.hidden;
      EXPECT_GT(analytic.cwiseAbs().maxCoeff(), 0.0) << p->name;
    }
  }
}

TEST(LossNetworkGradient, FrozenEncoderGradientWrtInput) {
  std::mt19937 rng(5);
  LossNetwork<double> loss_network({kFeatureCount, 256, 25});
  loss_network.initialise(6);
  loss_network.encoder.bias.value = randomMatrix(256, 1, rng, 0.1);
  for (int frames : {8, 7}) {
    MatD x = randomMatrix(kFeatureCount, 2 * frames, rng);
    const MatD r = randomMatrix(256, 2 * evenFrames(frames) / 2, rng);
    loss_network.zeroGrad();
    const MatD h = loss_network.encodeForward(x, frames);
    EXPECT_LT((h - loss_network.encode(x, frames)).cwiseAbs().maxCoeff(), 1e-12);
    const MatD dx = loss_network.encodeBackward(r);
    EXPECT_EQ(loss_network.encoder.weight.grad.cwiseAbs().maxCoeff(), 0.0);  // frozen: no parameter gradient
    auto loss = [&] { return loss_network.encode(x, frames).cwiseProduct(r).sum(); };
    EXPECT_LT(checkGradient(x, dx, loss, 60, rng).max_error, kGradientTolerance) << frames;
  }
}

TEST(TransformerGradient, TotalStyleLossWrtEveryParameter) {
  std::mt19937 rng(7);
  LossNetwork<double> loss_network({kFeatureCount, 256, 25});
  loss_network.initialise(8);
  loss_network.encoder.bias.value = randomMatrix(256, 1, rng, 0.05);
  const FeatureStatistics norm = test::randomNormalisation(rng);
  const LossWeights weights = testWeights();
  for (bool residual : {true, false}) {
    TransformationNetwork<double> t({kFeatureCount, 128, 25, residual});
    t.initialise(9);
    for (Parameter<double>* p : t.parameters())
      if (p->value.cols() == 1) p->value = randomMatrix(p->value.rows(), 1, rng, 0.05);
    const StyleBatch<double> batch = randomStyleBatch(loss_network, 2, 8, rng, !residual);
    t.zeroGrad();
    const ObjectiveTerms terms = accumulateObjective(t, loss_network, batch, norm, weights);
    const ObjectiveTerms evaluated = evaluateObjective(t, loss_network, batch, norm, weights);
    EXPECT_NEAR(terms.total, evaluated.total, 1e-10 * std::abs(evaluated.total));
    for (double term : {terms.content, terms.style, terms.foot, terms.bone, terms.trajectory})
      EXPECT_GT(term, 0.0);
    EXPECT_EQ(loss_network.encoder.weight.grad.cwiseAbs().maxCoeff(), 0.0);  // the loss network stays frozen
    auto loss = [&] { return evaluateObjective(t, loss_network, batch, norm, weights).total; };
    for (Parameter<double>* p : t.parameters()) {
      const MatD analytic = p->grad;
      const auto result = checkGradient(p->value, analytic, loss, 10, rng);  // 10 random entries each
      EXPECT_LT(result.max_error, kGradientTolerance) << p->name << (residual ? " residual" : " plain");
    }
  }
}

// A training step at its real size (16 windows of 240 frames, float, the spectral layers) gives the same
// terms and the same gradients, bit for bit, whether its parts run on the pool's threads or all on the
// calling thread (SerialComputeScope: the same split): no part writes another's values or reads them
// before they are done.
TEST(TransformerGradient, ATrainingStepIsTheSameWhicheverThreadsRunItsParts) {
  std::mt19937 rng(11);
  LossNetwork<float> loss_network;
  loss_network.initialise(12);
  TransformationNetwork<float> t;
  t.initialise(13);
  const FeatureStatistics norm = test::randomNormalisation(rng);
  StyleBatch<float> batch;
  batch.frames = 240;
  batch.content = randomMatrix(kFeatureCount, 16 * 240, rng).cast<float>();
  batch.contacts = test::randomContacts(batch.content.cols(), rng).cast<float>();
  batch.bone_lengths = test::randomBoneLengths(16, rng).cast<float>();
  batch.content_hidden = contentHidden(loss_network, batch.content, 240);
  batch.style_grams.push_back(styleGram(loss_network, Mat<float>(randomMatrix(kFeatureCount, 300, rng).cast<float>())));
  const auto step = [&] {
    t.zeroGrad();
    const ObjectiveTerms terms = accumulateObjective(t, loss_network, batch, norm, LossWeights{});
    std::vector<Mat<float>> grads;
    for (Parameter<float>* p : t.parameters()) grads.push_back(p->grad);
    return std::pair{terms, grads};
  };
  const auto [pooled_terms, pooled] = step();
  std::pair<ObjectiveTerms, std::vector<Mat<float>>> serial;
  {
    SerialComputeScope one_thread;
    serial = step();
  }
  EXPECT_EQ(pooled_terms.total, serial.first.total);
  EXPECT_EQ(pooled_terms.style, serial.first.style);
  EXPECT_EQ(pooled_terms.bone, serial.first.bone);
  for (std::size_t i = 0; i < pooled.size(); ++i) EXPECT_EQ(pooled[i], serial.second[i]) << t.parameters()[i]->name;
}

TEST(TransformationNetwork, OutputHasTheInputLengthAndResidualStartsNearIdentity) {
  TransformationNetwork<double> t;
  t.initialise(10);
  std::mt19937 rng(8);
  for (int frames : {1, 5, 24, 25}) {
    const MatD x = randomMatrix(kFeatureCount, frames, rng);
    const MatD y = t.apply(x, frames);
    EXPECT_EQ(y.cols(), frames);
    // Residual, output layer scaled down at init: the output starts close to the input.
    EXPECT_LT((y - x).norm(), 0.5 * x.norm()) << frames;
  }
}

TEST(Determinism, SameSeedSameWeightsOtherSeedOtherWeights) {
  LossNetwork<float> a;
  LossNetwork<float> b;
  a.initialise(42);
  b.initialise(42);
  EXPECT_EQ(a.encoder.weight.value, b.encoder.weight.value);
  EXPECT_EQ(a.decoder.weight.value, b.decoder.weight.value);
  b.initialise(43);
  EXPECT_NE(a.encoder.weight.value, b.encoder.weight.value);
  TransformationNetwork<float> ta;
  TransformationNetwork<float> tb;
  ta.initialise(1);
  tb.initialise(1);
  EXPECT_EQ(ta.conv2.weight.value, tb.conv2.weight.value);
  EXPECT_EQ(ta.conv3.weight.value, tb.conv3.weight.value);
}

TEST(LossNetwork, SameWeightsNeedsTheShapeAndEveryParameterToMatch) {
  LossNetwork<float> a({kFeatureCount, 4, 3});
  a.initialise(7);
  LossNetwork<float> b = a;
  EXPECT_TRUE(sameWeights(a, b));
  b.encoder.bias.value(1, 0) += 1e-3f;  // b0 alone: eq. 2 subtracts it too
  EXPECT_FALSE(sameWeights(a, b));
  b = a;
  b.decoder.weight.value(0, 0) += 1e-3f;
  EXPECT_FALSE(sameWeights(a, b));
  LossNetwork<float> wider({kFeatureCount, 5, 3});
  EXPECT_FALSE(sameWeights(a, wider));
}

TEST(Adam, ConvergesOnAQuadraticAndUsesBiasCorrection) {
  // f(w) = sum_i c_i (w_i - t_i)^2 with very different curvatures.
  Parameter<double> w;
  w.resize(4, 1);
  // Dynamic-size vectors: GCC 12 misreports AVX-512 loads of fixed-size ones mixed with blocks.
  const Eigen::VectorXd target = (Eigen::VectorXd(4) << 1.0, -2.0, 0.5, 3.0).finished();
  const Eigen::VectorXd curvature = (Eigen::VectorXd(4) << 1.0, 10.0, 0.1, 100.0).finished();
  AdamOptions options;
  options.learning_rate = 0.05;
  Adam<double> adam({&w}, options);
  // First step: bias correction makes it exactly lr * sign(g) (up to eps).
  adam.zeroGrad();
  w.grad.col(0) = 2.0 * curvature.cwiseProduct(w.value.col(0) - target);
  adam.step();
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(std::abs(w.value(i, 0)), 0.05, 1e-6);
  for (int step = 0; step < 3000; ++step) {
    adam.zeroGrad();
    w.grad.col(0) = 2.0 * curvature.cwiseProduct(w.value.col(0) - target);
    if (step > 2000) adam.setLearningRate(0.001);
    adam.step();
  }
  EXPECT_LT((w.value.col(0) - target).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_EQ(adam.stepCount(), 3001);
  EXPECT_THROW(adam.setLearningRate(-1.0), std::invalid_argument);
}

TEST(Training, AFewAdamStepsReduceBothLosses) {
  std::mt19937 rng(9);
  // A smooth synthetic signal: the loss network can learn it and the loss must fall.
  const int frames = 32;
  MatD x(kFeatureCount, 2 * frames);
  for (Eigen::Index t = 0; t < x.cols(); ++t)
    for (int f = 0; f < kFeatureCount; ++f) x(f, t) = std::sin(0.2 * static_cast<double>(t) + f);
  LossNetwork<double> loss_network({kFeatureCount, 32, 9});
  loss_network.initialise(11);
  Adam<double> adam(loss_network.parameters(), AdamOptions{3e-3});
  double first = 0;
  double last = 0;
  for (int step = 0; step < 40; ++step) {
    adam.zeroGrad();
    const double loss = loss_network.accumulateReconstruction(x, frames, 0.01).total;
    if (step == 0) first = loss;
    last = loss;
    adam.step();
  }
  EXPECT_LT(last, 0.5 * first);
}

}  // namespace
}  // namespace motionstyle::nn
