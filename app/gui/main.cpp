// motionstyle: the desktop app.
//   motionstyle [files...]            opens the given BVH clips
//   motionstyle --screenshot out.png  renders once after loading, saves a PNG of the window, exits
//                                     (exit code 0 on success, 1 if the PNG could not be written,
//                                     2 if a clip failed to load)
//   motionstyle --demo                opens the bundled sample clips (content and style) and, if
//                                     installed, the bundled style network (demo_scene.h)
//   motionstyle --log FILE            appends the app's log to FILE (app_log.h; also MOTIONSTYLE_LOG),
//                                     with where its named buttons and sliders are on the screen
#include <QAbstractButton>
#include <QAbstractSlider>
#include <QApplication>
#include <QComboBox>
#include <QCommandLineParser>
#include <QTimer>

#include <cstdio>

#include "app_log.h"
#include "common/allocator_tuning.h"
#include "demo_scene.h"
#include "main_window.h"
#include "result_panel.h"
#include "skeleton_viewport.h"

namespace {

// One log line per named button, slider and list box, where it is on the screen ("control: StylizeButton at
// 1062 162 size 360 26"), so that a test driving the window with real X events (xdotool) finds them.
void logControls(const QWidget& window) {
  for (const QWidget* widget : window.findChildren<QWidget*>()) {
    if (widget->objectName().isEmpty() || !widget->isVisible()) continue;
    if (!qobject_cast<const QAbstractButton*>(widget) && !qobject_cast<const QAbstractSlider*>(widget) &&
        !qobject_cast<const QComboBox*>(widget))
      continue;
    const QPoint at = widget->mapToGlobal(QPoint(0, 0));
    motionstyle::app_log::write(QStringLiteral("control: %1 at %2 %3 size %4 %5")
                                    .arg(widget->objectName()).arg(at.x()).arg(at.y())
                                    .arg(widget->width()).arg(widget->height()));
  }
}

}  // namespace

int main(int argc, char** argv) {
  motionstyle::restartWithHugePages(argv);     // the networks' buffers in 2 MB pages (allocator_tuning.h)
  motionstyle::keepLargeAllocationsInHeap();  // the networks' temporaries (allocator_tuning.h)
  // VTK needs a 3.2 core-profile context: the default format must be set before QApplication exists.
  motionstyle::SkeletonViewport::installDefaultSurfaceFormat();
  QApplication app(argc, argv);
  QApplication::setOrganizationName(QStringLiteral("MotionStyle"));
  QApplication::setApplicationName(QStringLiteral("motionstyle"));
  QApplication::setApplicationVersion(QStringLiteral(MOTIONSTYLE_VERSION));

  QCommandLineParser parser;
  parser.setApplicationDescription(QStringLiteral("Fast neural style transfer for motion data"));
  parser.addHelpOption();
  parser.addVersionOption();
  const QCommandLineOption screenshot(QStringLiteral("screenshot"),
                                      QStringLiteral("Save a PNG of the window after loading, then exit."),
                                      QStringLiteral("file"));
  const QCommandLineOption demo(QStringLiteral("demo"), QStringLiteral("Open the bundled demo: sample clips and style network."));
  const QCommandLineOption log(QStringLiteral("log"),
                               QStringLiteral("Append the app's log (timings of live edits, ...) to this file."),
                               QStringLiteral("file"));
  parser.addOption(screenshot);
  parser.addOption(demo);
  parser.addOption(log);
  parser.addPositionalArgument(QStringLiteral("clips"), QStringLiteral("BVH clips, or folders of them, to open."),
                               QStringLiteral("[clips or folders...]"));
  parser.process(app);

  const QString log_file = parser.isSet(log) ? parser.value(log) : qEnvironmentVariable("MOTIONSTYLE_LOG");
  if (!motionstyle::app_log::setFile(log_file))
    std::fprintf(stderr, "motionstyle: cannot write the log %s\n", qPrintable(log_file));
  const bool screenshot_mode = parser.isSet(screenshot);
  motionstyle::MainWindow window(/*persist_settings=*/!screenshot_mode);
  int load_failures = 0;
  if (screenshot_mode) {
    // No dialog may block an unattended run: report on stderr instead.
    window.setErrorReporter([&load_failures](const QString& title, const QString& message) {
      ++load_failures;
      std::fprintf(stderr, "motionstyle: %s: %s\n", qPrintable(title), qPrintable(message));
    });
  }
  window.show();
  window.openPaths(parser.positionalArguments());
  if (parser.isSet(demo)) {
    const motionstyle::DemoOutcome outcome = motionstyle::openDemo(window, *window.resultPanel());
    window.showStatus(outcome.message);
    std::fprintf(stderr, "motionstyle: %s\n", qPrintable(outcome.message));
  }

  if (motionstyle::app_log::enabled()) QTimer::singleShot(500, &window, [&window] { logControls(window); });
  if (!screenshot_mode) return QApplication::exec();

  // Let the window map and lay out, then grab it (grabbing renders the GL viewport itself).
  int exit_code = 0;
  QTimer::singleShot(200, &window, [&] {
    const QString file = parser.value(screenshot);
    if (!window.saveScreenshot(file)) exit_code = 1;
    else if (load_failures > 0) exit_code = 2;
    else std::fprintf(stdout, "motionstyle: wrote %s\n", qPrintable(file));
    QApplication::exit(exit_code);
  });
  QApplication::exec();
  return exit_code;
}
