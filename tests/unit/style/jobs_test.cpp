// The core jobs the CLI and the app share (style/*_job.h): invalid inputs first (validate() refuses
// them before any work), then their properties: the Result belongs to the inputs, a set cancel flag
// stops the job, a cancelled training keeps the network of its last completed epoch.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <stdexcept>

#include "common/errors.h"
#include "mapping/joint_mapping.h"
#include "motion/kinematics.h"
#include "style/evaluation_job.h"
#include "style/loss_network_training_job.h"
#include "style/optimization_transfer_job.h"
#include "style/style_training_job.h"
#include "style/stylize_cleanup_job.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

using test::TempDir;

style::StylizeCleanupJob cleanupJobOnFixture(int frames) {
  style::StylizeCleanupJob job;
  job.content = readBvh(test::fixture("cmu_131_01.bvh"));
  job.content.values.conservativeResize(frames, Eigen::NoChange);
  job.mapping = mapJoints(job.content.skeleton, "cmu_131_01.bvh");
  job.stylizer = std::make_shared<const style::Stylizer>(test::tinyStyleModel());
  return job;
}

TEST(StylizeCleanupJob, RefusesMissingOrInconsistentInputs) {
  style::StylizeCleanupJob job = cleanupJobOnFixture(90);
  job.stylizer.reset();
  EXPECT_THROW(job.validate(), std::invalid_argument);  // neither a network nor a stylized clip
  job = cleanupJobOnFixture(90);
  job.strength = 1.5;
  EXPECT_THROW(job.run(), std::invalid_argument);
  job.strength = 1.0;
  job.contact_overrides = Eigen::MatrixXi::Constant(10, 4, -1);  // not the content's frame count
  EXPECT_THROW(job.validate(), std::invalid_argument);
  job.contact_overrides = Eigen::MatrixXi::Constant(90, 4, -1);
  EXPECT_NO_THROW(job.validate());
  job.output_fps = -30.0;
  EXPECT_THROW(job.validate(), std::invalid_argument);
}

TEST(StylizeCleanupJob, AnOutputRateResamplesTheCleanedClip) {
  style::StylizeCleanupJob job = cleanupJobOnFixture(120);  // one second at 120 fps
  job.output_fps = 30.0;
  const style::StylizeCleanupResult result = job.run();
  EXPECT_DOUBLE_EQ(result.cleaned.fps(), 30.0);
  EXPECT_NEAR(result.cleaned.frameCount(), 30, 1);
  EXPECT_EQ(result.cleaned.skeleton.channelCount(), job.content.skeleton.channelCount());
}

TEST(StylizeCleanupJob, TheCleanedClipIsTheContentsRigAndLength) {
  const style::StylizeCleanupJob job = cleanupJobOnFixture(90);
  const style::StylizeCleanupResult result = job.run();
  EXPECT_EQ(result.cleaned.frameCount(), job.content.frameCount());
  EXPECT_EQ(result.cleaned.skeleton.channelCount(), job.content.skeleton.channelCount());
  EXPECT_TRUE(result.cleaned.values.allFinite());
  EXPECT_EQ(result.cleaned_world_positions.size(), 0);  // not asked for (the CLI)
  EXPECT_GT(result.stylized.frameCount(), 0);
  EXPECT_EQ(result.contacts.cols(), 4);
  EXPECT_GE(result.seconds, 0.0);
}

TEST(StylizeCleanupJob, ItGivesTheCleanedClipsWorldPositionsWhenAsked) {
  style::StylizeCleanupJob job = cleanupJobOnFixture(90);
  job.world_positions = true;  // as the app asks: its viewer draws them
  const style::StylizeCleanupResult result = job.run();
  EXPECT_TRUE(result.cleaned_world_positions.isApprox(worldPositions(result.cleaned), 1e-12));
}

TEST(StylizeCleanupJob, ASetCancelFlagStopsIt) {
  const style::StylizeCleanupJob job = cleanupJobOnFixture(90);
  const std::atomic<bool> cancel{true};
  EXPECT_THROW(job.run(&cancel), OperationCancelled);
}

// The memory of a live edit: a strength step reuses the network's output, another network does not,
// and the stylized clip is the memory-less job's bit for bit.
TEST(StylizeCleanupJob, ItsMemoryReusesTheNetworkOutputOnlyForTheSameNetworkAndClip) {
  style::StylizeCleanupJob job = cleanupJobOnFixture(90);
  job.memory = std::make_shared<style::StylizeCleanupMemory>();
  job.run();
  ASSERT_EQ(job.memory->stylizer, job.stylizer);
  const Eigen::MatrixXd kept = job.memory->network_output;
  job.strength = 0.4;
  style::StylizeCleanupJob fresh = job;
  fresh.memory = nullptr;
  EXPECT_EQ(job.run().stylized.features, fresh.run().stylized.features);
  EXPECT_EQ(job.memory->network_output, kept);

  nn::StyleModel other_model = test::tinyStyleModel();
  for (nn::Parameter<float>* p : other_model.transformation.parameters()) p->value *= 1.5f;
  job.stylizer = std::make_shared<const style::Stylizer>(std::move(other_model));
  fresh.stylizer = job.stylizer;
  EXPECT_EQ(job.run().stylized.features, fresh.run().stylized.features);
  EXPECT_EQ(job.memory->stylizer, job.stylizer);
  EXPECT_NE(job.memory->network_output, kept);

  job.content.values.conservativeResize(80, Eigen::NoChange);  // another clip
  fresh.content = job.content;
  EXPECT_EQ(job.run().stylized.features, fresh.run().stylized.features);
  EXPECT_EQ(job.memory->features.cols(), job.run().stylized.frameCount());
}

// A new memory seeded from another network's (the app's style switch): the job starts from the
// seed's features and clean-up solutions, its stylized clip is the memory-less job's, and the seed
// keeps its own network output.
TEST(StylizeCleanupJob, ASeededMemoryStartsFromAnotherNetworksAndLeavesItAsItWas) {
  style::StylizeCleanupJob first = cleanupJobOnFixture(90);
  first.memory = std::make_shared<style::StylizeCleanupMemory>();
  first.run();
  const Eigen::MatrixXd first_output = first.memory->network_output;

  nn::StyleModel other_model = test::tinyStyleModel();
  for (nn::Parameter<float>* p : other_model.transformation.parameters()) p->value *= 1.5f;
  style::StylizeCleanupJob second = first;
  second.stylizer = std::make_shared<const style::Stylizer>(std::move(other_model));
  second.memory = std::make_shared<style::StylizeCleanupMemory>();
  second.seed = first.memory;
  style::StylizeCleanupJob fresh = second;
  fresh.memory = nullptr;
  fresh.seed = nullptr;
  const style::StylizeCleanupResult seeded = second.run();
  EXPECT_EQ(seeded.stylized.features, fresh.run().stylized.features);
  EXPECT_GT(seeded.report.chunks_warm, 0);  // from the seed's solutions
  EXPECT_FALSE(seeded.network_output_kept);
  EXPECT_EQ(second.memory->stylizer, second.stylizer);
  ASSERT_TRUE(second.memory->content_features.has_value());
  EXPECT_EQ(second.memory->content_features->values, first.memory->content_features->values);
  EXPECT_EQ(first.memory->stylizer, first.stylizer);  // the seed as it was
  EXPECT_EQ(first.memory->network_output, first_output);
  second.strength = 0.5;  // the second network's own output, kept
  EXPECT_TRUE(second.run().network_output_kept);
}

// A memory copied from the same network's (the app's look-ahead after a strength change): the job
// runs only the clean-up, its stylized clip is the memory-less job's, and the original is left as it
// was. A copy of itself changes nothing.
TEST(StylizeCleanupJob, ACopiedMemoryKeepsTheNetworkOutputAndLeavesTheOriginal) {
  style::StylizeCleanupJob first = cleanupJobOnFixture(90);
  first.memory = std::make_shared<style::StylizeCleanupMemory>();
  first.run();
  const Eigen::MatrixXd first_output = first.memory->network_output;
  first.memory->copyFrom(*first.memory);
  EXPECT_EQ(first.memory->network_output, first_output);

  style::StylizeCleanupJob copied = first;
  copied.strength = 0.6;
  copied.memory = std::make_shared<style::StylizeCleanupMemory>();
  copied.memory->copyFrom(*first.memory);
  style::StylizeCleanupJob fresh = copied;
  fresh.memory = nullptr;
  const style::StylizeCleanupResult result = copied.run();
  EXPECT_TRUE(result.network_output_kept);
  EXPECT_GT(result.report.chunks_warm, 0);
  EXPECT_EQ(result.stylized.features, fresh.run().stylized.features);
  EXPECT_EQ(first.memory->network_output, first_output);  // the original as it was
  EXPECT_EQ(first.memory->stylizer, first.stylizer);
}

// The contacts are planted under the path the output follows (contact_projection.h), so a path change
// runs the network again, as the memory-less job does; a strength change after it keeps its output.
TEST(StylizeCleanupJob, APathChangeRunsTheNetworkAgain) {
  style::StylizeCleanupJob job = cleanupJobOnFixture(90);
  job.memory = std::make_shared<style::StylizeCleanupMemory>();
  job.run();
  job.path = style::PathMode::Style;
  style::StylizeCleanupJob fresh = job;
  fresh.memory = nullptr;
  const style::StylizeCleanupResult changed = job.run();
  EXPECT_FALSE(changed.network_output_kept);
  EXPECT_EQ(job.memory->path, style::PathMode::Style);
  EXPECT_EQ(changed.stylized.features, fresh.run().stylized.features);
  job.strength = 0.5;
  EXPECT_TRUE(job.run().network_output_kept);
}

// The content's features are extracted once per clip: a strength step keeps them (the same object),
// and a clip that differs by one value, or the same clip under another mapping, gets its own, so that
// the stylized clip stays the memory-less job's bit for bit.
TEST(StylizeCleanupJob, ItsMemoryKeepsTheContentsFeaturesOnlyForTheSameClipAndMapping) {
  style::StylizeCleanupJob job = cleanupJobOnFixture(90);
  job.memory = std::make_shared<style::StylizeCleanupMemory>();
  job.run();
  ASSERT_TRUE(job.memory->content_features.has_value());
  const double* kept = job.memory->content_features->values.data();
  job.strength = 0.5;
  job.run();
  EXPECT_EQ(job.memory->content_features->values.data(), kept);  // not extracted again

  style::StylizeCleanupJob fresh = job;
  fresh.memory = nullptr;
  job.content.values(45, 7) += 10.0;  // one channel of one frame moved
  fresh.content = job.content;
  EXPECT_EQ(job.run().stylized.features, fresh.run().stylized.features);
  EXPECT_EQ(job.memory->content.values, job.content.values);

  job.mapping.convention = "file:another.map";  // the same joints under another name: re-extracted
  const Eigen::MatrixXd before = job.memory->content_features->values;
  job.run();
  EXPECT_EQ(job.memory->mapping.convention, "file:another.map");
  EXPECT_EQ(job.memory->content_features->values, before);
}

TEST(OptimizationTransferJob, RefusesMissingFilesAndBadOptions) {
  TempDir dir;
  style::OptimizationTransferJob job;
  job.loss_network = test::tinyLossNetworkModel();
  EXPECT_THROW(job.validate(), std::invalid_argument);  // no clips named
  job.content = test::fixture("cmu_131_01.bvh");
  job.style = dir / "missing.bvh";
  EXPECT_THROW(job.run(), InputError);  // names the missing file
  job.style = test::fixture("zombie.bvh");
  job.options.iterations = -1;
  EXPECT_THROW(job.validate(), std::invalid_argument);
}

TEST(OptimizationOptions, OneIterationKnobKeepsTheDefaultsShareForTheConstraints) {
  style::OptimizationOptions options;
  options.setIterations(250);
  EXPECT_EQ(options.constraint_iterations, 100);
  options.setIterations(5);
  EXPECT_EQ(options.iterations, 5);
  EXPECT_EQ(options.constraint_iterations, 2);
  options.setIterations(1);
  EXPECT_EQ(options.constraint_iterations, 1);  // never none
}

TEST(EmbeddedLossNetwork, IsTheStyleNetworksOwn) {
  nn::StyleModel model = test::tinyStyleModel();
  model.metadata.training.sparsity = 0.25;
  const nn::LossNetworkModel loss = nn::embeddedLossNetwork(model);
  EXPECT_TRUE(nn::sameWeights(loss.network, model.loss_network));
  EXPECT_EQ(loss.normalisation.mean, model.normalisation.mean);
  EXPECT_EQ(loss.metadata.representation, model.metadata.representation);
  EXPECT_EQ(loss.metadata.training.sparsity, 0.25);
}

TEST(OptimizationTransferJob, CancelledBeforeItStartsGivesNoClip) {
  style::OptimizationTransferJob job;
  job.loss_network = test::tinyLossNetworkModel();
  job.content = test::fixture("cmu_131_01.bvh");
  job.style = test::fixture("zombie.bvh");
  const std::atomic<bool> cancel{true};
  style::OptimizationCallbacks callbacks;
  callbacks.cancel = &cancel;
  const auto result = job.run(callbacks);
  EXPECT_TRUE(result.cancelled);
  EXPECT_FALSE(result.clip.has_value());
}

style::StyleTrainingJob tinyTrainingJob(const TempDir& dir, int epochs) {
  nn::saveLossNetwork(test::tinyLossNetworkModel(), dir / "ae.net");
  style::StyleTrainingJob job;
  job.config.settings = test::tinySettings({}, epochs);
  job.config.settings.checkpoint = dir / "run.checkpoint";
  job.config.loss_network = dir / "ae.net";
  job.config.content_clips = test::fixtureClips();
  job.config.styles = {{std::nullopt, test::fixture("zombie.bvh")}};
  job.config.shape = test::tinyTransformationShape();
  job.config.weights.style = 1.0;
  job.preview_content = test::fixture("cmu_131_01.bvh");
  job.preview_interval_seconds = 0.0;
  return job;
}

TEST(StyleTrainingJob, RefusesAnInvalidConfig) {
  TempDir dir;
  style::StyleTrainingJob job = tinyTrainingJob(dir, 2);
  job.config.settings.epochs = 0;
  EXPECT_THROW(job.run(), std::invalid_argument);
}

TEST(StyleTrainingJob, PreviewsEachEpochAndACancelledRunKeepsItsLastEpoch) {
  TempDir dir;
  const style::StyleTrainingJob job = tinyTrainingJob(dir, 5);
  int previews = 0;
  const auto preview = [&](std::shared_ptr<const style::StylizedClip> clip, int epoch) {
    ++previews;
    EXPECT_EQ(epoch, previews);
    EXPECT_GT(clip->frameCount(), 0);
  };
  const auto result = job.run(test::cancelAtEndOfEpoch(2), preview);
  EXPECT_EQ(result.status, style::TrainingStatus::Cancelled);
  EXPECT_EQ(result.epochs_completed, 2);
  ASSERT_NE(result.model, nullptr);
  EXPECT_EQ(result.model->metadata.training.epochs, 2);
  EXPECT_EQ(previews, 2);
  EXPECT_TRUE(std::filesystem::exists(result.checkpoint));
  // The kept network is the checkpoint's.
  EXPECT_EQ(test::weightsOf(result.model->transformation), test::weightsOf(nn::loadStyleModel(result.checkpoint).transformation));
}

TEST(LossNetworkTrainingJob, RefusesAnInvalidConfig) {
  TempDir dir;
  style::LossNetworkTrainingJob job{test::tinyLossNetworkConfig(dir / "loss.net", 2)};
  job.config.settings.epochs = 0;
  EXPECT_THROW(job.run(), std::invalid_argument);
  job.config = test::tinyLossNetworkConfig(dir / "loss.net", 2);
  job.config.shape.width = 4;  // filter widths are odd
  EXPECT_THROW(job.validate(), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "loss.net"));
}

TEST(LossNetworkTrainingJob, ItsModelIsTheFileItWrote) {
  TempDir dir;
  const style::LossNetworkTrainingJob job{test::tinyLossNetworkConfig(dir / "loss.net", 2)};
  const auto result = job.run();
  EXPECT_EQ(result.status, style::TrainingStatus::Completed);
  EXPECT_EQ(result.epochs_completed, 2);
  EXPECT_EQ(result.history.size(), 2u);
  ASSERT_NE(result.model, nullptr);
  EXPECT_TRUE(nn::sameWeights(result.model->network, nn::loadLossNetwork(dir / "loss.net").network));
}

TEST(LossNetworkTrainingJob, ACancelledRunKeepsItsCheckpoint) {
  TempDir dir;
  const style::LossNetworkTrainingJob job{test::tinyLossNetworkConfig(dir / "loss.net", 4)};
  const auto result = job.run(test::cancelAtEndOfEpoch(1));
  EXPECT_EQ(result.status, style::TrainingStatus::Cancelled);
  EXPECT_EQ(result.epochs_completed, 1);
  EXPECT_TRUE(std::filesystem::exists(result.checkpoint));
  EXPECT_FALSE(std::filesystem::exists(dir / "loss.net"));
}

style::EvaluationJob evaluationJobOnFixtures() {
  style::EvaluationJob job;
  job.loss_network = test::tinyLossNetworkModel();
  job.network = test::tinyStyleModel();
  job.clips = {test::fixture("cmu_131_01.bvh"), test::fixture("zombie.bvh")};
  job.styles = {{std::nullopt, test::fixture("zombie.bvh")}};
  return job;
}

TEST(EvaluationJob, RefusesNoClipsOrNoStyleClip) {
  style::EvaluationJob job = evaluationJobOnFixtures();
  job.clips.clear();
  EXPECT_THROW(job.run(), std::invalid_argument);
  job = evaluationJobOnFixtures();
  job.styles.clear();
  EXPECT_THROW(job.validate(), std::invalid_argument);
  job = evaluationJobOnFixtures();
  job.clips.push_back("/nonexistent/clip.bvh");
  EXPECT_THROW(job.run(), InputError);
}

TEST(EvaluationJob, ReportsEveryClipAgainstItsStyleClip) {
  const style::EvaluationJob job = evaluationJobOnFixtures();
  const style::EvaluationReport report = job.run();
  ASSERT_EQ(report.clips.size(), 2u);
  int frames = 0;
  for (const style::ClipEvaluation& clip : report.clips) {
    EXPECT_NE(clip.style_clip.find("zombie.bvh"), std::string::npos);
    EXPECT_GT(clip.frames, 0);
    EXPECT_TRUE(std::isfinite(clip.style_distance_after) && std::isfinite(clip.content_distance_after));
    frames += clip.frames;
  }
  EXPECT_EQ(report.mean.frames, frames);
  EXPECT_GT(report.stylize_frames_per_second, 0.0);
}

TEST(EvaluationJob, ASetCancelFlagStopsIt) {
  const style::EvaluationJob job = evaluationJobOnFixtures();
  const std::atomic<bool> cancel{true};
  EXPECT_THROW(job.run(&cancel), OperationCancelled);
}

}  // namespace
}  // namespace motionstyle
