// Invalid inputs of core/style: data, network files, checkpoints, pairing and parameters. Each must give
// a clear error naming the culprit, and none may destroy an earlier good network file.
#include <gtest/gtest.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/resource.h>
#include <unistd.h>

#include <optional>

#include "common/errors.h"
#include "style/optimization_transfer.h"
#include "style/style_pairing.h"
#include "style/stylizer.h"
#include "style/training_state.h"
#include "style_test_support.h"

namespace motionstyle {
namespace {

using test::TempDir;

std::string messageOf(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& error) {
    return error.what();
  }
  return "<no exception>";
}

// ---- training data ------------------------------------------------------------------------------

TEST(StyleInvalid, EmptyFolderIsAnInputErrorNamingTheFolder) {
  TempDir dir;
  std::filesystem::create_directories(dir / "empty/sub");
  test::writeText(dir / "empty/readme.txt", "not a clip");
  EXPECT_THROW(style::findBvhFiles({dir / "empty"}), InputError);
  EXPECT_NE(messageOf([&] { style::findBvhFiles({dir / "empty"}); }).find("empty"), std::string::npos);
  EXPECT_NE(messageOf([&] { style::findBvhFiles({dir / "empty"}); }).find("no .bvh"), std::string::npos);

  style::LossNetworkTrainingConfig config;
  config.settings = test::tinySettings(dir / "ae.net", 1);
  config.data = {dir / "empty"};
  EXPECT_THROW(style::trainLossNetwork(config), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "ae.net"));
}

TEST(StyleInvalid, MissingPathIsAnInputError) {
  TempDir dir;
  EXPECT_THROW(style::findBvhFiles({dir / "nothing-here"}), InputError);
}

const char* kUnmappableBvh =
    "HIERARCHY\nROOT Blob\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
    "  JOINT Tentacle\n  {\n    OFFSET 0 10 0\n    CHANNELS 3 Zrotation Xrotation Yrotation\n"
    "    End Site\n    {\n      OFFSET 0 10 0\n    }\n  }\n}\nMOTION\nFrames: 2\nFrame Time: 0.0333333\n"
    "0 0 0 0 0 0 0 0 0\n0 0 0 0 0 0 0 0 0\n";

TEST(StyleInvalid, UnmappableContentNamesTheFile) {
  TempDir dir;
  test::writeText(dir / "content/walk_blob.bvh", kUnmappableBvh);
  const std::string message = messageOf([&] { style::loadMotionClip(dir / "content/walk_blob.bvh"); });
  EXPECT_NE(message.find("walk_blob.bvh"), std::string::npos) << message;
  EXPECT_THROW(style::loadMotionClips({dir / "content"}), InputError);
}

TEST(StyleInvalid, BadFileInAFolderFailsByDefaultAndIsSkippedOnRequest) {
  TempDir dir;
  std::filesystem::create_directories(dir / "data");
  std::filesystem::copy_file(test::fixture("zombie.bvh"), dir / "data/a_zombie.bvh");
  test::writeText(dir / "data/b_blob.bvh", kUnmappableBvh);
  EXPECT_NE(messageOf([&] { style::loadMotionClips({dir / "data"}); }).find("b_blob.bvh"), std::string::npos);

  style::DatasetOptions skip;
  skip.bad_files = style::BadFilePolicy::Skip;
  std::vector<std::string> warnings;
  const auto clips = style::loadMotionClips({dir / "data"}, skip, &warnings);
  ASSERT_EQ(clips.size(), 1u);
  EXPECT_EQ(clips[0].file.filename(), "a_zombie.bvh");
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("b_blob.bvh"), std::string::npos);
  // A file named explicitly fails even with the skip policy.
  EXPECT_THROW(style::loadMotionClips({dir / "data/b_blob.bvh"}, skip), InputError);
}

TEST(StyleInvalid, NaNInTheInputIsRejectedWithTheFileName) {
  TempDir dir;
  std::string text = test::readBytes(test::fixture("zombie.bvh"));
  const std::size_t frame_time = text.find("Frame Time:");
  const std::size_t first_value = text.find('\n', frame_time) + 1;
  const std::size_t end_of_number = text.find_first_of(" \t", text.find_first_not_of(" \t", first_value));
  text.replace(first_value, end_of_number - first_value, " nan");
  test::writeText(dir / "walk_nan.bvh", text);
  const std::string message = messageOf([&] { style::loadMotionClip(dir / "walk_nan.bvh"); });
  EXPECT_NE(message.find("walk_nan.bvh"), std::string::npos) << message;

  // Features that are not finite in a preloaded clip (the GUI's library) are rejected too.
  style::LossNetworkTrainingConfig config = test::tinyLossNetworkConfig(dir / "ae.net", 1);
  config.clips[0].features.values(5, 7) = std::numeric_limits<double>::quiet_NaN();
  const std::string preloaded = messageOf([&] { style::trainLossNetwork(config); });
  EXPECT_NE(preloaded.find("cmu_131_01.bvh"), std::string::npos) << preloaded;
  EXPECT_FALSE(std::filesystem::exists(dir / "ae.net"));
}

TEST(StyleInvalid, StyleClipShorterThanTheFilterWidthNamesTheClip) {
  TempDir dir;
  test::writeTrimmedFixture("zombie.bvh", 10, dir / "zombie_short.bvh");  // 10 frames at 30 fps -> ~19 at 60
  nn::saveLossNetwork(test::tinyLossNetworkModel(), dir / "ae.net");  // width 5: too lenient for this test
  nn::LossNetworkModel wide = test::tinyLossNetworkModel();
  wide.network = nn::LossNetwork<float>({kFeatureCount, 8, 25});
  wide.network.initialise(1);
  nn::saveLossNetwork(wide, dir / "wide.net");

  style::StyleTrainingConfig config;
  config.settings = test::tinySettings(dir / "style.net", 1);
  config.loss_network = dir / "wide.net";
  config.content_clips = test::fixtureClips();
  config.styles = {{std::nullopt, dir / "zombie_short.bvh"}};
  config.shape = test::tinyTransformationShape();
  const std::string message = messageOf([&] { style::trainStyleNetwork(config); });
  EXPECT_NE(message.find("zombie_short.bvh"), std::string::npos) << message;
  EXPECT_NE(message.find("too short"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(dir / "style.net"));

  // The optimisation method applies the same rule.
  const style::MotionClip content = test::fixtureClips()[0];
  const style::MotionClip short_style = style::loadMotionClip(dir / "zombie_short.bvh");
  EXPECT_THROW(style::optimizeStyleTransfer(wide, content.features, short_style.features, "zombie_short.bvh"),
               InputError);
}

// ---- network files ------------------------------------------------------------------------------

TEST(StyleInvalid, NetworkForADifferentRepresentationIsRejected) {
  TempDir dir;
  nn::LossNetworkModel model = test::tinyLossNetworkModel();
  model.metadata.representation.fps = 30.0;
  nn::saveLossNetwork(model, dir / "ae30.net");
  const std::string message = messageOf([&] { style::loadCompatibleLossNetwork(dir / "ae30.net"); });
  EXPECT_NE(message.find("ae30.net"), std::string::npos) << message;
  EXPECT_NE(message.find("representation"), std::string::npos) << message;

  nn::StyleModel style = test::tinyStyleModel();
  style.metadata.representation.reference_body_height_cm = 170.0;
  nn::saveStyleModel(style, dir / "tall.net");
  EXPECT_THROW(style::loadCompatibleStyleModel(dir / "tall.net"), InputError);
}

TEST(StyleInvalid, CorruptOrTruncatedNetworkIsAnInputError) {
  TempDir dir;
  const std::string bytes = nn::serialiseLossNetwork(test::tinyLossNetworkModel());
  std::string corrupt = bytes;
  corrupt[corrupt.size() / 2] = static_cast<char>(corrupt[corrupt.size() / 2] ^ 0x5a);
  test::writeText(dir / "corrupt.net", corrupt);
  test::writeText(dir / "truncated.net", bytes.substr(0, bytes.size() / 3));
  EXPECT_THROW(style::loadCompatibleLossNetwork(dir / "corrupt.net"), InputError);
  EXPECT_THROW(style::loadCompatibleLossNetwork(dir / "truncated.net"), InputError);

  style::StyleTrainingConfig config;
  config.settings = test::tinySettings(dir / "style.net", 1);
  config.loss_network = dir / "corrupt.net";
  config.content_clips = test::fixtureClips();
  config.styles = {{std::nullopt, test::fixture("zombie.bvh")}};
  EXPECT_THROW(style::trainStyleNetwork(config), InputError);
}

// ---- checkpoints --------------------------------------------------------------------------------

TEST(StyleInvalid, CheckpointInAMissingFolderFailsAndKeepsTheEarlierNetwork) {
  TempDir dir;
  const nn::LossNetworkModel good = test::tinyLossNetworkModel(11);
  nn::saveLossNetwork(good, dir / "ae.net");
  const std::string before = test::readBytes(dir / "ae.net");

  style::LossNetworkTrainingConfig config = test::tinyLossNetworkConfig(dir / "ae.net", 2);
  config.settings.checkpoint = dir / "no-such-folder/ae.checkpoint";
  EXPECT_THROW(style::trainLossNetwork(config), WriteError);
  EXPECT_EQ(test::readBytes(dir / "ae.net"), before);
  EXPECT_NO_THROW(style::loadCompatibleLossNetwork(dir / "ae.net"));
}

// Runs in the death test's child: trains again (other seed, so an overwrite would show) with writes
// limited to 4 KiB; exits 3 on the expected WriteError.
[[noreturn]] void trainUnderAFileSizeLimit(const style::LossNetworkTrainingConfig& config) {
  ::signal(SIGXFSZ, SIG_IGN);
  rlimit limit{};
  limit.rlim_cur = 4096;
  limit.rlim_max = 4096;
  ::setrlimit(RLIMIT_FSIZE, &limit);
  style::LossNetworkTrainingConfig again = config;
  again.settings.seed = 99;
  try {
    style::trainLossNetwork(again);
  } catch (const WriteError&) {
    std::_Exit(3);
  } catch (...) {
    std::_Exit(4);
  }
  std::_Exit(0);
}

// A real write failure: the file-size limit makes every write past 4 KiB fail (EFBIG, like ENOSPC on a
// full disk). The limited training runs in a child process (a "threadsafe" death test re-executes this
// binary, so the nn worker threads exist in the child too); the folder is handed to it through the
// environment, since the child re-runs this test body from the start.
TEST(StyleInvalidDeathTest, DiskFullDuringACheckpointKeepsTheEarlierCheckpoint) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  constexpr const char* kDirVariable = "MOTIONSTYLE_STYLE_TEST_DISK_FULL_DIR";
  const char* inherited = std::getenv(kDirVariable);
  std::optional<TempDir> own;
  std::filesystem::path dir;
  if (inherited) {
    dir = inherited;  // the child: the parent's folder, already holding a good checkpoint
  } else {
    own.emplace();
    dir = own->path();
  }
  style::LossNetworkTrainingConfig config = test::tinyLossNetworkConfig(dir / "ae.net", 1);
  config.settings.keep_checkpoint = true;
  const std::filesystem::path checkpoint = config.settings.checkpointPath();
  std::string network_before, state_before, output_before;
  if (!inherited) {
    ASSERT_EQ(style::trainLossNetwork(config).status, style::TrainingStatus::Completed);
    network_before = test::readBytes(checkpoint);
    state_before = test::readBytes(style::statePath(checkpoint));
    output_before = test::readBytes(dir / "ae.net");
    ASSERT_FALSE(network_before.empty());
    ::setenv(kDirVariable, dir.c_str(), 1);
  }
  EXPECT_EXIT(trainUnderAFileSizeLimit(config),
      ::testing::ExitedWithCode(3), "");
  ::unsetenv(kDirVariable);
  EXPECT_EQ(test::readBytes(checkpoint), network_before);
  EXPECT_EQ(test::readBytes(style::statePath(checkpoint)), state_before);
  EXPECT_EQ(test::readBytes(dir / "ae.net"), output_before);
  EXPECT_NO_THROW(style::readCheckpoint(checkpoint));
}

TEST(StyleInvalid, ResumeWithoutACheckpointOrWithOtherDataIsAnInputError) {
  TempDir dir;
  style::LossNetworkTrainingConfig config = test::tinyLossNetworkConfig(dir / "ae.net", 2);
  config.settings.resume = true;
  EXPECT_THROW(style::trainLossNetwork(config), InputError);

  config.settings.resume = false;
  config.settings.epochs = 1;
  config.settings.keep_checkpoint = true;
  ASSERT_EQ(style::trainLossNetwork(config).status, style::TrainingStatus::Completed);
  config.settings.resume = true;
  config.settings.epochs = 2;
  config.clips.pop_back();  // other data
  const std::string message = messageOf([&] { style::trainLossNetwork(config); });
  EXPECT_NE(message.find("other data"), std::string::npos) << message;
}

TEST(StyleInvalid, CorruptOrMismatchedTrainingStateIsAnInputError) {
  TempDir dir;
  style::LossNetworkTrainingConfig config = test::tinyLossNetworkConfig(dir / "ae.net", 1);
  ASSERT_EQ(style::trainLossNetwork(config).status, style::TrainingStatus::Completed);
  const std::filesystem::path checkpoint = config.settings.checkpointPath();
  std::string state = test::readBytes(style::statePath(checkpoint));
  EXPECT_THROW(style::parseTrainingState(state.substr(0, state.size() - 9), "cut.state"), InputError);
  EXPECT_THROW(style::parseTrainingState("short", "tiny.state"), InputError);
  state[40] = static_cast<char>(state[40] ^ 1);
  EXPECT_THROW(style::parseTrainingState(state, "flipped.state"), InputError);

  // A checkpoint network that is not the one the state was written with.
  nn::saveLossNetwork(test::tinyLossNetworkModel(12), checkpoint);
  EXPECT_THROW(style::readCheckpoint(checkpoint), InputError);
}

// ---- configuration and pairing ------------------------------------------------------------------

TEST(StyleInvalid, ContentLabelsWithoutAStyleClipAreListed) {
  const std::vector<style::StyleSource> labelled = {{"walk", "walk_old.bvh"}};
  const std::string message = messageOf([&] { style::pairStyles({"walk", "run", "jump", "run"}, labelled); });
  EXPECT_NE(message.find("jump, run"), std::string::npos) << message;
  EXPECT_THROW(style::pairStyles({"walk"}, {}), InputError);
}

TEST(StyleInvalid, BadSettingsAreRejectedBeforeAnyWork) {
  TempDir dir;
  style::LossNetworkTrainingConfig config = test::tinyLossNetworkConfig(dir / "ae.net", 1);
  config.settings.epochs = 0;
  EXPECT_THROW(style::trainLossNetwork(config), std::invalid_argument);
  config = test::tinyLossNetworkConfig(dir / "ae.net", 1);
  config.settings.learning_rate = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(style::trainLossNetwork(config), std::invalid_argument);
  config = test::tinyLossNetworkConfig(dir / "ae.net", 1);
  config.settings.resume = true;
  config.settings.init = dir / "x.net";
  EXPECT_THROW(style::trainLossNetwork(config), std::invalid_argument);
  config = test::tinyLossNetworkConfig(dir / "ae.net", 1);
  config.settings.threads = 97;
  EXPECT_THROW(style::trainLossNetwork(config), std::invalid_argument);
  config = test::tinyLossNetworkConfig(dir / "ae.net", 1);
  config.settings.windows.frames = 61;
  EXPECT_THROW(style::trainLossNetwork(config), std::invalid_argument);
  EXPECT_THROW(style::splitHoldout({"a.bvh"}, 1), std::invalid_argument);
}

TEST(StyleInvalid, StrengthOutsideZeroToOneIsRejected) {
  const style::Stylizer stylizer(test::tinyStyleModel());
  const Eigen::MatrixXd& content = test::fixtureClips()[0].features.values;
  EXPECT_THROW(stylizer.stylizeFeatures(content, {}, -0.1), std::invalid_argument);
  EXPECT_THROW(stylizer.stylizeFeatures(content, {}, 1.5), std::invalid_argument);
  EXPECT_THROW(stylizer.stylizeFeatures(content, {}, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  EXPECT_THROW(stylizer.stylizeFeatures(Eigen::MatrixXd::Zero(65, 10), {}, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace motionstyle
