// style_content_frontier.h on small synthetic clips: invalid input first, then what the frontier must
// be (at the wanted ratio, below any other way to that ratio, the motions' frontier above the hidden
// units').
#include "style_content_frontier.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace motionstyle::bench {
namespace {

Eigen::MatrixXd gram(const Eigen::MatrixXd& h) { return h * h.transpose() / static_cast<double>(h.cols()); }

double contentDistance(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).squaredNorm() / static_cast<double>(a.size());
}

double styleRatio(const FrontierClip& clip, const Eigen::MatrixXd& h) {
  return (gram(h) - clip.style_gram).squaredNorm() / (gram(clip.hidden) - clip.style_gram).squaredNorm();
}

// Non-negative hidden units (they follow a ReLU) and a style clip's Gram matrix of another clip.
FrontierClip randomClip(std::mt19937& rng, int hidden, int frames, Eigen::MatrixXd* style_hidden = nullptr) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  FrontierClip clip;
  clip.hidden = Eigen::MatrixXd::NullaryExpr(hidden, frames, [&] { return unit(rng); });
  Eigen::MatrixXd style = Eigen::MatrixXd::NullaryExpr(hidden, frames, [&] { return 1.5 * unit(rng) * unit(rng); });
  clip.style_gram = gram(style);
  if (style_hidden != nullptr) *style_hidden = style;
  return clip;
}

TEST(StyleContentFrontier, RejectsInvalidInput) {
  std::mt19937 rng(1);
  const FrontierClip clip = randomClip(rng, 6, 20);
  EXPECT_THROW(leastContentAtStyleRatio({}, 0.5), std::invalid_argument);
  EXPECT_THROW(leastContentAtStyleRatio({clip}, 0.0), std::invalid_argument);
  EXPECT_THROW(leastContentAtStyleRatio({clip}, 1.0), std::invalid_argument);
  FrontierClip wrong_gram = clip;
  wrong_gram.style_gram = Eigen::MatrixXd::Identity(5, 5);
  EXPECT_THROW(leastContentAtStyleRatio({wrong_gram}, 0.5), std::invalid_argument);
  FrontierClip at_its_style = clip;
  at_its_style.style_gram = gram(clip.hidden);
  EXPECT_THROW(leastContentAtStyleRatio({at_its_style}, 0.5), std::invalid_argument);
  EXPECT_THROW(leastContentAtStyleRatio({clip}, 0.5, FrontierSpace::Motions), std::invalid_argument);  // no encoder
}

TEST(StyleContentFrontier, ReachesTheWantedRatioBelowTheStraightWayThere) {
  std::mt19937 rng(2);
  Eigen::MatrixXd style_a, style_b;
  const std::vector<FrontierClip> clips = {randomClip(rng, 6, 30, &style_a), randomClip(rng, 6, 40, &style_b)};
  const FrontierPoint point = leastContentAtStyleRatio(clips, 0.4);
  EXPECT_NEAR(point.mean_style_ratio, 0.4, 0.4 * 0.006);
  EXPECT_GT(point.mean_content_distance, 0.0);
  // Another way to the same mean ratio: each clip moved straight toward a clip with the style's Gram
  // matrix, by the one fraction that gives the mean ratio (bisection).
  const auto straight = [&](double t) {
    return std::pair{0.5 * (styleRatio(clips[0], clips[0].hidden + t * (style_a - clips[0].hidden)) +
                            styleRatio(clips[1], clips[1].hidden + t * (style_b - clips[1].hidden))),
                     0.5 * (contentDistance(clips[0].hidden + t * (style_a - clips[0].hidden), clips[0].hidden) +
                            contentDistance(clips[1].hidden + t * (style_b - clips[1].hidden), clips[1].hidden))};
  };
  double low = 0.0, high = 1.0;
  for (int i = 0; i < 60; ++i) (straight(0.5 * (low + high)).first > point.mean_style_ratio ? low : high) = 0.5 * (low + high);
  EXPECT_LT(point.mean_content_distance, straight(high).second);
  // A stronger style costs more content.
  EXPECT_GT(leastContentAtStyleRatio(clips, 0.2).mean_content_distance, point.mean_content_distance);
}

TEST(StyleContentFrontier, MotionsReachNoLowerThanTheHiddenUnits) {
  nn::LossNetwork<float> encoder(nn::LossNetworkShape{4, 6, 3});
  encoder.initialise(7);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  FrontierClip clip;
  clip.encoder = &encoder;
  clip.features = Eigen::MatrixXd::NullaryExpr(4, 32, [&] { return normal(rng); });
  clip.hidden = encoder.encode(clip.features.cast<float>(), 32).cast<double>();
  const Eigen::MatrixXd style_features = Eigen::MatrixXd::NullaryExpr(4, 32, [&] { return 2.0 * normal(rng); });
  clip.style_gram = gram(encoder.encode(style_features.cast<float>(), 32).cast<double>());
  const FrontierPoint hidden = leastContentAtStyleRatio({clip}, 0.5, FrontierSpace::HiddenUnits);
  const FrontierPoint motions = leastContentAtStyleRatio({clip}, 0.5, FrontierSpace::Motions);
  EXPECT_NEAR(motions.mean_style_ratio, 0.5, 0.5 * 0.006);
  EXPECT_GE(motions.mean_content_distance, 0.99 * hidden.mean_content_distance);
}

}  // namespace
}  // namespace motionstyle::bench
