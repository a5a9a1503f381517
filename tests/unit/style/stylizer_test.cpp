// Stylization (strength, any length, no seams), the optimisation method and the evaluation figures.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>
#include <nlohmann/json.hpp>

#include "common/errors.h"
#include "style/evaluation.h"
#include "style/optimization_transfer.h"
#include "style/familiarity.h"
#include "style/stylizer.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

// A clip of `frames` frames made by repeating the fixtures' features end to end.
Eigen::MatrixXd longFeatures(int frames) {
  Eigen::MatrixXd out(kFeatureCount, frames);
  int filled = 0;
  while (filled < frames)
    for (const auto& clip : test::fixtureClips()) {
      const int take = std::min(clip.frameCount(), frames - filled);
      out.middleCols(filled, take) = clip.features.values.leftCols(take);
      filled += take;
      if (filled == frames) break;
    }
  return out;
}

// Damaged weights that pass the file's checks can still throw a joint kilometres away: an error that
// names the network, not a clip the clean-up chokes on.
TEST(Stylizer, RefusesANetworkWhoseOutputIsNotPhysical) {
  nn::StyleModel model = test::tinyStyleModel();
  for (nn::Parameter<float>* p : model.transformation.parameters())
    if (p->value.cols() == 1) p->value.setConstant(1e5f);
  const style::Stylizer stylizer(std::move(model), "damaged.net");
  try {
    stylizer.stylizeFeatures(test::fixtureClips()[0].features.values, {}, 1.0);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(error.file(), "damaged.net");
    EXPECT_NE(error.detail().find("not physical"), std::string::npos) << error.what();
  }
}

TEST(Stylizer, StrengthZeroReturnsTheContentExactly) {
  const style::Stylizer stylizer(test::tinyStyleModel());
  const MotionFeatures& content = test::fixtureClips()[0].features;
  const style::StylizedClip clip = stylizer.stylize(content, 0.0);
  EXPECT_EQ(clip.features, content.values);
  EXPECT_EQ(clip.contacts, content.contacts);
  EXPECT_EQ(clip.world_positions, canonicalWorldPositions(content.values, content.anchor));
  EXPECT_EQ(clip.fps, 60.0);
}

// The blend is linear in feature space; the bone lengths are then set (enforceBoneLengths), so the
// root velocities (no bones) blend exactly and the joints to within the bones' adjustment.
TEST(Stylizer, StrengthBlendsLinearlyInFeatureSpaceThenSetsBoneLengths) {
  const style::Stylizer stylizer(test::tinyStyleModel());
  const Eigen::MatrixXd& content = test::fixtureClips()[0].features.values;
  const Eigen::MatrixXd full = stylizer.stylizeFeatures(content, {}, 1.0, style::PathMode::Style);
  const Eigen::MatrixXd half = stylizer.stylizeFeatures(content, {}, 0.5, style::PathMode::Style);
  EXPECT_GT((full - content).cwiseAbs().maxCoeff(), 1e-3);  // the network does something
  const auto velocities = [](const Eigen::MatrixXd& f) { return Eigen::MatrixXd(f.middleRows<3>(kSidewaysVelocity)); };
  EXPECT_TRUE(velocities(half).isApprox(0.5 * (velocities(content) + velocities(full)), 1e-9));
  const Eigen::VectorXd reference = Eigen::Map<const Eigen::VectorXd>(referenceProportions().bone_length.data(), kCanonicalJointCount);
  for (const Eigen::MatrixXd* output : {&full, &half})
    EXPECT_LT((canonicalBoneLengths(*output) - reference).cwiseAbs().maxCoeff(), 1e-9);
}

// The projection's depooling leaves the decoded change alternating between even and odd frames; the
// finish takes exactly that frequency out of the change (stylizer.h), so an output that differs from
// another only by an alternation finishes the same inside the clip.
TEST(Stylizer, FinishTakesTheFrameAlternationOutOfTheNetworksChange) {
  const style::Stylizer stylizer(test::tinyStyleModel());
  const Eigen::MatrixXd& content = test::fixtureClips()[0].features.values;
  const Eigen::MatrixXd output = stylizer.networkOutput(content, {}, style::PathMode::Style);
  Eigen::MatrixXd alternating = output;
  for (Eigen::Index t = 0; t < alternating.cols(); ++t) alternating.col(t).array() += t % 2 == 0 ? 1.5 : -1.5;
  const Eigen::MatrixXd smooth = stylizer.finishFeatures(content, {}, output, 1.0, style::PathMode::Style);
  const Eigen::MatrixXd finished = stylizer.finishFeatures(content, {}, alternating, 1.0, style::PathMode::Style);
  const Eigen::Index inside = content.cols() - 2;
  ASSERT_GT(inside, 10);
  EXPECT_LT((finished.middleCols(1, inside) - smooth.middleCols(1, inside)).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT((finished.col(0) - smooth.col(0)).cwiseAbs().maxCoeff(), 0.1);  // the clamped edge keeps half
}

// The two halves (live edits keep the network's output and redo only the blend) are the whole.
TEST(Stylizer, NetworkOutputThenFinishIsStylizeBitForBit) {
  const style::Stylizer stylizer(test::tinyStyleModel());
  const Eigen::MatrixXd& content = test::fixtureClips()[0].features.values;
  const Eigen::MatrixXd& contacts = test::fixtureClips()[0].features.contacts;
  EXPECT_THROW(stylizer.finishFeatures(content, {}, content.leftCols(content.cols() - 1), 0.5), std::invalid_argument);
  EXPECT_THROW(stylizer.finishFeatures(content, {}, content, 1.5), std::invalid_argument);
  EXPECT_THROW(stylizer.finishFeatures(content, contacts.leftCols(contacts.cols() - 1), content, 0.5),
               std::invalid_argument);
  for (const style::PathMode path : {style::PathMode::Content, style::PathMode::Style}) {
    const Eigen::MatrixXd output = stylizer.networkOutput(content, contacts, path);
    for (const double strength : {0.0, 0.3, 1.0})
      EXPECT_EQ(stylizer.finishFeatures(content, contacts, output, strength, path),
                stylizer.stylizeFeatures(content, contacts, strength, path));
  }
}

// Given the content's contacts, the stylizer plants them (contact_projection.h); on a random decoder,
// which cannot plant them, its step along the solution is cut so that the feet slide no more than the
// network's own (a planting decoder: cleanup_stylized_test). Contacts of another length are refused.
TEST(Stylizer, ItsContactProjectionNeverAddsSliding) {
  const style::Stylizer stylizer(test::tinyStyleModel());
  const MotionFeatures& content = test::fixtureClips()[0].features;
  EXPECT_THROW(stylizer.networkOutput(content.values, content.contacts.leftCols(10), style::PathMode::Content),
               std::invalid_argument);
  style::ContactProjection off;
  off.iterations = 0;  // refused all the same when nothing would be planted
  EXPECT_THROW(style::Stylizer(test::tinyStyleModel(), "the test network", {}, off)
                   .networkOutput(content.values, content.contacts.leftCols(10), style::PathMode::Content),
               std::invalid_argument);
  for (const style::PathMode path : {style::PathMode::Content, style::PathMode::Style}) {
    const double sliding = style::footSkate(stylizer.stylizeFeatures(content.values, {}, 1.0, path), content.contacts,
                                            content.anchor);
    const double planted = style::footSkate(stylizer.stylizeFeatures(content.values, content.contacts, 1.0, path),
                                            content.contacts, content.anchor);
    EXPECT_LE(planted, sliding) << style::pathModeName(path);
  }
}

// Concurrent callers (a batch's workers, the app's job and its familiarity reading) each run on a
// prepared network of their own: the results are the serial ones, bit for bit.
TEST(Stylizer, ConcurrentCallsGiveTheSerialResults) {
  const style::Stylizer stylizer(test::tinyStyleModel());
  std::vector<Eigen::MatrixXd> clips, serial;
  for (const int frames : {180, 301, 64, 500}) {
    clips.push_back(longFeatures(frames));
    serial.push_back(stylizer.networkOutput(clips.back(), {}, style::PathMode::Content));
  }
  std::atomic<int> mismatches{0};
  const auto worker = [&](int offset) {
    for (int round = 0; round < 10; ++round)
      for (size_t i = 0; i < clips.size(); ++i) {
        const size_t k = (i + static_cast<size_t>(offset)) % clips.size();
        if (stylizer.networkOutput(clips[k], {}, style::PathMode::Content) != serial[k]) ++mismatches;
        if (stylizer.projectFeatures(clips[k]).cols() != clips[k].cols()) ++mismatches;
      }
  };
  std::thread a(worker, 0), b(worker, 1), c(worker, 2);
  a.join();
  b.join();
  c.join();
  EXPECT_EQ(mismatches.load(), 0);
}

TEST(Stylizer, OutputHasTheInputLengthForOddAndLongClips) {
  const style::Stylizer stylizer(test::tinyStyleModel());
  for (int frames : {1, 2, 25, 301, 1000}) {
    const Eigen::MatrixXd content = longFeatures(frames);
    const Eigen::MatrixXd out = stylizer.stylizeFeatures(content, {}, 1.0);
    EXPECT_EQ(out.cols(), frames);
    EXPECT_EQ(out.rows(), kFeatureCount);
    EXPECT_TRUE(out.allFinite());
  }
}

// Fully convolutional: stylizing a long clip or its two halves differs only within the receptive field
// of the cut. With the full-size networks (width 25) the field is T's 3 x 12 frames plus the
// loss network's ~3 x 12 (encode, pool, decode): 120 frames of margin is ample.
TEST(Stylizer, NoSeamsAwayFromACut) {
  nn::StyleModel model{nn::TransformationNetwork<float>(), nn::LossNetwork<float>(), test::tinyLossNetworkModel().normalisation, {}, {}};
  model.transformation.initialise(21);
  model.loss_network.initialise(22);
  model.metadata.representation = style::currentRepresentation();
  const style::Stylizer stylizer(model);
  const Eigen::MatrixXd content = longFeatures(1000);
  const Eigen::MatrixXd whole = stylizer.stylizeFeatures(content, {}, 1.0);
  const Eigen::MatrixXd first = stylizer.stylizeFeatures(content.leftCols(500), {}, 1.0);
  const Eigen::MatrixXd second = stylizer.stylizeFeatures(content.rightCols(500), {}, 1.0);
  const double scale = whole.cwiseAbs().maxCoeff();
  EXPECT_LT((whole.leftCols(380) - first.leftCols(380)).cwiseAbs().maxCoeff(), 1e-4 * scale);
  EXPECT_LT((whole.rightCols(380) - second.rightCols(380)).cwiseAbs().maxCoeff(), 1e-4 * scale);
  // ... and near the cut the halves do differ (the test can fail).
  EXPECT_GT((whole.middleCols(495, 5) - first.rightCols(5)).cwiseAbs().maxCoeff(), 1e-4 * scale);
}

TEST(Stylizer, ItsPreparedProjectionIsTheLossNetworksAndReadsTheSameFamiliarity) {
  const nn::StyleModel model = test::tinyStyleModel();
  const style::Stylizer stylizer(model);
  EXPECT_THROW(stylizer.projectFeatures(Eigen::MatrixXd::Zero(65, 10)), std::invalid_argument);
  for (const style::MotionClip& clip : test::fixtureClips()) {
    const Eigen::MatrixXd fresh = style::projectFeatures({model.loss_network, model.normalisation, {}}, clip.features.values);
    const Eigen::MatrixXd prepared = stylizer.projectFeatures(clip.features.values);
    ASSERT_EQ(prepared.cols(), clip.features.values.cols());
    EXPECT_LE((prepared - fresh).cwiseAbs().maxCoeff(), 1e-9);
    // Twice through the same prepared kernels: the same answer (nothing left over from a call).
    EXPECT_EQ(stylizer.projectFeatures(clip.features.values), prepared);
    EXPECT_NEAR(style::measureFamiliarity(stylizer, clip.features.values).mean_cm,
                style::measureFamiliarity(model, clip.features.values).mean_cm, 1e-9);
  }
}

TEST(OptimizationTransfer, ReducesTheStyleDistanceAndKeepsTheLength) {
  const nn::LossNetworkModel loss_network = test::tinyLossNetworkModel();
  const auto& content = test::fixtureClips()[0];
  const auto& style_clip = test::fixtureClips()[1];
  style::OptimizationOptions options;
  options.iterations = 100;
  options.constraint_iterations = 20;
  options.style_weight = 1.0;
  int calls = 0;
  style::OptimizationCallbacks callbacks;
  callbacks.progress = [&](const style::OptimizationProgress&) { ++calls; };
  const style::OptimizationResult result =
      style::optimizeStyleTransfer(loss_network, content.features, style_clip.features, "zombie.bvh", options, callbacks);
  ASSERT_FALSE(result.cancelled);
  EXPECT_EQ(calls, 120);
  ASSERT_EQ(result.clip.frameCount(), content.frameCount());
  EXPECT_EQ(result.clip.world_positions.rows(), content.frameCount());

  const auto gramDistance = [&](const Eigen::MatrixXd& features) {
    const auto normalise = [&](const Eigen::MatrixXd& x) {
      return nn::Mat<float>(((x.colwise() - loss_network.normalisation.mean).array().colwise() / loss_network.normalisation.std.array())
                                .matrix()
                                .cast<float>());
    };
    const nn::Mat<float> h = loss_network.network.encode(normalise(features), static_cast<int>(features.cols()));
    const nn::Mat<float> target = nn::styleGram(loss_network.network, normalise(style_clip.features.values));
    return static_cast<double>(nn::styleLoss<float>(h, static_cast<int>(h.cols()), {target}, 0.0f, nullptr));
  };
  EXPECT_LT(gramDistance(result.clip.features), gramDistance(content.features.values));
}

TEST(OptimizationTransfer, ZeroIterationsGiveTheProjectionAndCancellationStops) {
  const nn::LossNetworkModel loss_network = test::tinyLossNetworkModel();
  const auto& content = test::fixtureClips()[0].features;
  style::OptimizationOptions none;
  none.iterations = 0;
  none.constraint_iterations = 0;
  none.path = style::PathMode::Style;
  const auto projected = style::optimizeStyleTransfer(loss_network, content, test::fixtureClips()[1].features, "z", none);
  // The projection (its root velocities: the joints then get their bone lengths), away from the clip's
  // edges, where the projection pads and the optimisation's bare convolution does not.
  const Eigen::MatrixXd reference = style::projectFeatures(loss_network, content.values);
  const Eigen::Index inner = content.values.cols() - 2 * 80;
  ASSERT_GT(inner, 100);
  EXPECT_TRUE(projected.clip.features.block(kSidewaysVelocity, 80, 3, inner)
                  .isApprox(reference.block(kSidewaysVelocity, 80, 3, inner), 1e-4));
  none.path = style::PathMode::Content;  // the default: the projection's poses on the content's path
  const auto on_path = style::optimizeStyleTransfer(loss_network, content, test::fixtureClips()[1].features, "z", none);
  EXPECT_EQ(on_path.clip.features.middleRows<3>(kSidewaysVelocity), content.values.middleRows<3>(kSidewaysVelocity));
  EXPECT_TRUE(on_path.clip.features.topRows(63).isApprox(projected.clip.features.topRows(63), 1e-6));

  std::atomic<bool> cancel{false};
  style::OptimizationCallbacks callbacks;
  callbacks.cancel = &cancel;
  int calls = 0;
  callbacks.progress = [&](const style::OptimizationProgress&) {
    if (++calls == 5) cancel = true;
  };
  const auto cancelled =
      style::optimizeStyleTransfer(loss_network, content, test::fixtureClips()[1].features, "z", {}, callbacks);
  EXPECT_TRUE(cancelled.cancelled);
  EXPECT_EQ(calls, 5);
  EXPECT_EQ(cancelled.clip.frameCount(), 0);
}

TEST(Evaluation, FootSkateAndBoneErrorMeasureKnownMotion) {
  // Every joint at the root, the root moving forward 1 cm per frame at 60 fps, feet always in contact:
  // each foot slides at 60 cm/s; every bone has length 0 against target 1 cm.
  Eigen::MatrixXd features = Eigen::MatrixXd::Zero(kFeatureCount, 30);
  features.row(kForwardVelocity).setOnes();
  FeatureAnchor anchor;
  anchor.fps = 60.0;
  EXPECT_NEAR(style::footSkate(features, Eigen::MatrixXd::Ones(kContactCount, 30), anchor), 60.0, 1e-9);
  EXPECT_EQ(style::footSkate(features, Eigen::MatrixXd::Zero(kContactCount, 30), anchor), 0.0);
  EXPECT_NEAR(style::boneLengthError(features, Eigen::VectorXd::Ones(nn::kBoneCount)), 1.0, 1e-12);
}

TEST(Evaluation, ReportHasEveryFigure) {
  const nn::StyleModel network = test::tinyStyleModel();
  const nn::LossNetworkModel loss_network{network.loss_network, network.normalisation, network.metadata};
  const auto& clips = test::fixtureClips();
  const style::EvaluationReport report = style::evaluateStyleNetwork(loss_network, network, {clips[0]}, {clips[1]}, {0});
  ASSERT_EQ(report.clips.size(), 1u);
  EXPECT_TRUE(report.loss_network_matches_network);
  const style::ClipEvaluation& e = report.clips[0];
  EXPECT_EQ(e.frames, clips[0].frameCount());
  EXPECT_GT(e.reconstruction_mse, 0.0);
  EXPECT_GT(e.reconstruction_joint_error_cm, 0.0);
  EXPECT_GT(e.style_distance_before, 0.0);
  EXPECT_GT(e.content_distance_after, 0.0);
  EXPECT_LT(e.bone_error_cm_content, 1.0);  // the content's bones barely vary
  EXPECT_GT(e.stylize_seconds, 0.0);
  const auto json = nlohmann::json::parse(style::evaluationJson(report));
  EXPECT_EQ(json["format"], "motionstyle-evaluation");
  for (const char* key : {"reconstruction", "content_distance", "style_distance", "bone_error_cm", "foot_skate_cm_s"}) {
    EXPECT_TRUE(json["summary"].contains(key)) << key;
    EXPECT_TRUE(json["clips"][0].contains(key)) << key;
  }
  EXPECT_NEAR(json["summary"]["style_distance"]["before"].get<double>(), e.style_distance_before, 1e-12);
  // The projection alone (L(C)): a figure of its own, between the content's and, usually, the output's,
  // and not the output's (the style network did something beyond the projection).
  EXPECT_GT(e.style_distance_projection, 0.0);
  EXPECT_NE(e.style_distance_projection, e.style_distance_after);
  EXPECT_NE(e.style_distance_projection, e.style_distance_before);
  EXPECT_NEAR(json["clips"][0]["style_distance"]["projection_only"].get<double>(), e.style_distance_projection, 1e-12);
  EXPECT_NEAR(json["summary"]["style_distance"]["projection_ratio"].get<double>(),
              e.style_distance_projection / e.style_distance_before, 1e-9);
  // Backward compatible: the earlier keys are all still there.
  for (const char* key : {"before", "after", "ratio"}) EXPECT_TRUE(json["summary"]["style_distance"].contains(key)) << key;
}

// The distances are read from what the user gets: Stylizer::stylize, whose stances are held in the
// clip's own rig too, not the reference rig's stylizeFeatures (the two differ on this clip).
TEST(Evaluation, MeasuresTheClipTheUserGets) {
  const nn::StyleModel network = test::tinyStyleModel();
  const nn::LossNetworkModel loss_network{network.loss_network, network.normalisation, network.metadata};
  const auto& clips = test::fixtureClips();
  const MotionFeatures& content = clips[0].features;
  const style::Stylizer stylizer(network);
  const Eigen::MatrixXd user = stylizer.stylize(content, 1.0).features;
  const Eigen::MatrixXd reference_rig = stylizer.stylizeFeatures(content.values, content.contacts, 1.0);
  ASSERT_GT((user - reference_rig).cwiseAbs().maxCoeff(), 1e-3) << "the clip must tell the two apart";
  const nn::Mat<float> gram = style::styleGramOf(network.loss_network, network.normalisation, clips[1].features.values);
  const style::StyleDistances expected =
      style::measureStyleDistances(network.loss_network, network.normalisation, content.values, user, gram);
  const style::ClipEvaluation e = style::evaluateStyleNetwork(loss_network, network, {clips[0]}, {clips[1]}, {0}).clips.at(0);
  EXPECT_DOUBLE_EQ(e.content_distance_after, expected.content_after);
  EXPECT_DOUBLE_EQ(e.style_distance_after, expected.style_after);
}

// Stylizers of networks trained against one loss network share its prepared projection while any
// of them holds it; another loss network gets its own, and once every holder is gone it is released.
// A Stylizer that dropped its idle copies gives the same output.
TEST(SharedProjection, IsOnePerLossNetworkWhileHeld) {
  const nn::StyleModel model = test::tinyStyleModel();
  std::shared_ptr<const nn::FastStylizer> first = style::sharedProjection(model.loss_network);
  EXPECT_EQ(style::sharedProjection(model.loss_network), first);
  nn::LossNetwork<float> other = model.loss_network;
  other.decoder.weight.value(0, 0) += 0.5f;
  EXPECT_NE(style::sharedProjection(other), first);
  const std::weak_ptr<const nn::FastStylizer> released = first;
  first.reset();
  EXPECT_TRUE(released.expired());
  // Two Stylizers of the same network: the same output as ever (the projection is shared, not changed).
  const style::Stylizer a(model, "a"), b(model, "b");
  const Eigen::MatrixXd& content = test::fixtureClips()[0].features.values;
  const Eigen::MatrixXd output = a.networkOutput(content, {}, style::PathMode::Content);
  EXPECT_EQ(output, b.networkOutput(content, {}, style::PathMode::Content));
  a.releaseIdleNetworks();  // its prepared copies dropped: the next call makes one, the same output
  EXPECT_EQ(a.networkOutput(content, {}, style::PathMode::Content), output);
}

}  // namespace
}  // namespace motionstyle
