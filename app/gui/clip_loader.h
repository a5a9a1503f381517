#pragma once
// A clip as the desktop app holds it: the editable Motion (file units) plus the positions the viewport
// draws (computed once at load, cm, Y-up). Loading goes through the core (readBvh, worldPositions).

#include <QString>

#include <Eigen/Core>

#include <filesystem>

#include "figure_data.h"
#include "motion/motion.h"

namespace motionstyle {

struct LoadedClip {
  QString path;                       // absolute path of the file
  QString name;                       // file name without folder, for lists and the legend
  Motion motion;                      // as read: file units and axes, rotations in degrees
  Eigen::MatrixXd display_positions;  // frames x 3*joints, cm, Y-up (see display_normalisation.h)

  int frameCount() const { return motion.frameCount(); }
  double fps() const { return motion.fps(); }
  int animatedJointCount() const;  // joints excluding End Sites
};

// Reads and prepares a BVH file. Throws InputError (bad or unreadable file) and std::bad_alloc; never
// leaves a partial clip.
LoadedClip loadClip(const std::filesystem::path& file);

// The viewport's view of a clip in a role (topology and display positions; no contacts yet).
FigureData figureFromClip(const LoadedClip& clip, FigureRole role);

}  // namespace motionstyle
