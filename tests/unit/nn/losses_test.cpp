// Loss terms (eq. 3-9): invalid input first, then defining properties, then gradient checks.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "gradient_check.h"
#include "loss_fixtures.h"
#include "nn/losses.h"

namespace motionstyle::nn {
namespace {

using test::checkGradient;
using test::kGradientTolerance;
using test::MatD;
using test::randomMatrix;

TEST(LossesInvalid, MismatchedShapesThrow) {
  std::mt19937 rng(1);
  const FeatureStatistics n = test::randomNormalisation(rng);
  const MatD x = randomMatrix(kFeatureCount, 8, rng);
  MatD wrong_grad(3, 3);
  EXPECT_THROW(meanSquaredError<double>(x, MatD::Zero(kFeatureCount, 7), 1.0, nullptr), std::invalid_argument);
  EXPECT_THROW(meanSquaredError<double>(x, x, 1.0, &wrong_grad), std::invalid_argument);
  EXPECT_THROW(footContactLoss<double>(x, 4, MatD::Zero(3, 8), n, 1.0, nullptr), std::invalid_argument);
  EXPECT_THROW(footContactLoss<double>(x, 3, MatD::Zero(4, 8), n, 1.0, nullptr), std::invalid_argument);
  EXPECT_THROW(footContactLoss<double>(MatD::Zero(65, 8), 4, MatD::Zero(4, 8), n, 1.0, nullptr),
               std::invalid_argument);
  EXPECT_THROW(boneLengthLoss<double>(x, 4, MatD::Zero(kBoneCount, 3), n, 1.0, nullptr), std::invalid_argument);
  EXPECT_THROW(trajectoryLoss<double>(x, MatD::Zero(kFeatureCount, 4), n, 1.0, nullptr), std::invalid_argument);
  const MatD h = randomMatrix(5, 8, rng);
  EXPECT_THROW(styleLoss<double>(h, 4, {MatD::Zero(5, 5), MatD::Zero(5, 5), MatD::Zero(5, 5)}, 1.0, nullptr),
               std::invalid_argument);
  EXPECT_THROW(styleLoss<double>(h, 4, {MatD::Zero(4, 4)}, 1.0, nullptr), std::invalid_argument);
  EXPECT_THROW(gramMatrix<double>(MatD::Zero(5, 0)), std::invalid_argument);
  FeatureStatistics bad = n;
  bad.std(3) = 0.0;
  EXPECT_THROW(trajectoryLoss<double>(x, x, bad, 1.0, nullptr), std::invalid_argument);
  bad = n;
  bad.mean.resize(10);
  EXPECT_THROW(bad.validate(), std::invalid_argument);
}

TEST(Gram, IsDividedByTheFrameCountSoRepeatingAClipChangesNothing) {
  std::mt19937 rng(2);
  const MatD h = randomMatrix(6, 9, rng);
  MatD twice(6, 18);
  twice << h, h;
  EXPECT_LT((gramMatrix<double>(twice) - gramMatrix<double>(h)).cwiseAbs().maxCoeff(), 1e-12);
  const MatD g = gramMatrix<double>(h);
  EXPECT_NEAR(g(1, 2), h.row(1).dot(h.row(2)) / 9.0, 1e-12);
  EXPECT_LT((g - g.transpose()).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(FootContact, ZeroForAPlantedFootAndPositiveForASlidingOne) {
  std::mt19937 rng(3);
  FeatureStatistics n;
  n.mean = Eigen::VectorXd::Zero(kFeatureCount);
  n.std = Eigen::VectorXd::Ones(kFeatureCount);
  // De-normalised = normalised here. Root moves and turns; every foot stays planted in the world.
  const int frames = 6;
  MatD x = randomMatrix(kFeatureCount, frames, rng, 20.0);
  for (int t = 0; t < frames; ++t) {
    x(kSidewaysVelocity, t) = 0.3 * t;
    x(kForwardVelocity, t) = 2.0;
    x(kTurningVelocity, t) = 0.05 * (t + 1);
  }
  for (int t = 0; t + 1 < frames; ++t) {
    const double w = x(kTurningVelocity, t);
    for (CanonicalJoint j : kContactJoint) {
      const int f = 3 * index(j);
      // p(t+1) = R_y(-w) (p(t) - v(t))
      const double px = x(f, t) - x(kSidewaysVelocity, t);
      const double pz = x(f + 2, t) - x(kForwardVelocity, t);
      x(f, t + 1) = std::cos(w) * px - std::sin(w) * pz;
      x(f + 1, t + 1) = x(f + 1, t);
      x(f + 2, t + 1) = std::sin(w) * px + std::cos(w) * pz;
    }
  }
  const MatD all = MatD::Ones(kContactCount, frames);
  EXPECT_LT(footContactLoss<double>(x, frames, all, n, 1.0, nullptr), 1e-20);
  MatD sliding = x;
  sliding(3 * index(CanonicalJoint::LeftToe), 3) += 2.0;  // 2 cm slide into frame 3
  const MatD one = [&] {
    MatD c = MatD::Zero(kContactCount, frames);
    c(static_cast<int>(ContactLabel::LeftToe), 2) = 1.0;
    return c;
  }();
  // One labelled (t, c): |d|^2 = 2^2 after R_y: the slide is a pure translation.
  EXPECT_NEAR(footContactLoss<double>(sliding, frames, one, n, 1.0, nullptr), 4.0, 1e-9);
  // Nothing labelled: zero, and no gradient.
  MatD grad = MatD::Zero(kFeatureCount, frames);
  EXPECT_EQ(footContactLoss<double>(sliding, frames, MatD::Zero(kContactCount, frames), n, 1.0, &grad), 0.0);
  EXPECT_EQ(grad.cwiseAbs().maxCoeff(), 0.0);
}

TEST(FootContact, LastFrameOfAWindowIsNeverPairedWithTheNextWindow) {
  std::mt19937 rng(4);
  const FeatureStatistics n = test::randomNormalisation(rng);
  const MatD x = randomMatrix(kFeatureCount, 8, rng);
  MatD contacts = MatD::Zero(kContactCount, 8);
  contacts.col(3).setOnes();  // last frame of window 0
  EXPECT_EQ(footContactLoss<double>(x, 4, contacts, n, 1.0, nullptr), 0.0);
  EXPECT_GT(footContactLoss<double>(x, 8, contacts, n, 1.0, nullptr), 0.0);
}

TEST(BoneLength, ZeroForMatchingLengthsAndSafeForZeroLengthBones) {
  std::mt19937 rng(5);
  FeatureStatistics n;
  n.mean = Eigen::VectorXd::Zero(kFeatureCount);
  n.std = Eigen::VectorXd::Ones(kFeatureCount);
  MatD x = randomMatrix(kFeatureCount, 3, rng, 30.0);
  MatD lengths(kBoneCount, 1);
  for (int b = 0; b < kBoneCount; ++b) {
    const int child = b + 1;
    const int parent = kCanonicalParent[static_cast<std::size_t>(child)];
    lengths(b, 0) = (x.block(3 * child, 0, 3, 1) - x.block(3 * parent, 0, 3, 1)).norm();
  }
  // Same lengths in every frame: move each frame's joints rigidly (translate).
  for (int t = 1; t < 3; ++t)
    for (int j = 0; j < kCanonicalJointCount; ++j) {
      // Scalar writes: GCC 12 misreports AVX-512 loads when a fixed-size vector meets a dynamic block.
      x(3 * j, t) = x(3 * j, 0) + t;
      x(3 * j + 1, t) = x(3 * j + 1, 0) + 2.0 * t;
      x(3 * j + 2, t) = x(3 * j + 2, 0) - t;
    }
  EXPECT_LT(boneLengthLoss<double>(x, 3, lengths, n, 1.0, nullptr), 1e-20);

  // A zero-length bone (hand end on the wrist): finite loss and gradient.
  const int hand_end = index(CanonicalJoint::LeftHandEnd);
  x.block(3 * hand_end, 0, 3, 1) = x.block(3 * index(CanonicalJoint::LeftWrist), 0, 3, 1);
  MatD grad = MatD::Zero(kFeatureCount, 3);
  const double loss = boneLengthLoss<double>(x, 3, lengths, n, 1.0, &grad);
  EXPECT_TRUE(std::isfinite(loss));
  EXPECT_TRUE(grad.allFinite());
  EXPECT_NEAR(loss, lengths(hand_end - 1, 0) * lengths(hand_end - 1, 0) / (kBoneCount * 3.0), 1e-9);
}

TEST(Trajectory, MeasuresDeNormalisedVelocityErrors) {
  FeatureStatistics n;
  n.mean = Eigen::VectorXd::Constant(kFeatureCount, 5.0);
  n.std = Eigen::VectorXd::Constant(kFeatureCount, 2.0);
  MatD target = MatD::Zero(kFeatureCount, 4);
  MatD x = target;
  x(kForwardVelocity, 1) = 1.0;  // 2 cm/frame faster in one of 4 frames
  x.row(0).setConstant(7.0);     // positions do not count
  EXPECT_NEAR(trajectoryLoss<double>(x, target, n, 1.0, nullptr), 4.0 / 4.0, 1e-12);
}

TEST(LossGradient, EveryTermOverRandomShapes) {
  std::mt19937 rng(6);
  for (int trial = 0; trial < 4; ++trial) {
    const int frames = 2 + static_cast<int>(rng() % 6);
    const int windows = 1 + static_cast<int>(rng() % 3);
    const Eigen::Index n = static_cast<Eigen::Index>(windows) * frames;
    const FeatureStatistics norm = test::randomNormalisation(rng);
    MatD x = randomMatrix(kFeatureCount, n, rng);
    const double weight = 0.7;
    auto check = [&](const char* name, MatD& input, const std::function<double(MatD*)>& term) {
      MatD grad = MatD::Zero(input.rows(), input.cols());
      term(&grad);
      auto loss = [&] { return weight * term(nullptr); };
      const auto result = checkGradient(input, grad, loss, 0, rng);
      EXPECT_LT(result.max_error, kGradientTolerance) << name << " trial " << trial;
    };
    const MatD target = randomMatrix(kFeatureCount, n, rng);
    check("mse", x, [&](MatD* g) { return meanSquaredError<double>(x, target, weight, g); });
    check("content", x, [&](MatD* g) { return contentLoss<double>(x, target, weight, g); });
    const MatD contacts = test::randomContacts(n, rng);
    check("foot", x, [&](MatD* g) { return footContactLoss<double>(x, frames, contacts, norm, weight, g); });
    const MatD lengths = test::randomBoneLengths(windows, rng);
    check("bone", x, [&](MatD* g) { return boneLengthLoss<double>(x, frames, lengths, norm, weight, g); });
    check("trajectory", x, [&](MatD* g) { return trajectoryLoss<double>(x, target, norm, weight, g); });

    const int channels = 3 + static_cast<int>(rng() % 5);
    MatD h = randomMatrix(channels, n, rng).cwiseMax(0.0);  // hidden units are ReLU outputs
    h += randomMatrix(channels, n, rng, 0.1);
    std::vector<MatD> one{gramMatrix<double>(randomMatrix(channels, 7, rng))};
    std::vector<MatD> per_window;
    for (int b = 0; b < windows; ++b) per_window.push_back(gramMatrix<double>(randomMatrix(channels, 5, rng)));
    check("style shared", h, [&](MatD* g) { return styleLoss<double>(h, frames, one, weight, g); });
    check("style per window", h, [&](MatD* g) { return styleLoss<double>(h, frames, per_window, weight, g); });

    Parameter<double> p1;
    Parameter<double> p2;
    p1.resize(3, 4);
    p2.resize(5, 1);
    p1.value = randomMatrix(3, 4, rng);
    p2.value = randomMatrix(5, 1, rng);
    const double l1 = meanAbsoluteWeight<double>({&p1, &p2}, weight);
    EXPECT_NEAR(l1, (p1.value.cwiseAbs().sum() + p2.value.cwiseAbs().sum()) / 17.0, 1e-12);
    auto l1_loss = [&] {
      Parameter<double> a = p1;
      Parameter<double> b = p2;
      return weight * meanAbsoluteWeight<double>({&a, &b}, 0.0);
    };
    const MatD g1 = p1.grad;
    const MatD g2 = p2.grad;
    EXPECT_LT(checkGradient(p1.value, g1, l1_loss, 0, rng).max_error, kGradientTolerance);
    EXPECT_LT(checkGradient(p2.value, g2, l1_loss, 0, rng).max_error, kGradientTolerance);
  }
}

}  // namespace
}  // namespace motionstyle::nn
