#pragma once
// A tiny, untrained but valid style network for the GUI tests (8 hidden units, width 5; its loss
// network 16 hidden units), with the fixtures' feature statistics: built in milliseconds, saved where
// a test wants it.

#include <QString>
#include <QTemporaryDir>

#include <filesystem>
#include <vector>

#include "features/feature_statistics.h"
#include "gui_test_support.h"
#include "nn/network_file.h"
#include "style/motion_dataset.h"
#include "style/training.h"

namespace motionstyle::test {

inline nn::StyleModel tinyStyleModel(unsigned seed = 5) {
  std::vector<Eigen::MatrixXd> values;
  for (const char* clip : {"cmu_131_01.bvh", "zombie.bvh"})
    values.push_back(style::loadMotionClip(fixture(QString::fromLatin1(clip)).toStdString()).features.values);
  nn::StyleModel model{nn::TransformationNetwork<float>({kFeatureCount, 8, 5, true}),
                       nn::LossNetwork<float>({kFeatureCount, 16, 5}), computeFeatureStatistics(values), {}, {}};
  model.transformation.initialise(seed);
  model.loss_network.initialise(3);
  model.metadata.representation = style::currentRepresentation();
  return model;
}

inline std::filesystem::path saveInto(const QTemporaryDir& dir, const QString& name, const nn::StyleModel& model) {
  const std::filesystem::path file = dir.filePath(name + QStringLiteral(".net")).toStdString();
  nn::saveStyleModel(model, file);
  return file;
}

}  // namespace motionstyle::test
