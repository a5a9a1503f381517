#pragma once
// Helpers shared by the core/style tests: temporary folders, the committed fixtures as clips, and tiny
// networks so that training runs take a fraction of a second.

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "nn/network_file.h"
#include "style/motion_dataset.h"
#include "style/training.h"
#include "test_paths.h"

namespace motionstyle::test {

inline void writeText(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file, std::ios::binary) << text;
}

inline std::string readBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The first `frames` frames of a fixture, written to `file` (a short clip for the length rules).
inline void writeTrimmedFixture(const std::string& fixture_name, int frames, const std::filesystem::path& file) {
  Motion motion = readBvh(fixture(fixture_name));
  motion.values.conservativeResize(frames, Eigen::NoChange);
  writeBvh(motion, file);
}

inline const std::vector<style::MotionClip>& fixtureClips() {
  static const std::vector<style::MotionClip> clips = {style::loadMotionClip(fixture("cmu_131_01.bvh")),
                                                       style::loadMotionClip(fixture("zombie.bvh"))};
  return clips;
}

// Small shapes: 16 hidden units, width 5; windows of 60 frames with a step of 30.
inline nn::LossNetworkShape tinyLossNetworkShape() { return {kFeatureCount, 16, 5}; }
inline nn::TransformationShape tinyTransformationShape() { return {kFeatureCount, 8, 5, true}; }

inline style::TrainingSettings tinySettings(const std::filesystem::path& output, int epochs) {
  style::TrainingSettings settings;
  settings.epochs = epochs;
  settings.batch_size = 8;
  settings.learning_rate = 3e-3;
  settings.seed = 7;
  settings.output = output;
  settings.windows = {60, 30};
  return settings;
}

inline style::LossNetworkTrainingConfig tinyLossNetworkConfig(const std::filesystem::path& output, int epochs) {
  style::LossNetworkTrainingConfig config;
  config.settings = tinySettings(output, epochs);
  config.clips = fixtureClips();
  config.shape = tinyLossNetworkShape();
  return config;
}

// An untrained but valid tiny loss network with statistics of the fixtures, saved to `file`.
// Callbacks that cancel a run as epoch `epoch` ends (after its checkpoint): how an interrupted run
// stops, with its settings (epochs, so its learning-rate schedule) unchanged.
inline style::TrainingCallbacks cancelAtEndOfEpoch(int epoch) {
  auto cancel = std::make_shared<std::atomic<bool>>(false);
  style::TrainingCallbacks callbacks;
  callbacks.cancel = cancel.get();
  callbacks.progress = [cancel, epoch](const style::TrainingProgress& p) {
    if (p.phase == style::TrainingProgress::Phase::EpochEnd && p.epoch == epoch) *cancel = true;
  };
  return callbacks;
}

inline nn::LossNetworkModel tinyLossNetworkModel(std::uint32_t seed = 3) {
  nn::LossNetworkModel model{nn::LossNetwork<float>(tinyLossNetworkShape()), {}, {}};
  model.network.initialise(seed);
  std::vector<Eigen::MatrixXd> values;
  for (const auto& clip : fixtureClips()) values.push_back(clip.features.values);
  model.normalisation = computeFeatureStatistics(values);
  model.metadata.representation = style::currentRepresentation();
  return model;
}

inline nn::StyleModel tinyStyleModel(std::uint32_t seed = 5) {
  const nn::LossNetworkModel loss = tinyLossNetworkModel();
  nn::StyleModel model{nn::TransformationNetwork<float>(tinyTransformationShape()), loss.network, loss.normalisation, {}, {}};
  model.transformation.initialise(seed);
  model.metadata.representation = style::currentRepresentation();
  return model;
}

// Every weight of a network, in parameter order (takes a copy: parameters() is not const).
template <typename Network>
std::vector<float> weightsOf(Network network) {
  std::vector<float> all;
  for (const auto* p : network.parameters()) all.insert(all.end(), p->value.data(), p->value.data() + p->value.size());
  return all;
}

}  // namespace motionstyle::test
