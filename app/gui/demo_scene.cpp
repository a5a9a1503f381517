#include "demo_scene.h"

#include <QFileInfo>
#include <QObject>

#include <filesystem>

#include "common/resource_paths.h"
#include "main_window.h"
#include "result_panel.h"

namespace motionstyle {

DemoOutcome openDemo(MainWindow& window, ResultPanel& results) {
  DemoOutcome outcome;
  const std::optional<std::filesystem::path> resources = resourceDirectory();
  if (!resources) {
    outcome.message = QObject::tr("Demo unavailable: %1")
                          .arg(QString::fromStdString(describeResourceLookup(currentResourceSearch())));
    return outcome;
  }
  const std::filesystem::path samples = *resources / "samples";
  const QStringList clips = {QString::fromStdString((samples / kDemoContentSample).string()),
                             QString::fromStdString((samples / kDemoStyleSample).string())};
  // A sample already open is reused: the demo never lists a clip twice.
  auto openOnce = [&](const QString& file) {
    const QString absolute = QFileInfo(file).absoluteFilePath();
    for (int i = 0; i < window.clipCount(); ++i)
      if (QFileInfo(window.clip(i).path).absoluteFilePath() == absolute) return i;
    return window.openFiles({file}) == 1 ? window.clipCount() - 1 : -1;
  };
  const int content = openOnce(clips[0]);
  const int style = openOnce(clips[1]);
  outcome.clips_loaded = content >= 0 && style >= 0;
  if (outcome.clips_loaded) {
    window.setContentClip(content);
    window.setStyleClip(style);
  }
  if (const auto network = shippedNetworkFile(*resources, kDemoNetwork))
    outcome.network_loaded = results.loadNetworkFile(QString::fromStdString(network->string()));
  if (!outcome.clips_loaded)
    outcome.message = QObject::tr("Demo: the sample clips are missing from %1").arg(QString::fromStdString(resources->string()));
  else if (!outcome.network_loaded)
    outcome.message = QObject::tr("Demo: sample clips loaded; no bundled style network yet (open one in the Result panel)");
  else
    outcome.message = QObject::tr("Demo: press \"Stylize & Clean Up\" in the Result panel");
  return outcome;
}

}  // namespace motionstyle
