#pragma once
// ClipRoles: what a panel reads of the window's clips and their roles, without a pointer to the window.
// MainWindow fills it with functions over its own state and announces changes by its clipsChanged()
// signal, which it connects to the panel; the panel never calls back into the window.

#include <QStringList>

#include <functional>
#include <vector>

#include "clip_loader.h"

namespace motionstyle {

struct ClipRoles {
  std::function<std::vector<const LoadedClip*>()> clips;  // every loaded clip, in the Clips list's order
  std::function<const LoadedClip*()> content;            // the clip with the Content role, or nullptr
  std::function<const LoadedClip*()> style;              // the clip with the Style role, or nullptr
  std::function<QStringList()> training_paths;           // the clips in the training set
  std::function<double()> display_fps;                   // the timeline's rate (0: none yet)
};

// What a training trains on when no clip is in the training set and no folder is given: every open
// clip that is mapped and is not the Style clip (an animator opens their takes and a style clip and
// presses Train).
inline QStringList defaultTrainingPaths(const ClipRoles& roles) {
  QStringList paths;
  const LoadedClip* style = roles.style();
  for (const LoadedClip* clip : roles.clips())
    if (clip != style && clip->isMapped() && !paths.contains(clip->path)) paths << clip->path;
  return paths;
}

}  // namespace motionstyle
