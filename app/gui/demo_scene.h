#pragma once
// The first-run demo (`motionstyle --demo`): the bundled sample clips as content and style and, when
// the shipped networks are installed, the bundled style network, so that one click on "Stylize"
// shows a result. Resources are found by core/common/resource_paths.h (build tree or
// <prefix>/share/motionstyle). Parts that are missing are left out, and the returned text says so.

#include <QString>

namespace motionstyle {

class MainWindow;
class ResultPanel;

inline constexpr const char* kDemoContentSample = "cmu_131_01_walk.bvh";
inline constexpr const char* kDemoStyleSample = "zombie_walk.bvh";
inline constexpr const char* kDemoNetwork = "elderly";

struct DemoOutcome {
  bool clips_loaded = false;    // content and style both loaded
  bool network_loaded = false;  // the bundled style network is in the Result panel
  QString message;              // for the status bar, e.g. "Demo: press Stylize" or what was missing
};

// Loads the demo into `window` (its clips list and its Result panel).
DemoOutcome openDemo(MainWindow& window, ResultPanel& results);

}  // namespace motionstyle
