#pragma once
// What the live-editing GUI tests share (test_live.cpp, test_look_ahead.cpp): the app log's "live:"
// lines parsed (app_log.h: "cleaned result on screen N ms after the change"), clips written from the
// fixtures, and a base with the user's path to a first result (the window shown, a clip opened, the
// shipped elderly network chosen, Stylize).
#include <QFile>
#include <QRegularExpression>
#include <QSlider>
#include <QStyle>
#include <QTemporaryDir>
#include <QTest>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "app_log.h"
#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "common/allocator_tuning.h"
#include "common/resource_paths.h"
#include "demo_scene.h"
#include "gui_test_support.h"
#include "main_window.h"
#include "result_panel.h"
#include "shipped_networks.h"
#include "skeleton_viewport.h"

namespace motionstyle::live_test {

inline constexpr int kJobTimeoutMs = 120000;  // a hang guard, not a timing

struct LogEntry {
  QString change;
  int latency_ms = 0;
  int job_ms = 0;      // of which the job on the worker
  int figures_ms = 0;  // and the figures rebuilt and painted; the rest is waiting for the worker and the event loop
  double strength = 0.0;
  int chunks_solved = 0, chunks = 0;
  bool remembered = false;  // shown again from the Result panel's recent results: no job ran
  bool network_kept = false;  // a job that ran only the clean-up: the network output was kept
};

inline std::vector<LogEntry> readLiveLog(const QString& path) {
  QFile file(path);
  std::vector<LogEntry> entries;
  if (!file.open(QIODevice::ReadOnly | QIODevice::Text)) return entries;
  static const QRegularExpression pattern(QStringLiteral(
      R"(live: (.*) -> cleaned result on screen (\d+) ms after the change \(job (\d+) ms, figures (\d+) ms, strength ([0-9.]+), )"
      R"(\d+ frames, )"
      R"(clean-up solved (\d+) of (\d+) chunks)"));
  for (const QString& line : QString::fromUtf8(file.readAll()).split(QLatin1Char('\n'))) {
    const QRegularExpressionMatch match = pattern.match(line);
    if (match.hasMatch())
      entries.push_back({match.captured(1), match.captured(2).toInt(), match.captured(3).toInt(),
                         match.captured(4).toInt(), match.captured(5).toDouble(), match.captured(6).toInt(),
                         match.captured(7).toInt(), line.contains(QStringLiteral("remembered")),
                         line.contains(QStringLiteral("network output kept"))});
  }
  return entries;
}

inline QString readLogText(const QString& path) {
  QFile file(path);
  return file.open(QIODevice::ReadOnly | QIODevice::Text) ? QString::fromUtf8(file.readAll()) : QString();
}

// The status bar's last line, from the log ("status: TEXT", MainWindow::showStatus).
inline QString lastStatus(const QString& path) {
  const QString text = readLogText(path);
  const QString marker = QStringLiteral("status: ");
  const qsizetype at = text.lastIndexOf(marker);
  return at < 0 ? QString() : text.mid(at + marker.size()).section(QLatin1Char('\n'), 0, 0);
}

// A clip of `frames` frames from a fixture: its first frames, or played forward then backward (no jump).
inline QString writeClip(const QTemporaryDir& dir, const QString& fixture, const QString& name, int frames = 500) {
  Motion clip = readBvh(test::fixture(fixture).toStdString());
  const int n = clip.frameCount();
  MatrixRowMajor values(frames, clip.values.cols());
  for (int f = 0; f < frames; ++f) {
    const int cycle = f % (2 * n - 2);
    values.row(f) = clip.values.row(cycle < n ? cycle : 2 * n - 2 - cycle);
  }
  clip.values = values;
  const QString path = dir.filePath(name);
  writeBvh(clip, path.toStdString());
  return path;
}

// The x of `value` on a horizontal slider (the handle's centre).
inline int sliderX(const QSlider& slider, int value) {
  const int handle = slider.style()->pixelMetric(QStyle::PM_SliderLength, nullptr, &slider);
  const double share = double(value - slider.minimum()) / double(slider.maximum() - slider.minimum());
  return handle / 2 + static_cast<int>(std::lround(share * (slider.width() - handle)));
}

inline int median(std::vector<int> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

inline void printLatencies(const char* what, const std::vector<LogEntry>& entries) {
  if (entries.empty()) return;
  std::vector<int> latency, job, figures;
  for (const LogEntry& entry : entries) {
    latency.push_back(entry.latency_ms);
    job.push_back(entry.job_ms);
    figures.push_back(entry.figures_ms);
  }
  qInfo("%s: %zu results on screen, latency median %d ms, max %d ms (medians: job %d ms, figures %d ms)", what,
        entries.size(), median(latency), *std::max_element(latency.begin(), latency.end()), median(job),
        median(figures));
}

class LiveTestBase : public QObject {
 protected:
  QTemporaryDir scratch_;
  QString log_;
  std::filesystem::path network_;

  // The window shown, `clips` opened (the first is the content, a second the style clip) and the
  // elderly network chosen; nothing stylized yet.
  bool openWithNetwork(MainWindow& window, const QStringList& clips) {
    window.resize(1400, 900);
    window.show();
    return QTest::qWaitForWindowExposed(&window) && window.openFiles(clips) == clips.size() &&
           window.resultPanel()->loadNetworkFile(QString::fromStdString(network_.string()));
  }

  // The user's path to a first result: the window shown, `clip` opened as the content, the elderly
  // network chosen, Stylize, and the result in.
  bool showStylized(MainWindow& window, const QString& clip) {
    if (!openWithNetwork(window, {clip})) return false;
    ResultPanel* panel = window.resultPanel();
    panel->stylize();
    return QTest::qWaitFor([&] { return panel->result() != nullptr && !panel->isBusy(); }, kJobTimeoutMs);
  }

  // After a change: until the log has a line past its first `lines` (a result on screen) and the
  // panel is idle.
  bool waitForNewResult(const ResultPanel* panel, size_t lines) const {
    return QTest::qWaitFor([&] { return readLiveLog(log_).size() > lines && !panel->isBusy(); }, kJobTimeoutMs);
  }

  // initTestCase: the app log in scratch_, the shipped elderly network found.
  void initLogAndNetwork() {
    QVERIFY(scratch_.isValid());
    log_ = scratch_.filePath(QStringLiteral("motionstyle.log"));
    QVERIFY(app_log::setFile(log_));
    const auto resources = resourceDirectory();
    QVERIFY2(resources.has_value(), "the repository's resources/ (shipped networks) were not found");
    const auto elderly = shippedNetworkFile(*resources, kDemoNetwork);
    QVERIFY(elderly.has_value());
    network_ = *elderly;
  }
};

}  // namespace motionstyle::live_test

// main() with the app's own process set-up (app/gui/main.cpp), so that the latencies are the app's.
#define MOTIONSTYLE_LIVE_TEST_MAIN(TestClass)                     \
  int main(int argc, char** argv) {                               \
    motionstyle::restartWithHugePages(argv);                      \
    motionstyle::keepLargeAllocationsInHeap();                    \
    motionstyle::SkeletonViewport::installDefaultSurfaceFormat(); \
    QApplication app(argc, argv);                                 \
    app.setAttribute(Qt::AA_Use96Dpi, true);                      \
    TestClass test;                                               \
    return QTest::qExec(&test, argc, argv);                       \
  }
