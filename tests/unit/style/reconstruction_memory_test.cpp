// The reconstruction memory (style/reconstruction_memory.h): invalid input and damaged files first, then
// its properties: it is the decoder's reconstruction error over the clips it remembers, its gradient
// is that error's, it survives its file, and an adaptation that keeps it forgets less.
#include <gtest/gtest.h>

#include <random>

#include "common/errors.h"
#include "style/adaptation.h"
#include "style/reconstruction_memory.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

using test::TempDir;

// The loss network's own reconstruction error of `clip` (mean over features and frames, normalised).
double reconstructionError(const nn::LossNetworkModel& model, const style::MotionClip& clip) {
  const nn::Mat<float> x = model.normalisation.normalized(clip.features.values);
  const nn::Mat<float> reconstructed = model.network.project(x, static_cast<int>(x.cols()));
  return static_cast<double>((reconstructed - x).squaredNorm()) / static_cast<double>(x.size());
}

// The zombie with a sawtooth on every feature (a slow rise, a sudden fall every 23 frames): motion whose
// hidden units are not the same played backwards, so that S's blocks above its diagonal (C(m)^T) and
// below it (C(m)) differ.
const style::MotionClip& sawtoothZombie() {
  static const style::MotionClip clip = [] {
    style::MotionClip c = test::fixtureClips()[1];
    for (Eigen::Index t = 0; t < c.features.values.cols(); ++t)
      c.features.values.col(t).array() += 30.0 * static_cast<double>(t % 23) / 23.0;
    return c;
  }();
  return clip;
}

style::ReconstructionMemory zombieMemory(const nn::LossNetworkModel& model) {
  return style::rememberReconstruction(model, {sawtoothZombie()}, "the zombie");
}

TEST(ReconstructionMemoryTest, RejectsNoClipsBadClipsAndOtherShapes) {
  const nn::LossNetworkModel model = test::tinyLossNetworkModel();
  EXPECT_THROW(style::rememberReconstruction(model, {}, "nothing"), std::invalid_argument);
  style::MotionClip bad = test::fixtureClips()[1];
  bad.features.values(3, 7) = NAN;
  EXPECT_THROW(style::rememberReconstruction(model, {bad}, "bad"), InputError);
  const style::ReconstructionMemory memory = zombieMemory(model);
  EXPECT_NO_THROW(memory.validate());
  EXPECT_THROW(style::memoryError(memory, Eigen::MatrixXf::Zero(66, 3)), std::invalid_argument);
  style::ReconstructionMemory broken = memory;
  broken.lags.pop_back();
  EXPECT_THROW(broken.validate(), std::invalid_argument);
  broken = memory;
  broken.cross(0, 0) = INFINITY;
  EXPECT_THROW(broken.validate(), std::invalid_argument);
  broken = memory;
  broken.frames = 0;
  EXPECT_THROW(broken.validate(), std::invalid_argument);
  // Another encoder: the memory's hidden units are not this network's.
  EXPECT_NO_THROW(memory.requireMatches(model, "memory"));
  EXPECT_THROW(memory.requireMatches(test::tinyLossNetworkModel(4), "memory"), std::invalid_argument);
  // A changed decoder (an adapted network) still fits.
  nn::LossNetworkModel adapted = model;
  adapted.network.decoder.weight.value *= 0.5f;
  EXPECT_NO_THROW(memory.requireMatches(adapted, "memory"));
}

TEST(ReconstructionMemoryTest, DamagedFilesAreErrorsNamingTheFile) {
  TempDir dir;
  const auto expectInputError = [](const std::filesystem::path& file) {
    try {
      style::loadReconstructionMemory(file);
      ADD_FAILURE() << "no error for " << file;
    } catch (const InputError& error) {
      EXPECT_EQ(error.file(), file.string());
    }
  };
  expectInputError(dir / "missing.memory");
  expectInputError(dir.path());  // a folder: refused before any byte is read, as a device would be
  test::writeText(dir / "text.memory", "HIERARCHY\nROOT Hips\n");
  expectInputError(dir / "text.memory");
  const style::ReconstructionMemory memory = zombieMemory(test::tinyLossNetworkModel());
  style::saveReconstructionMemory(memory, dir / "good.memory");
  const std::string bytes = test::readBytes(dir / "good.memory");
  test::writeText(dir / "cut.memory", bytes.substr(0, bytes.size() / 2));
  expectInputError(dir / "cut.memory");
  std::string flipped = bytes;
  flipped[flipped.size() / 2] = static_cast<char>(flipped[flipped.size() / 2] ^ 0x10);
  test::writeText(dir / "flipped.memory", flipped);
  expectInputError(dir / "flipped.memory");
  // Hostile bytes anywhere, and every length cut: an InputError each time, never a crash or a hang.
  std::mt19937 rng(5);
  std::uniform_int_distribution<std::size_t> at(0, bytes.size() - 1);
  for (int trial = 0; trial < 60; ++trial) {
    std::string damaged = bytes;
    const std::size_t where = trial < 40 ? at(rng) : static_cast<std::size_t>(trial - 40);  // the header too
    damaged[where] = static_cast<char>(rng() & 0xff);
    if (damaged == bytes) continue;
    test::writeText(dir / "damaged.memory", trial % 3 == 0 ? damaged.substr(0, at(rng)) : damaged);
    expectInputError(dir / "damaged.memory");
  }
}

TEST(ReconstructionMemoryTest, IsTheDecodersReconstructionErrorOfItsClips) {
  const nn::LossNetworkModel model = test::tinyLossNetworkModel();
  const style::ReconstructionMemory memory = zombieMemory(model);
  EXPECT_EQ(memory.clips, 1);
  EXPECT_GE(memory.frames, static_cast<double>(sawtoothZombie().frameCount()));
  // Only the pairs a clip's edges cut differ (width 5 on 1,500 frames): well within 1 %.
  const double direct = reconstructionError(model, sawtoothZombie());
  EXPECT_NEAR(style::memoryError(memory, model.network.decoder.weight.value), direct, 0.01 * direct);
  // And for another decoder: the quadratic holds for any W, not only the one it was made with.
  nn::LossNetworkModel other = model;
  other.network.decoder.weight.value *= -0.3f;
  const double other_direct = reconstructionError(other, sawtoothZombie());
  EXPECT_NEAR(style::memoryError(memory, other.network.decoder.weight.value), other_direct, 0.01 * other_direct);
}

TEST(ReconstructionMemoryTest, ItsGradientIsItsErrors) {
  const nn::LossNetworkModel model = test::tinyLossNetworkModel();
  const style::ReconstructionMemory memory = zombieMemory(model);
  const Eigen::MatrixXf weight = model.network.decoder.weight.value;
  Eigen::MatrixXf gradient;
  style::memoryError(memory, weight, &gradient);
  ASSERT_EQ(gradient.rows(), weight.rows());
  ASSERT_EQ(gradient.cols(), weight.cols());
  std::mt19937 rng(11);
  std::uniform_int_distribution<Eigen::Index> row(0, weight.rows() - 1), col(0, weight.cols() - 1);
  for (int probe = 0; probe < 12; ++probe) {
    const Eigen::Index r = row(rng), c = col(rng);
    const float h = 1e-2f;
    const double step = h;
    Eigen::MatrixXf plus = weight, minus = weight;
    plus(r, c) += h;
    minus(r, c) -= h;
    // A quadratic: the central difference is exact but for rounding.
    const double numeric = (style::memoryError(memory, plus) - style::memoryError(memory, minus)) / (2.0 * step);
    EXPECT_NEAR(gradient(r, c), numeric, 1e-3 * std::max(1.0, std::abs(numeric))) << "weight " << r << ", " << c;
  }
}

TEST(ReconstructionMemoryTest, SurvivesItsFileInEitherPrecision) {
  TempDir dir;
  const nn::LossNetworkModel model = test::tinyLossNetworkModel();
  // The plain zombie: the sawtooth's moments are beyond f16's range, which saving refuses (below).
  const style::ReconstructionMemory memory = style::rememberReconstruction(model, {test::fixtureClips()[1]}, "the zombie");
  EXPECT_THROW(style::saveReconstructionMemory(zombieMemory(model), dir / "big.memory", nn::WeightPrecision::F16),
               std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "big.memory"));
  style::saveReconstructionMemory(memory, dir / "f32.memory");
  style::saveReconstructionMemory(memory, dir / "f16.memory", nn::WeightPrecision::F16);
  const style::ReconstructionMemory exact = style::loadReconstructionMemory(dir / "f32.memory");
  const style::ReconstructionMemory half = style::loadReconstructionMemory(dir / "f16.memory");
  EXPECT_EQ(exact.description, "the zombie");
  EXPECT_EQ(exact.encoder_fingerprint, memory.encoder_fingerprint);
  EXPECT_NO_THROW(half.requireMatches(model, "f16.memory"));
  const Eigen::MatrixXf& weight = model.network.decoder.weight.value;
  const double error = style::memoryError(memory, weight);
  EXPECT_NEAR(style::memoryError(exact, weight), error, 1e-5 * error);
  EXPECT_NEAR(style::memoryError(half, weight), error, 2e-2 * error);
  EXPECT_LT(std::filesystem::file_size(dir / "f16.memory"), std::filesystem::file_size(dir / "f32.memory"));
}

TEST(ReconstructionMemoryTest, AnAdaptationThatKeepsItForgetsLess) {
  TempDir dir;
  // A network that knows the CMU clip (trained on it), then adapted to the zombie.
  style::LossNetworkTrainingConfig config = test::tinyLossNetworkConfig(dir / "cmu.net", 30);
  config.clips = {test::fixtureClips()[0]};
  const nn::LossNetworkModel knows_cmu = style::trainLossNetwork(config).model;
  const style::MotionClip& cmu = test::fixtureClips()[0];
  const style::MotionClip& zombie = test::fixtureClips()[1];
  const auto adapt = [&](bool with_memory) {
    style::AdaptationJob job;
    job.loss_network = knows_cmu;
    job.clips = {zombie};
    job.settings.epochs = 30;
    job.settings.learning_rate = 3e-3;
    job.settings.output = dir / (with_memory ? "with.net" : "without.net");
    if (with_memory) job.memory = style::rememberReconstruction(knows_cmu, {cmu}, "the CMU clip");
    return job.run();
  };
  const style::AdaptationResult without = adapt(false), with = adapt(true);
  ASSERT_EQ(with.status, style::TrainingStatus::Completed);
  const double before = reconstructionError(knows_cmu, cmu);
  const double forgot_without = reconstructionError(without.model, cmu) - before;
  const double forgot_with = reconstructionError(with.model, cmu) - before;
  EXPECT_GT(forgot_without, 0.0);
  EXPECT_LT(forgot_with, 0.5 * forgot_without) << "without " << forgot_without << ", with " << forgot_with;
  EXPECT_LT(with.mean_after_cm, with.mean_before_cm);  // the zombie is still learnt
  EXPECT_EQ(with.memory, "the CMU clip");
  bool recorded = false;
  for (const auto& [key, value] : with.model.metadata.properties)
    recorded |= key == "adapted_memory" && value.find("the CMU clip") != std::string::npos;
  EXPECT_TRUE(recorded);
  // The adapted network's own memory, written beside it: the CMU clip's kept ten times over the
  // zombie's, the objective the adaptation minimised, term by term.
  ASSERT_TRUE(with.memory_after.has_value());
  EXPECT_EQ(with.memory_file, dir / "with.memory");
  const style::ReconstructionMemory written = style::loadReconstructionMemory(dir / "with.memory");
  EXPECT_NO_THROW(written.requireMatches(with.model, "with.memory"));
  EXPECT_NE(written.description.find("the CMU clip; the 1 clip(s) it was adapted on"), std::string::npos) << written.description;
  EXPECT_EQ(written.clips, 2);
  const Eigen::MatrixXf& adapted = with.model.network.decoder.weight.value;
  const double objective = (reconstructionError(with.model, zombie) + 10.0 * reconstructionError(with.model, cmu)) / 11.0;
  EXPECT_NEAR(style::memoryError(written, adapted), objective, 0.02 * objective);
  // Found beside the adapted network when it is adapted again.
  const std::optional<style::ReconstructionMemory> found = style::findMatchingMemory(with.model, dir / "with.net");
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->description, written.description);
  // Without a memory kept, the memory written is the clips' alone.
  ASSERT_TRUE(without.memory_after.has_value());
  EXPECT_EQ(without.memory_after->clips, 1);
  // Memories of two encoders do not merge; nor with a weight of zero.
  const style::ReconstructionMemory other = style::rememberReconstruction(test::tinyLossNetworkModel(9), {cmu}, "other");
  EXPECT_THROW(style::mergeMemories(written, 1.0, other, 1.0, "both"), std::invalid_argument);
  EXPECT_THROW(style::mergeMemories(written, 0.0, written, 1.0, "both"), std::invalid_argument);
  // A memory of another encoder is refused before any work.
  style::AdaptationJob mismatched;
  mismatched.loss_network = knows_cmu;
  mismatched.clips = {zombie};
  mismatched.settings.output = dir / "mismatched.net";
  mismatched.memory = style::rememberReconstruction(test::tinyLossNetworkModel(9), {cmu}, "another network's");
  EXPECT_THROW(mismatched.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace motionstyle
