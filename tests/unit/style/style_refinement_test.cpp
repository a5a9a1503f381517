// The style refinement (style_refinement.h) and the hidden-unit descent it shares with the
// optimisation method: invalid input first, then that it lowers eq. 10's objective, picks the nearest
// style target, and that the Stylizer runs it only where asked and where the network has targets.
#include <gtest/gtest.h>

#include <atomic>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "common/errors.h"
#include "features/proportions.h"
#include "nn/losses.h"
#include "nn/transformation_objective.h"
#include "style/evaluation.h"
#include "style/hidden_style_descent.h"
#include "style/style_refinement.h"
#include "style/stylizer.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

nn::Mat<float> randomHidden(int rows, int cols, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  nn::Mat<float> m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = u(rng);
  return m;
}

// The objective the refinement descends, evaluated without gradients.
double objective(const nn::Mat<float>& hidden, const nn::Mat<float>& content, const nn::Mat<float>& gram,
                 const style::StyleRefinement& r) {
  const double c = nn::meanSquaredError<float>(hidden, content, 0.0f, nullptr);
  const double s = nn::styleLoss<float>(hidden, static_cast<int>(hidden.cols()), {gram}, 0.0f, nullptr);
  return r.content_weight * c + r.style_weight * s;
}

// A tiny style network that stores the zombie's Gram matrix as its one (default) style target.
nn::StyleModel tinyModelWithTarget() {
  nn::StyleModel model = test::tinyStyleModel();
  const Eigen::MatrixXd& style = test::fixtureClips()[1].features.values;
  model.style_targets.push_back({"", style::styleGramOf(model.loss_network, model.normalisation, style)});
  return model;
}

TEST(StyleRefinementInvalid, RefusesBadSettingsAndShapes) {
  const auto refused = [](auto change) {
    style::StyleRefinement r;
    change(r);
    return [r] { r.validate(); };
  };
  EXPECT_THROW(refused([](auto& r) { r.iterations = -1; })(), std::invalid_argument);
  EXPECT_THROW(refused([](auto& r) { r.iterations = style::StyleRefinement::kMaxIterations + 1; })(), std::invalid_argument);
  EXPECT_THROW(refused([](auto& r) { r.learning_rate = 0; })(), std::invalid_argument);
  EXPECT_THROW(refused([](auto& r) { r.learning_rate = std::numeric_limits<double>::quiet_NaN(); })(), std::invalid_argument);
  EXPECT_THROW(refused([](auto& r) { r.style_weight = -1; })(), std::invalid_argument);
  EXPECT_THROW(refused([](auto& r) { r.content_weight = 0, r.style_weight = 0; })(), std::invalid_argument);
  EXPECT_THROW(refused([](auto& r) { r.converged_fraction = 1.0; })(), std::invalid_argument);
  EXPECT_THROW(refused([](auto& r) { r.converged_fraction = -0.01; })(), std::invalid_argument);
  EXPECT_THROW(refused([](auto& r) { r.converged_fraction = std::numeric_limits<double>::quiet_NaN(); })(),
               std::invalid_argument);
  EXPECT_NO_THROW(style::StyleRefinement{}.validate());

  const nn::Mat<float> hidden = randomHidden(8, 20, 1);
  nn::Mat<float> edited = hidden;
  EXPECT_THROW(style::refineHiddenUnits(edited, randomHidden(8, 19, 2), nn::gramMatrix(hidden), {}), std::invalid_argument);
  EXPECT_THROW(style::refineHiddenUnits(edited, hidden, randomHidden(7, 7, 3), {}), std::invalid_argument);
  EXPECT_THROW(style::HiddenStyleDescent(hidden, hidden, nn::gramMatrix(hidden), 0, 0, 0.01), std::invalid_argument);
  EXPECT_THROW(style::nearestStyleTarget({{"walk", randomHidden(7, 7, 4)}}, hidden), std::invalid_argument);
  EXPECT_EQ(style::nearestStyleTarget({}, hidden), -1);
  style::StyleRefinement negative;
  negative.iterations = -1;
  EXPECT_THROW(style::Stylizer(test::tinyStyleModel(), "tiny", negative), std::invalid_argument);
  EXPECT_THROW(style::transformationShare(Eigen::MatrixXd::Zero(65, 10), 5), std::invalid_argument);
  EXPECT_THROW(style::transformationShare(Eigen::MatrixXd::Zero(kFeatureCount, 0), 5), std::invalid_argument);
  EXPECT_THROW(style::transformationShare(Eigen::MatrixXd::Zero(kFeatureCount, 10), -1), std::invalid_argument);
}

// A clip of `frames` frames whose hips stand at `ratios` (per frame, cycled) of the reference leg length.
Eigen::MatrixXd hipsAt(const std::vector<double>& ratios, int frames) {
  Eigen::MatrixXd features = Eigen::MatrixXd::Zero(kFeatureCount, frames);
  for (int t = 0; t < frames; ++t) features(1, t) = ratios[static_cast<std::size_t>(t) % ratios.size()] * referenceProportions().legLength();
  return features;
}

TEST(StyleRefinement, TheTransformationsShareFallsFromUprightToCrouchedHips) {
  const auto share = [](double ratio) { return style::transformationShare(hipsAt({ratio}, 2), 1)[0]; };
  EXPECT_EQ(share(1.05), 1.0f);  // a walk
  EXPECT_EQ(share(style::kUprightHipRatio), 1.0f);
  EXPECT_FLOAT_EQ(share(0.5 * (style::kUprightHipRatio + style::kCrouchedHipRatio)), 0.5f);
  EXPECT_EQ(share(style::kCrouchedHipRatio), 0.0f);
  EXPECT_EQ(share(0.51), 0.0f);  // 131_01's kneel
  for (double r = 0.60; r < 0.85; r += 0.01) EXPECT_LE(share(r), share(r + 0.01)) << r;
  // A column is its two frames' mean; columns past the clip read its last frame.
  const std::vector<float> columns = style::transformationShare(hipsAt({0.5, 1.1, 1.1}, 3), 3);
  ASSERT_EQ(columns.size(), 3u);
  EXPECT_GT(columns[0], 0.5f);  // (0.5 + 1.1) / 2 = 0.8
  EXPECT_EQ(columns[1], 1.0f);
  EXPECT_EQ(columns[2], 1.0f);
}

// Where the content crouches the refinement starts from the content's own hidden units: with a step too
// small to move anything, the output is the content's projection; upright, it is T's output. Compared
// away from the clip's ends, where the decoder also reads the edge padding's columns (T's).
TEST(StyleRefinement, ACrouchingClipStartsFromTheContentAndAnUprightOneFromTheNetwork) {
  const nn::StyleModel model = tinyModelWithTarget();
  Eigen::MatrixXd upright = test::fixtureClips()[0].features.values;
  upright.row(1).setConstant(1.05 * referenceProportions().legLength());
  Eigen::MatrixXd crouched = upright;
  crouched.row(1).setConstant(0.5 * referenceProportions().legLength());
  style::StyleRefinement still;
  still.iterations = 1;
  still.learning_rate = 1e-12;
  const style::Stylizer starting(model, "tiny", still);
  style::StyleRefinement off;
  off.iterations = 0;
  const style::Stylizer network(model, "tiny", off);
  constexpr int kEdge = 32;
  ASSERT_GT(upright.cols(), 4 * kEdge);
  const auto difference = [&](const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    return (a - b).middleCols(kEdge, a.cols() - 2 * kEdge).cwiseAbs().maxCoeff();
  };
  const double network_change = difference(network.networkOutput(crouched, {}, style::PathMode::Content),
                                           starting.projectFeatures(crouched));
  ASSERT_GT(network_change, 0.01);  // T moves the clip, or the test could not tell the two starts apart
  EXPECT_LT(difference(starting.networkOutput(crouched, {}, style::PathMode::Content), starting.projectFeatures(crouched)),
            0.05 * network_change);
  EXPECT_LT(difference(starting.networkOutput(upright, {}, style::PathMode::Content),
                       network.networkOutput(upright, {}, style::PathMode::Content)),
            0.05 * network_change);
}

// The descent's own eq. 5 (split over the cores by chunks of columns) is nn::styleLoss's, value and
// gradient, for a clip of several chunks and a remainder.
TEST(StyleRefinement, ItsTermsAreTheLossesOfEq10) {
  const nn::Mat<float> start = randomHidden(16, 150, 11);
  const nn::Mat<float> content = randomHidden(16, 150, 12);
  const nn::Mat<float> target = nn::gramMatrix(randomHidden(16, 40, 13));
  style::HiddenStyleDescent descent(start, content, target, 2.0, 30.0, 0.01);
  descent.zeroGrad();
  const double value = descent.addTerms();
  nn::Mat<float> grad = nn::Mat<float>::Zero(start.rows(), start.cols());
  const double c = nn::meanSquaredError<float>(start, content, 2.0f, &grad);
  const double s = nn::styleLoss<float>(start, static_cast<int>(start.cols()), {target}, 30.0f, &grad);
  EXPECT_NEAR(descent.content(), c, 1e-6 * c);
  EXPECT_NEAR(descent.style(), s, 1e-5 * s);
  EXPECT_NEAR(value, 2.0 * c + 30.0 * s, 1e-5 * value);
  EXPECT_LT((descent.hidden().grad - grad).cwiseAbs().maxCoeff(), 1e-5f * grad.cwiseAbs().maxCoeff());
}

TEST(StyleRefinement, PicksTheNearestTarget) {
  const nn::Mat<float> hidden = randomHidden(8, 30, 5);
  const std::vector<nn::StyleTarget> targets = {{"walk", randomHidden(8, 8, 6)},
                                                {"run", nn::gramMatrix(hidden) * 1.01f},
                                                {"", randomHidden(8, 8, 7)}};
  EXPECT_EQ(style::nearestStyleTarget(targets, hidden), 1);
}

// Hidden units to refine: the content's, a start near them and a style target away from both.
struct DescentProblem {
  nn::Mat<float> content = randomHidden(8, 40, 8);
  nn::Mat<float> start = content + 0.1f * randomHidden(8, 40, 9);
  nn::Mat<float> target = nn::gramMatrix(randomHidden(8, 60, 10)) * 2.0f;
};

TEST(StyleRefinement, StepsLowerTheObjectiveAndZeroStepsChangeNothing) {
  const auto [content, start, target] = DescentProblem{};
  style::StyleRefinement refinement;
  refinement.iterations = 0;
  refinement.converged_fraction = 0.0;  // every step
  nn::Mat<float> unchanged = start;
  EXPECT_EQ(style::refineHiddenUnits(unchanged, content, target, refinement), 0);
  EXPECT_EQ(unchanged, start);

  double previous = objective(start, content, target, refinement);
  for (int steps : {10, 30, 100}) {
    refinement.iterations = steps;
    nn::Mat<float> refined = start;
    style::refineHiddenUnits(refined, content, target, refinement);
    const double now = objective(refined, content, target, refinement);
    EXPECT_LT(now, previous) << steps << " steps";
    previous = now;
  }
}

// It stops once 10 steps lowered the objective by less than the converged fraction: the last 10
// steps it ran did, the 10 before them did not; with the fraction 0 it runs every step it may.
TEST(StyleRefinement, StopsOnceTenStepsLowerTheObjectiveByLessThanTheConvergedFraction) {
  const auto [content, start, target] = DescentProblem{};
  style::StyleRefinement converging;
  converging.iterations = 5000;
  nn::Mat<float> converged = start;
  const int steps = style::refineHiddenUnits(converged, content, target, converging);
  EXPECT_GT(steps, style::StyleRefinement::kConvergenceSteps);
  EXPECT_LT(steps, converging.iterations);
  // The same run with the fraction 0, cut after n steps: the same states (deterministic).
  const auto after = [&](int n) {
    style::StyleRefinement all = converging;
    all.converged_fraction = 0.0;
    all.iterations = n;
    nn::Mat<float> h = start;
    EXPECT_EQ(style::refineHiddenUnits(h, content, target, all), n);
    return h;
  };
  EXPECT_EQ(after(steps), converged);
  const auto e = [&](int n) { return objective(after(n), content, target, converging); };
  const int span = style::StyleRefinement::kConvergenceSteps;
  EXPECT_LT(e(steps - 1 - span) - e(steps - 1), converging.converged_fraction * e(steps - 1 - span));
  EXPECT_GE(e(steps - 2 - span) - e(steps - 2), converging.converged_fraction * e(steps - 2 - span));
}

// A set cancel flag stops the refinement before its next step (a dropped job stops within a step),
// inside the Stylizer too; a network that does not refine has nothing to stop.
TEST(StyleRefinement, ASetCancelFlagStopsIt) {
  const nn::Mat<float> content = randomHidden(8, 40, 8);
  const nn::Mat<float> target = nn::gramMatrix(randomHidden(8, 60, 10));
  nn::Mat<float> hidden = content;
  const std::atomic<bool> cancel{true};
  EXPECT_THROW(style::refineHiddenUnits(hidden, content, target, style::StyleRefinement{}, &cancel), OperationCancelled);
  const std::atomic<bool> go{false};
  EXPECT_NO_THROW(style::refineHiddenUnits(hidden, content, target, style::StyleRefinement{}, &go));

  const Eigen::MatrixXd& clip = test::fixtureClips()[0].features.values;
  const style::Stylizer refining(tinyModelWithTarget(), "tiny");
  EXPECT_THROW(refining.networkOutput(clip, {}, style::PathMode::Content, {}, &cancel), OperationCancelled);
  EXPECT_EQ(refining.networkOutput(clip, {}, style::PathMode::Content, {}, &go), refining.networkOutput(clip, {}, style::PathMode::Content));
  const style::Stylizer plain(test::tinyStyleModel(), "tiny");  // no style targets: no refinement
  EXPECT_NO_THROW(plain.networkOutput(clip, {}, style::PathMode::Content, {}, &cancel));
}

TEST(StyleRefinement, TheStylizerRunsItOnlyWithTargetsAndItAddsStyle) {
  const nn::StyleModel model = tinyModelWithTarget();
  const Eigen::MatrixXd& content = test::fixtureClips()[0].features.values;
  style::StyleRefinement off;
  off.iterations = 0;
  const style::Stylizer plain(model, "tiny", off);
  const style::Stylizer without_targets(test::tinyStyleModel(), "tiny");  // the default refinement
  EXPECT_EQ(plain.refinementSteps(), 0);
  EXPECT_EQ(without_targets.refinementSteps(), 0);
  // No targets: the network's output as it is (the same network, the same bits).
  EXPECT_EQ(without_targets.networkOutput(content, {}, style::PathMode::Content), plain.networkOutput(content, {}, style::PathMode::Content));

  style::StyleRefinement on;
  on.iterations = 60;
  const style::Stylizer refined(model, "tiny", on);
  EXPECT_EQ(refined.refinementSteps(), 60);
  const Eigen::MatrixXd before = plain.networkOutput(content, {}, style::PathMode::Content);
  const Eigen::MatrixXd after = refined.networkOutput(content, {}, style::PathMode::Content);
  ASSERT_EQ(after.cols(), content.cols());
  const nn::Mat<float>& gram = model.style_targets[0].gram;
  const style::StyleDistances d_before = style::measureStyleDistances(model.loss_network, model.normalisation, content, before, gram);
  const style::StyleDistances d_after = style::measureStyleDistances(model.loss_network, model.normalisation, content, after, gram);
  EXPECT_LT(d_after.style_after, 0.9 * d_before.style_after);
  // Deterministic: the same clip, the same refined output.
  EXPECT_EQ(refined.networkOutput(content, {}, style::PathMode::Content), after);
}

}  // namespace
}  // namespace motionstyle
