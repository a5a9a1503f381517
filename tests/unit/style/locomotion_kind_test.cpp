// The locomotion kind (locomotion_kind.h): invalid input first, then the rules on made-up clips, the
// target each kind is paired with, and that the Stylizer's refinement aims at the clip's kind's target,
// not the one nearest the network's output.
#include <gtest/gtest.h>

#include <numbers>
#include <stdexcept>

#include "features/feature_layout.h"
#include "mapping/joint_mapping.h"
#include "style/evaluation.h"
#include "style/locomotion_kind.h"
#include "style/stylize_cleanup_job.h"
#include "style/stylizer.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

constexpr int kFrames = 120;

// A clip moving forward at `speed` cm/s and turning at `degrees_per_second` (left positive), the
// representation's rate; its joints stay where they are (the kind reads the root and the contacts).
Eigen::MatrixXd movingClip(double speed, double degrees_per_second) {
  Eigen::MatrixXd features = Eigen::MatrixXd::Zero(kFeatureCount, kFrames);
  features.row(kForwardVelocity).setConstant(speed / kDefaultFeatureFps);
  features.row(kTurningVelocity).setConstant(degrees_per_second * std::numbers::pi / 180.0 / kDefaultFeatureFps);
  return features;
}

// Contacts with every heel and toe down but on `airborne` frames out of every ten.
Eigen::MatrixXd contactsWithFlight(int airborne) {
  Eigen::MatrixXd contacts = Eigen::MatrixXd::Ones(kContactCount, kFrames);
  for (int t = 0; t < kFrames; ++t)
    if (t % 10 < airborne) contacts.col(t).setZero();
  return contacts;
}

TEST(LocomotionKindInvalid, RefusesShapesThatAreNotAClipsFeaturesAndContacts) {
  EXPECT_THROW(style::locomotionKind(Eigen::MatrixXd::Zero(65, kFrames), {}), std::invalid_argument);
  EXPECT_THROW(style::locomotionKind(Eigen::MatrixXd::Zero(kFeatureCount, 0), {}), std::invalid_argument);
  EXPECT_THROW(style::locomotionKind(movingClip(100, 0), Eigen::MatrixXd::Ones(3, kFrames)), std::invalid_argument);
  EXPECT_THROW(style::locomotionKind(movingClip(100, 0), Eigen::MatrixXd::Ones(kContactCount, kFrames - 1)),
               std::invalid_argument);
}

TEST(LocomotionKind, ARunIsReadFromItsFlightAndWithoutContactsFromItsSpeed) {
  // A fifth of the frames with no foot down is a run, whatever the speed; fewer is a walk.
  EXPECT_EQ(style::locomotionKind(movingClip(150, 0), contactsWithFlight(2)), "run");
  EXPECT_EQ(style::locomotionKind(movingClip(300, 0), contactsWithFlight(1)), "walk");
  // Without contacts, the speed decides.
  EXPECT_EQ(style::locomotionKind(movingClip(style::kRunSpeedCmPerSecond + 1, 0), {}), "run");
  EXPECT_EQ(style::locomotionKind(movingClip(style::kRunSpeedCmPerSecond - 1, 0), {}), "walk");
  // A run that turns is still a run (the networks' style clips have no turning run).
  EXPECT_EQ(style::locomotionKind(movingClip(300, 30), {}), "run");
}

TEST(LocomotionKind, AWalkTurnsLeftOrRightPastTheTurningRate) {
  const Eigen::MatrixXd down = contactsWithFlight(0);
  const double rate = style::kTurnDegreesPerSecond;
  EXPECT_EQ(style::locomotionKind(movingClip(100, rate + 1), down), "walk-turn-left");
  EXPECT_EQ(style::locomotionKind(movingClip(100, -rate - 1), down), "walk-turn-right");
  EXPECT_EQ(style::locomotionKind(movingClip(100, rate - 1), down), "walk");
  EXPECT_EQ(style::locomotionKind(movingClip(100, 1 - rate), down), "walk");
  // Standing still is read as a walk: the style's walk is what it is paired with.
  EXPECT_EQ(style::locomotionKind(movingClip(0, 0), down), "walk");
}

TEST(LocomotionKind, EachKindIsPairedAsTrainingPairsItsLabel) {
  const nn::Mat<float> gram = nn::Mat<float>::Zero(2, 2);
  const std::vector<nn::StyleTarget> four = {{"run", gram}, {"walk-turn-left", gram}, {"walk", gram}, {"", gram}};
  EXPECT_EQ(style::styleTargetFor(four, "run"), 0);
  EXPECT_EQ(style::styleTargetFor(four, "walk-turn-left"), 1);
  EXPECT_EQ(style::styleTargetFor(four, "walk"), 2);
  // A turn without its own target: the walk's, before the default.
  EXPECT_EQ(style::styleTargetFor(four, "walk-turn-right"), 2);
  // Without a walk, the default; with neither, none.
  EXPECT_EQ(style::styleTargetFor({{"run", gram}, {"", gram}}, "walk-turn-right"), 1);
  EXPECT_EQ(style::styleTargetFor({{"run", gram}}, "walk"), -1);
  EXPECT_EQ(style::styleTargetFor({}, "walk"), -1);
}

// A tiny network whose "walk" target is the Gram matrix of its own output on `content` (so the nearest
// target to that output) and whose "walk-turn-left" target is the zombie's.
nn::StyleModel tinyModelWithWalkAndTurn(const Eigen::MatrixXd& content) {
  nn::StyleModel model = test::tinyStyleModel();
  style::StyleRefinement off;
  off.iterations = 0;
  const Eigen::MatrixXd output = style::Stylizer(model, "tiny", off).networkOutput(content, {}, style::PathMode::Content);
  model.style_targets.push_back({"walk", style::styleGramOf(model.loss_network, model.normalisation, output)});
  model.style_targets.push_back({"walk-turn-left", style::styleGramOf(model.loss_network, model.normalisation,
                                                                      test::fixtureClips()[1].features.values)});
  return model;
}

TEST(LocomotionKind, TheRefinementAimsAtTheClipsKindNotTheTargetNearestTheNetworksOutput) {
  // CMU 131_01 turned left at 20 deg/s: a turning walk.
  Eigen::MatrixXd turning = test::fixtureClips()[0].features.values;
  turning.row(kTurningVelocity).setConstant(20.0 * std::numbers::pi / 180.0 / kDefaultFeatureFps);
  ASSERT_EQ(style::locomotionKind(turning, {}), "walk-turn-left");
  const nn::StyleModel both = tinyModelWithWalkAndTurn(turning);
  nn::StyleModel walk_only = both;
  walk_only.style_targets.pop_back();
  style::StyleRefinement off, on;
  off.iterations = 0;
  on.iterations = 60;
  const Eigen::MatrixXd network = style::Stylizer(both, "tiny", off).networkOutput(turning, {}, style::PathMode::Content);
  ASSERT_EQ(style::nearestStyleTarget(both.style_targets,
                                      both.loss_network.encode(both.normalisation.normalized(network),
                                                               static_cast<int>(network.cols()))),
            0)
      << "the test needs the walk target nearest the network's output";
  // The refinement with the turn's target alone (the default) and with the walk's alone: the turning
  // clip's output is the first, bit for bit; the same clip walked straight is the second.
  nn::StyleModel turn_only = both;
  turn_only.style_targets = {{"", both.style_targets[1].gram}};
  const auto refined = [&](const nn::StyleModel& model, const Eigen::MatrixXd& clip) {
    return style::Stylizer(model, "tiny", on).networkOutput(clip, {}, style::PathMode::Content);
  };
  const Eigen::MatrixXd aimed = refined(both, turning);
  EXPECT_EQ(aimed, refined(turn_only, turning));
  EXPECT_GT((aimed - refined(walk_only, turning)).cwiseAbs().maxCoeff(), 1e-3);
  Eigen::MatrixXd straight = turning;
  straight.row(kTurningVelocity).setZero();
  EXPECT_EQ(refined(both, straight), refined(walk_only, straight));
}

TEST(LocomotionKind, AKindGivenIsAimedAtInsteadOfTheClipsAndTheClipSaysWhich) {
  Eigen::MatrixXd turning = test::fixtureClips()[0].features.values;
  turning.row(kTurningVelocity).setConstant(20.0 * std::numbers::pi / 180.0 / kDefaultFeatureFps);
  const nn::StyleModel both = tinyModelWithWalkAndTurn(turning);
  nn::StyleModel walk_only = both;
  walk_only.style_targets.pop_back();
  const style::Stylizer stylizer(both, "tiny");
  EXPECT_THROW(stylizer.networkOutput(turning, {}, style::PathMode::Content, "jog"), std::invalid_argument);
  EXPECT_THROW(stylizer.aimedKind(turning, {}, "Walk"), std::invalid_argument);
  EXPECT_THROW(stylizer.stylizeFeatures(turning, {}, 1.0, style::PathMode::Content, "sprint"), std::invalid_argument);
  EXPECT_EQ(stylizer.aimedKind(turning, {}), "walk-turn-left");
  EXPECT_EQ(stylizer.aimedKind(turning, {}, "run"), "run");
  EXPECT_EQ(stylizer.aimedKind(turning, {}, "walk"), "walk");
  // Told "walk", the turning clip is refined as the walk-only network refines it.
  const Eigen::MatrixXd aimed_walk = stylizer.networkOutput(turning, {}, style::PathMode::Content, "walk");
  EXPECT_EQ(aimed_walk, style::Stylizer(walk_only, "tiny").networkOutput(turning, {}, style::PathMode::Content));
  EXPECT_GT((aimed_walk - stylizer.networkOutput(turning, {}, style::PathMode::Content)).cwiseAbs().maxCoeff(), 1e-3);
  // The stylized clip names the kind aimed at; none without a refinement or at strength 0.
  MotionFeatures content = test::fixtureClips()[0].features;
  content.values = turning;
  EXPECT_EQ(stylizer.stylize(content, 1.0).kind, "walk-turn-left");
  const style::StylizedClip told = stylizer.stylize(content, 0.5, style::PathMode::Content, "walk");
  EXPECT_EQ(told.kind, "walk");
  EXPECT_EQ(told.features, style::Stylizer(walk_only, "tiny").stylize(content, 0.5).features);
  EXPECT_EQ(stylizer.stylize(content, 0.0).kind, "");
  style::StyleRefinement off;
  off.iterations = 0;
  EXPECT_EQ(style::Stylizer(both, "tiny", off).stylize(content, 1.0, style::PathMode::Content, "run").kind, "");
}

// The job's kind (the app's Aim at): refused when unknown; a change runs the network again on a job's
// memory, as the memory-less job does, and a strength change after it keeps that output.
TEST(LocomotionKind, AJobsKindIsCheckedAndAChangeOfItRunsTheNetworkAgain) {
  style::StylizeCleanupJob job;
  job.content = readBvh(test::fixture("cmu_131_01.bvh"));
  job.content.values.conservativeResize(90, Eigen::NoChange);
  job.mapping = mapJoints(job.content.skeleton, "cmu_131_01.bvh");
  const MotionFeatures features = extractFeatures(job.content, job.mapping);
  const std::string own = style::locomotionKind(features.values, features.contacts);  // aimed at the walk's
  ASSERT_TRUE(own == "walk" || own == "walk-turn-right") << own;
  job.stylizer = std::make_shared<const style::Stylizer>(tinyModelWithWalkAndTurn(features.values));
  job.kind = "shuffle";
  EXPECT_THROW(job.validate(), std::invalid_argument);
  job.kind.clear();
  job.memory = std::make_shared<style::StylizeCleanupMemory>();
  const style::StylizeCleanupResult read = job.run();
  EXPECT_EQ(read.stylized.kind, own);
  job.kind = "walk-turn-left";
  style::StylizeCleanupJob fresh = job;
  fresh.memory = nullptr;
  const style::StylizeCleanupResult chosen = job.run();
  EXPECT_FALSE(chosen.network_output_kept);
  EXPECT_EQ(chosen.stylized.kind, "walk-turn-left");
  EXPECT_EQ(chosen.stylized.features, fresh.run().stylized.features);
  EXPECT_GT((chosen.stylized.features - read.stylized.features).cwiseAbs().maxCoeff(), 1e-3);
  job.strength = 0.5;
  EXPECT_TRUE(job.run().network_output_kept);
}

}  // namespace
}  // namespace motionstyle
