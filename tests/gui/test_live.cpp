// Live editing as a user does it, in the real window under Xvfb: the strength slider dragged with the
// mouse and a contact stroke painted on the timeline, on 500-frame clips (120 fps, and 30 fps, whose
// clean-up runs on 1,000 frames at the network's 60 fps), with the shipped elderly network. The
// latencies come from the app's own log (app_log.h): "cleaned result on screen N ms after the change".
// They are printed (the figures in the README come from here), not asserted: a test checks behaviour.
// Checked: results arrive while the hand is still on the control, drawn at reduced resolution until
// it lets go; the last result answers the last value; a contact stroke late in the clip re-solves
// only the chunk it touches.
#include <QComboBox>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QPushButton>
#include <QRegularExpression>
#include <QSignalSpy>
#include <QSlider>
#include <QStyle>
#include <QTemporaryDir>
#include <QTest>

#include <cmath>

#include <algorithm>
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
#include "network_panel.h"
#include "result_panel.h"
#include "shipped_networks.h"
#include "skeleton_viewport.h"
#include "timeline_widget.h"
#include "track_view.h"

using namespace motionstyle;

namespace {

constexpr int kJobTimeoutMs = 120000;  // a hang guard, not a timing

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

std::vector<LogEntry> readLiveLog(const QString& path) {
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

QString readLogText(const QString& path) {
  QFile file(path);
  return file.open(QIODevice::ReadOnly | QIODevice::Text) ? QString::fromUtf8(file.readAll()) : QString();
}

// The status bar's last line, from the log ("status: TEXT", MainWindow::showStatus).
QString lastStatus(const QString& path) {
  const QString text = readLogText(path);
  const QString marker = QStringLiteral("status: ");
  const qsizetype at = text.lastIndexOf(marker);
  return at < 0 ? QString() : text.mid(at + marker.size()).section(QLatin1Char('\n'), 0, 0);
}

// A clip of `frames` frames from a fixture: its first frames, or played forward then backward (no jump).
QString writeClip(const QTemporaryDir& dir, const QString& fixture, const QString& name, int frames = 500) {
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
int sliderX(const QSlider& slider, int value) {
  const int handle = slider.style()->pixelMetric(QStyle::PM_SliderLength, nullptr, &slider);
  const double share = double(value - slider.minimum()) / double(slider.maximum() - slider.minimum());
  return handle / 2 + static_cast<int>(std::lround(share * (slider.width() - handle)));
}

int median(std::vector<int> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

void printLatencies(const char* what, const std::vector<LogEntry>& entries) {
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

}  // namespace

class LiveTest : public QObject {
  Q_OBJECT

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

 private slots:
  void initTestCase() {
    QVERIFY(scratch_.isValid());
    log_ = scratch_.filePath(QStringLiteral("motionstyle.log"));
    QVERIFY(app_log::setFile(log_));
    const auto resources = resourceDirectory();
    QVERIFY2(resources.has_value(), "the repository's resources/ (shipped networks) were not found");
    const auto elderly = shippedNetworkFile(*resources, kDemoNetwork);
    QVERIFY(elderly.has_value());
    network_ = *elderly;
  }

  void cleanupTestCase() { app_log::setFile(QString()); }

  void draggingTheStrengthShowsResultsWhileTheHandMoves_data() {
    QTest::addColumn<QString>("fixture");
    QTest::newRow("120 fps") << QStringLiteral("cmu_131_01.bvh");
    QTest::newRow("30 fps") << QStringLiteral("zombie.bvh");
  }

  void draggingTheStrengthShowsResultsWhileTheHandMoves() {
    QFETCH(QString, fixture);
    const QString clip = writeClip(scratch_, fixture, QStringLiteral("clip_500.bvh"));
    MainWindow window(false);
    QVERIFY(showStylized(window, clip));
    ResultPanel* panel = window.resultPanel();

    auto* slider = panel->findChild<QSlider*>(QStringLiteral("StrengthSlider"));
    QVERIFY(slider != nullptr && slider->isEnabled());
    const size_t before = readLiveLog(log_).size();
    const int y = slider->height() / 2;
    QTest::mousePress(slider, Qt::LeftButton, Qt::NoModifier, QPoint(sliderX(*slider, 100), y));
    for (int value = 98; value >= 40; value -= 2) {  // a hand moving for about a second
      QTest::mouseMove(slider, QPoint(sliderX(*slider, value), y));
      QTest::qWait(30);
    }
    const std::vector<LogEntry> while_dragging = readLiveLog(log_);
    // Results that arrive while the hand is down are drawn at reduced resolution (LiveResolution)...
    QVERIFY(window.viewport()->reducedResolution());
    QTest::mouseRelease(slider, Qt::LeftButton, Qt::NoModifier, QPoint(sliderX(*slider, 40), y));
    QVERIFY(QTest::qWaitFor([&] { return !panel->isBusy(); }, kJobTimeoutMs));
    // ... and the last one, once it is let go, at full resolution.
    QVERIFY(!window.viewport()->reducedResolution());
    QCOMPARE(window.viewport()->grabFrame().size(), window.viewport()->size() * window.viewport()->devicePixelRatio());
    QVERIFY2(slider->value() < 60, qPrintable(QString::number(slider->value())));

    std::vector<LogEntry> latencies;
    for (size_t i = before; i < while_dragging.size(); ++i)
      if (while_dragging[i].change.contains(QStringLiteral("strength"))) latencies.push_back(while_dragging[i]);
    QVERIFY2(latencies.size() >= 3, "results must follow the slider while it moves");
    const std::vector<LogEntry> all = readLiveLog(log_);
    QCOMPARE(all.back().strength, panel->strength());  // the last result answers the last value
    QVERIFY(!panel->resultIsStale());
    printLatencies(qPrintable(QStringLiteral("strength drag, 500 frames at ") + QString::fromLatin1(QTest::currentDataTag())),
                   latencies);
    QVERIFY(!test::saveScreenshot(window.grab().toImage(),
                                  QStringLiteral("live_strength_") + QString::fromLatin1(QTest::currentDataTag()).remove(QLatin1Char(' ')))
                 .isEmpty());
  }

  // The figures are rebuilt for each result only: when the shown one goes out of date they are renamed
  // once, not rebuilt, and nothing happens at the other steps of the hand (rebuilding them took GUI
  // time, and a core, from the job that replaces them).
  void stepsOfADragRenameTheFiguresOnce() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_steps.bvh"));
    MainWindow window(false);
    QVERIFY(showStylized(window, clip));
    ResultPanel* panel = window.resultPanel();
    auto* slider = panel->findChild<QSlider*>(QStringLiteral("StrengthSlider"));
    QVERIFY(slider != nullptr);
    QSignalSpy rebuilt(panel, &ResultPanel::resultChanged);
    QSignalSpy renamed(panel, &ResultPanel::resultRenamed);
    const int renders = window.viewport()->renderCount();
    for (int value = 98; value >= 90; value -= 2) slider->setValue(value);  // five steps before any answer
    QCOMPARE(rebuilt.count(), 0);
    QCOMPARE(renamed.count(), 1);
    QVERIFY(panel->resultIsStale());
    const QString stale_name = window.viewport()->figure(window.viewport()->figureCount() - 1).name;
    QVERIFY2(stale_name.contains(QStringLiteral("out of date")), qPrintable(stale_name));
    QCoreApplication::processEvents();  // the legend repaints; the 3-D view has nothing new to draw
    QCOMPARE(window.viewport()->renderCount(), renders);
    QVERIFY(QTest::qWaitFor([&] { return !panel->isBusy(); }, kJobTimeoutMs));
    QVERIFY(!panel->resultIsStale());
    QCOMPARE(panel->strength(), 0.9);
  }

  // A job that has only just started when the hand moves on is replaced at once (its values are
  // already left behind); the next change waits for the replacement, so results keep coming. A long
  // clip, so that "only just started" (half a job) holds whatever the machine's load.
  void aJobThatHasOnlyJustStartedIsReplaced() {
    const QString clip =
        writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_replace.bvh"), 6000);
    MainWindow window(false);
    QVERIFY(showStylized(window, clip));
    ResultPanel* panel = window.resultPanel();
    auto* slider = panel->findChild<QSlider*>(QStringLiteral("StrengthSlider"));
    QVERIFY(slider != nullptr);
    const size_t before = readLiveLog(log_).size();
    QSignalSpy busy(panel, &ResultPanel::busyChanged);
    slider->setValue(90);  // starts a job
    slider->setValue(80);  // at once: that job is replaced
    slider->setValue(70);  // the replacement is young too, but is not replaced twice in a row: waits
    QVERIFY(QTest::qWaitFor([&] { return !panel->isBusy(); }, kJobTimeoutMs));
    const std::vector<LogEntry> all = readLiveLog(log_);
    std::vector<double> shown;
    for (size_t i = before; i < all.size(); ++i) shown.push_back(all[i].strength);
    QCOMPARE(shown, (std::vector<double>{0.8, 0.7}));
    // 0.7's job started before 0.8's (out-of-date) result was painted: the panel never went idle in
    // between, it went busy once and idle once.
    QCOMPARE(busy.count(), 2);
    QCOMPARE(busy.at(0).at(0).toBool(), true);
    QCOMPARE(busy.at(1).at(0).toBool(), false);
  }

  // Another style picked in the Result panel's list with the keyboard, as a user does: the network
  // is loaded and the clip stylized and cleaned up again. Printed: the wall time from the key press to
  // the new result painted, beside the log's latency.
  // Switching the style with the keyboard, as an artist compares two styles: a style not yet shown
  // for these inputs is computed (a job), one shown before for the same clip, strength, path and
  // contacts is shown again at once (recent_results.h). Both are timed, separately.
  void switchingTheStyleShowsItsResult_data() {
    QTest::addColumn<QString>("fixture");
    QTest::newRow("120 fps") << QStringLiteral("cmu_131_01.bvh");  // 250 frames at 60 fps to refine
    QTest::newRow("30 fps") << QStringLiteral("zombie.bvh");       // 1,000: the refinement 4x longer
  }

  void switchingTheStyleShowsItsResult() {
    QFETCH(QString, fixture);
    const QString clip = writeClip(scratch_, fixture, QStringLiteral("clip_switch_%1").arg(fixture));
    MainWindow window(false);
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(-1);  // which switches are computed must not depend on the test's pace
    QVERIFY(showStylized(window, clip));
    auto* choice = panel->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    auto* slider = panel->findChild<QSlider*>(QStringLiteral("StrengthSlider"));
    QVERIFY(choice != nullptr && choice->count() >= 3 && slider != nullptr);
    std::vector<int> wall_computed, wall_remembered, wall_run;
    std::vector<LogEntry> computed, remembered, run;
    for (int step = 0; step < 8; ++step) {
      // Odd steps first move the strength by one notch (and wait for its result), so that neither
      // style has a result for the new inputs: the switch that follows is a job, which keeps the
      // other style's network output (shown on this clip before) and runs only the clean-up.
      const bool fresh_inputs = step % 2 == 1 && step > 1;
      if (fresh_inputs) {
        const size_t before = readLiveLog(log_).size();
        slider->setValue(slider->value() - 1);
        QVERIFY(waitForNewResult(panel, before));
      }
      const size_t before = readLiveLog(log_).size();
      const QString from = choice->currentText();
      choice->setFocus();
      QElapsedTimer timer;
      timer.start();
      QTest::keyClick(choice, step % 2 == 0 ? Qt::Key_Down : Qt::Key_Up);
      QVERIFY(choice->currentText() != from);
      QVERIFY(waitForNewResult(panel, before));
      const int wall = static_cast<int>(timer.elapsed());
      const LogEntry entry = readLiveLog(log_).back();
      QVERIFY(entry.change.contains(QStringLiteral("style")));
      QVERIFY(!panel->resultIsStale());
      if (step == 0) continue;  // the first read of a network (390-460 ms), not a switch between prepared ones
      // Back and forth with nothing else changed, each style's result is remembered; after a strength
      // change, the other style's is not.
      QVERIFY2(entry.remembered == !fresh_inputs, qPrintable(QStringLiteral("step %1").arg(step)));
      if (entry.remembered) QVERIFY(lastStatus(log_).startsWith(QStringLiteral("Shown again")));
      QVERIFY2(entry.remembered || entry.network_kept, qPrintable(QStringLiteral("step %1: the network ran").arg(step)));
      (entry.remembered ? remembered : computed).push_back(entry);
      (entry.remembered ? wall_remembered : wall_computed).push_back(wall);
    }
    // Further down the list: styles never shown on this clip, the network runs (the first one's file
    // is read first: not timed).
    for (int step = 0; step < 4; ++step) {
      const size_t before = readLiveLog(log_).size();
      QElapsedTimer timer;
      timer.start();
      QTest::keyClick(choice, Qt::Key_Down);
      QVERIFY(waitForNewResult(panel, before));
      const int wall = static_cast<int>(timer.elapsed());
      const LogEntry entry = readLiveLog(log_).back();
      if (step == 0) {
        QVERIFY(entry.remembered);  // back to the style shown last, at these inputs
        continue;
      }
      QVERIFY(!entry.remembered && !entry.network_kept);
      if (step == 1) continue;  // its file read on the GUI thread
      run.push_back(entry);
      wall_run.push_back(wall);
    }
    QVERIFY(!computed.empty() && !remembered.empty());
    qInfo("%s, 500 frames:", qPrintable(fixture));
    printLatencies("style switch after a strength change, to a style shown on this clip (only the clean-up runs)",
                   computed);
    printLatencies("style switch to a style never shown on this clip (the network runs)", run);
    printLatencies("style switch back to a style shown for the same inputs", remembered);
    qInfo("style switch: key press -> new result painted, wall clock: after a change %d ms, max %d ms; remembered "
          "median %d ms, max %d ms; network run (its file read first) median %d ms",
          median(wall_computed), *std::max_element(wall_computed.begin(), wall_computed.end()), median(wall_remembered),
          *std::max_element(wall_remembered.begin(), wall_remembered.end()), median(wall_run));
  }

  // While the user looks at a result, the styles near it in the chooser (for a 500-frame clip, every
  // other shipped style) are computed ahead: a switch to the next one, and then to the one after, is
  // shown without a job.
  // A change of the inputs drops them.
  void theNearbyStylesAreComputedAhead() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_ahead.bvh"));
    MainWindow window(false);
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(0);
    QVERIFY(showStylized(window, clip));
    auto* choice = panel->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    QVERIFY(choice != nullptr && choice->currentIndex() + 2 < choice->count());
    // 500 frames: every other shipped style is computed ahead (lookAheadStyles), one at a time.
    const int ahead = std::min(panel->lookAheadStyles(), choice->count() - 1);
    QCOMPARE(ahead, std::min(ResultPanel::kLookAheadMaxStyles, choice->count() - 1));
    QVERIFY(QTest::qWaitFor([&] { return panel->recentResults().size() == 1 + ahead; }, kJobTimeoutMs));
    QVERIFY(readLogText(log_).contains(QStringLiteral("look-ahead: ")));

    choice->setFocus();
    for (const char* which : {"the next style", "the one after it"}) {
      const size_t before = readLiveLog(log_).size();
      const QString from = choice->currentText();
      QElapsedTimer timer;
      timer.start();
      QTest::keyClick(choice, Qt::Key_Down);
      QVERIFY(choice->currentText() != from);
      QVERIFY(waitForNewResult(panel, before));
      const LogEntry entry = readLiveLog(log_).back();
      QVERIFY2(entry.remembered, qPrintable(QStringLiteral("%1 was not computed ahead").arg(QLatin1String(which))));
      QVERIFY(!panel->resultIsStale());
      QVERIFY(lastStatus(log_).startsWith(QStringLiteral("Computed ahead")));  // never shown before: not "again"
      qInfo("style switch to %s, computed ahead: key press -> new result painted %d ms (figures %d ms)", which,
            static_cast<int>(timer.elapsed()), entry.figures_ms);
    }

    // Another strength: nothing computed ahead matches it; the switch back is a job.
    panel->setLookAheadDelay(-1);
    auto* slider = panel->findChild<QSlider*>(QStringLiteral("StrengthSlider"));
    const size_t before_strength = readLiveLog(log_).size();
    slider->setValue(slider->value() - 5);
    QVERIFY(waitForNewResult(panel, before_strength));
    const size_t before_back = readLiveLog(log_).size();
    QTest::keyClick(choice, Qt::Key_Up);
    QVERIFY(waitForNewResult(panel, before_back));
    QVERIFY(!readLiveLog(log_).back().remembered);
  }

  // Stylize, or a switch to the next style, while the look-ahead computes that very result: the panel
  // waits for it instead of dropping it and running the same job again (6,000 frames: each style's job
  // takes far longer than the 50 ms the test gives it to start).
  void aResultBeingComputedAheadIsWaitedFor() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_6000.bvh"), 6000);
    MainWindow window(false);
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(0);
    auto* choice = panel->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    QVERIFY(choice != nullptr && choice->count() >= 3);
    // The window up for a moment before the clip opens: the shipped networks are prepared.
    const qsizetype read = readLogText(log_).count(QStringLiteral("read and prepared"));
    window.show();
    QVERIFY(QTest::qWaitFor([&] {
      return readLogText(log_).count(QStringLiteral("read and prepared")) == read + choice->count();
    }, kJobTimeoutMs));
    QVERIFY(openWithNetwork(window, {clip}));
    QTest::qWait(50);  // the chosen style's look-ahead job starts
    size_t before = readLiveLog(log_).size();
    panel->stylize();
    QVERIFY(panel->isBusy());
    QVERIFY(waitForNewResult(panel, before));
    LogEntry entry = readLiveLog(log_).back();
    QCOMPARE(entry.change, QStringLiteral("Stylize"));
    QVERIFY2(entry.remembered, "Stylize ran the job the look-ahead was running");
    qInfo("Stylize while the look-ahead computed it (6,000 frames): %d ms to the result, of which waiting %d ms",
          entry.latency_ms, entry.job_ms);
    QVERIFY(lastStatus(log_).startsWith(QStringLiteral("Stylized and cleaned up 6000 frames")));

    QVERIFY(choice->currentIndex() + 1 < choice->count());
    QTest::qWait(50);  // the next style's look-ahead job starts
    before = readLiveLog(log_).size();
    choice->setFocus();
    QTest::keyClick(choice, Qt::Key_Down);
    QVERIFY(panel->isBusy());
    QVERIFY(waitForNewResult(panel, before));
    entry = readLiveLog(log_).back();
    QVERIFY2(entry.remembered, "the switch ran the job the look-ahead was running");
    qInfo("switch to the style the look-ahead computed: %d ms to the result, of which waiting %d ms", entry.latency_ms,
          entry.job_ms);
    QVERIFY(!panel->resultIsStale());

    // Cancel while waiting (another strength: the next style's clean-up is under way when it is
    // picked): the panel is free at once, and the next edit gets its result.
    auto* slider = panel->findChild<QSlider*>(QStringLiteral("StrengthSlider"));
    QVERIFY(slider != nullptr);
    before = readLiveLog(log_).size();
    slider->setValue(slider->value() - 10);
    QVERIFY(waitForNewResult(panel, before));
    QTest::qWait(50);
    QTest::keyClick(choice, Qt::Key_Down);
    QVERIFY(panel->isBusy());
    panel->cancel();
    QVERIFY(!panel->isBusy());
    before = readLiveLog(log_).size();
    slider->setValue(slider->value() - 10);
    QVERIFY(waitForNewResult(panel, before));
    QVERIFY(!panel->resultIsStale());
    QCOMPARE(readLiveLog(log_).back().strength, panel->strength());
  }

  // A strength drag let go: the styles around the chosen one are computed for the new strength at once,
  // not after the rest that keeps the look-ahead out of a drag's steps (longer than the wait here).
  void theLookAheadStartsWhenTheHandLetsGo() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_let_go.bvh"));
    MainWindow window(false);
    QVERIFY(showStylized(window, clip));
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(2 * kJobTimeoutMs);
    auto* slider = panel->findChild<QSlider*>(QStringLiteral("StrengthSlider"));
    QVERIFY(slider != nullptr);
    const int y = slider->height() / 2;
    QTest::mousePress(slider, Qt::LeftButton, Qt::NoModifier, QPoint(sliderX(*slider, 100), y));
    for (int value = 96; value >= 80; value -= 4) {
      QTest::mouseMove(slider, QPoint(sliderX(*slider, value), y));
      QTest::qWait(60);
    }
    QVERIFY(window.viewport()->reducedResolution());  // results came while the hand was down
    QTest::mouseRelease(slider, Qt::LeftButton, Qt::NoModifier, QPoint(sliderX(*slider, 80), y));
    QVERIFY(QTest::qWaitFor([&] { return !panel->isBusy() && !panel->resultIsStale(); }, kJobTimeoutMs));
    const QString computed = QStringLiteral("computed for the current inputs");
    const qsizetype before = readLogText(log_).count(computed);
    QVERIFY(QTest::qWaitFor([&] { return readLogText(log_).count(computed) > before; }, kJobTimeoutMs));
  }

  // A clip of 2,000 frames (17 s at 120 fps, as a capture session delivers them): every shipped style
  // is computed ahead too, so a pick anywhere in the list is shown without a job, not only one of
  // the two nearest.
  void everyStyleOfA2000FrameClipIsComputedAhead() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_2000.bvh"), 2000);
    MainWindow window(false);
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(0);
    QVERIFY(showStylized(window, clip));
    auto* choice = panel->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    QVERIFY(choice != nullptr && choice->count() >= 5);
    QCOMPARE(panel->lookAheadStyles(), std::min(ResultPanel::kLookAheadMaxStyles, choice->count() - 1));
    QVERIFY(QTest::qWaitFor([&] { return panel->recentResults().size() == choice->count(); }, kJobTimeoutMs));
    // The style at the far end of the list from the chosen one.
    const bool to_last = choice->currentIndex() < choice->count() / 2;
    const size_t before = readLiveLog(log_).size();
    choice->setFocus();
    QTest::keyClick(choice, to_last ? Qt::Key_End : Qt::Key_Home);
    QCOMPARE(choice->currentIndex(), to_last ? choice->count() - 1 : 0);
    QVERIFY(waitForNewResult(panel, before));
    const LogEntry entry = readLiveLog(log_).back();
    QVERIFY2(entry.remembered, "the style furthest from the chosen one was not computed ahead");
    QVERIFY(!panel->resultIsStale());
    qInfo("style switch to the furthest style of a 2,000-frame clip, computed ahead: %d ms (figures %d ms)",
          entry.latency_ms, entry.figures_ms);
  }

  // Before any clip is open, the shipped networks are read and prepared: a style picked in the
  // chooser is then in use at once (not read on a worker first, its result waiting for the read).
  // A clip opened starts the look-ahead at once, without the rest an edit waits for.
  void theShippedNetworksAreReadBeforeAClipOpens() {
    MainWindow window(false);
    std::vector<QString> reports;
    window.setErrorReporter([&](const QString& title, const QString&) { reports.push_back(title); });
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(0);
    auto* choice = panel->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    QVERIFY(choice != nullptr && choice->count() >= 2);
    // A listed file that is not a network: skipped without a word (the user hears of it if they pick it).
    const QString broken = scratch_.filePath(QStringLiteral("broken.net"));
    QFile file(broken);
    QVERIFY(file.open(QIODevice::WriteOnly) && file.write("not a network\n") > 0);
    file.close();
    choice->insertItem(1, QStringLiteral("Broken"), broken);
    const int before = static_cast<int>(readLogText(log_).count(QStringLiteral("read and prepared")));
    window.resize(1400, 900);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QVERIFY(QTest::qWaitFor([&] {
      return readLogText(log_).count(QStringLiteral("read and prepared")) == before + choice->count() - 1;
    }, kJobTimeoutMs));
    QVERIFY(readLogText(log_).contains(QStringLiteral("broken.net not readable")));
    QVERIFY(reports.empty());
    choice->setFocus();
    QTest::keyClick(choice, Qt::Key_End);
    QCOMPARE(panel->networkName(), choice->itemText(choice->count() - 1));  // in use already
    QTest::keyClick(choice, Qt::Key_Home);
    QCOMPARE(panel->networkName(), choice->itemText(0));

    // A clip opened: its styles are computed although an edit's rest (longer than the wait) never ends,
    // every shipped one (500 frames), past the unreadable entry next to the chosen one.
    panel->setLookAheadDelay(2 * kJobTimeoutMs);
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_opened.bvh"));
    QCOMPARE(window.openFiles({clip}), 1);
    QVERIFY(QTest::qWaitFor([&] { return panel->recentResults().size() == choice->count() - 1; }, kJobTimeoutMs));
    QVERIFY(reports.empty());
  }

  // A style chosen before the first result: while the user looks at the clip, the chosen style and
  // then its neighbours are computed ahead, so the Stylize button shows the result at once (the user
  // never waits for the first one) and a switch right after it too. An input changed before Stylize
  // drops them (anInputChangedBeforeStylizeIsComputedAheadAgain): the press then shows the new inputs'
  // result, never one made for the old.
  void theChosenStyleIsComputedBeforeStylizeIsPressed() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_first.bvh"));
    MainWindow window(false);
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(0);
    QVERIFY(openWithNetwork(window, {clip}));
    auto* choice = panel->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    QVERIFY(choice != nullptr && choice->count() >= 3);
    const int ahead = std::min(1 + panel->lookAheadStyles(), choice->count());
    QVERIFY(QTest::qWaitFor([&] { return panel->recentResults().size() == ahead; }, kJobTimeoutMs));
    QVERIFY(panel->result() == nullptr);  // nothing is shown before the user asks

    auto* button = panel->findChild<QPushButton*>(QStringLiteral("StylizeButton"));
    QVERIFY(button != nullptr);
    size_t before = readLiveLog(log_).size();
    QTest::mouseClick(button, Qt::LeftButton);
    QVERIFY(waitForNewResult(panel, before));
    LogEntry entry = readLiveLog(log_).back();
    QCOMPARE(entry.change, QStringLiteral("Stylize"));
    QVERIFY2(entry.remembered, "Stylize ran a job: the chosen style was not computed ahead");
    QVERIFY(panel->result() != nullptr && !panel->resultIsStale());
    QVERIFY(lastStatus(log_).startsWith(QStringLiteral("Stylized and cleaned up 500 frames")));
    qInfo("Stylize with the chosen style computed ahead: click -> result on screen %d ms", entry.latency_ms);

    before = readLiveLog(log_).size();
    choice->setFocus();
    QTest::keyClick(choice, Qt::Key_Down);
    QVERIFY(waitForNewResult(panel, before));
    QVERIFY2(readLiveLog(log_).back().remembered, "the next style was not computed ahead");
  }

  void anInputChangedBeforeStylizeIsComputedAheadAgain() {
    const QString clip = writeClip(scratch_, QStringLiteral("zombie.bvh"), QStringLiteral("clip_first_other.bvh"), 300);
    MainWindow window(false);
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(0);
    QVERIFY(openWithNetwork(window, {clip}));
    auto* button = panel->findChild<QPushButton*>(QStringLiteral("StylizeButton"));
    QVERIFY(button != nullptr);
    const qsizetype looked_ahead = readLogText(log_).count(QStringLiteral("look-ahead: "));
    panel->setStrength(0.6);  // a result computed ahead is logged only while its inputs are the panel's
    QVERIFY(QTest::qWaitFor([&] { return readLogText(log_).count(QStringLiteral("look-ahead: ")) > looked_ahead; },
                            kJobTimeoutMs));
    const size_t before = readLiveLog(log_).size();
    QTest::mouseClick(button, Qt::LeftButton);
    QVERIFY(waitForNewResult(panel, before));
    const LogEntry entry = readLiveLog(log_).back();
    QVERIFY(entry.remembered);
    QCOMPARE(entry.strength, 0.6);
    QCOMPARE(panel->result()->cleaned.frameCount(), 300);
  }

  // While the Style networks panel has the cores (here the optimisation method), nothing is computed
  // ahead, even after a change with the look-ahead's delay at zero; when its job ends, it resumes.
  void aJobOfTheStyleNetworksPanelHoldsTheLookAhead() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_held.bvh"));
    const QString style_clip = writeClip(scratch_, QStringLiteral("zombie.bvh"), QStringLiteral("clip_held_style.bvh"), 200);
    MainWindow window(false);
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(-1);
    QVERIFY(openWithNetwork(window, {clip, style_clip}));
    NetworkPanel* networks = window.networkPanel();
    networks->setLossNetworkFile(shippedLossNetworkFile());
    QSignalSpy finished(networks, &NetworkPanel::jobFinished);
    QVERIFY(networks->startTransfer(100000));
    const qsizetype looked_ahead = readLogText(log_).count(QStringLiteral("look-ahead: "));
    panel->setLookAheadDelay(0);
    panel->setStrength(0.9);  // a change: with the delay at zero the look-ahead would start at once
    QTest::qWait(800);
    QCOMPARE(panel->recentResults().size(), 0);
    QCOMPARE(readLogText(log_).count(QStringLiteral("look-ahead: ")), looked_ahead);
    networks->cancelJob();
    QVERIFY(finished.wait(kJobTimeoutMs));
    QVERIFY(QTest::qWaitFor([&] { return panel->recentResults().size() >= 1; }, kJobTimeoutMs));
  }

  // A style picked in the chooser whose file was never read is read on a worker: the key press
  // returns at once with the old network still in use and its result marked out of date ("Reading"),
  // no job runs for the old style meanwhile (a strength change waits too), and the new style's result
  // follows, its latency counted from the pick. A file that fails to read puts the chooser and the
  // result back as they were, with a report.
  void aStylePickedBeforeItsFileIsReadDoesNotBlock() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_reading.bvh"));
    MainWindow window(false);
    QStringList reports;
    window.setErrorReporter([&reports](const QString& title, const QString&) { reports << title; });
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(-1);
    QVERIFY(showStylized(window, clip));
    auto* choice = panel->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    auto* slider = panel->findChild<QSlider*>(QStringLiteral("StrengthSlider"));
    QVERIFY(choice != nullptr && slider != nullptr && choice->currentIndex() + 1 < choice->count());
    const QString before_name = panel->networkName();
    const size_t before = readLiveLog(log_).size();
    choice->setFocus();
    QTest::keyClick(choice, Qt::Key_Down);  // the next shipped style, never read in this window
    QCOMPARE(panel->networkName(), before_name);  // not used yet: its file is being read
    QVERIFY(panel->resultIsStale());
    QVERIFY(!panel->isBusy());
    slider->setValue(slider->value() - 1);  // no job for the style being left
    QVERIFY(!panel->isBusy());
    QVERIFY(waitForNewResult(panel, before));
    const LogEntry entry = readLiveLog(log_).back();
    QVERIFY2(entry.change.contains(QStringLiteral("style")), qPrintable(entry.change));
    QVERIFY(panel->networkName() != before_name && panel->networkName() == choice->currentText());
    QCOMPARE(entry.strength, slider->value() / 100.0);
    QVERIFY(!panel->resultIsStale());

    // A pick back to the network in use while another entry is read: no switch, the result current again.
    const QString in_use_before = panel->networkName();
    QTest::keyClick(choice, Qt::Key_Down);  // never read yet
    QVERIFY(panel->resultIsStale());
    QTest::keyClick(choice, Qt::Key_Up);    // the network in use, prepared
    QCOMPARE(panel->networkName(), in_use_before);
    QVERIFY(QTest::qWaitFor([&] { return !panel->isBusy() && !panel->resultIsStale(); }, kJobTimeoutMs));
    QTest::qWait(500);  // the read ends (it only fills the cache): the chooser and the network stay
    QCOMPARE(panel->networkName(), in_use_before);
    QCOMPARE(choice->currentText(), in_use_before);

    // A network file damaged since it was prepared is read again, and fails.
    const QString copy = scratch_.filePath(QStringLiteral("copied_style.net"));
    QVERIFY(QFile::copy(QString::fromStdString(network_.string()), copy));
    QVERIFY(panel->loadNetworkFile(copy));
    QVERIFY(QTest::qWaitFor([&] { return !panel->isBusy(); }, kJobTimeoutMs));
    QTest::keyClick(choice, Qt::Key_Up);  // another style: the copy's entry is left
    QVERIFY(QTest::qWaitFor([&] { return !panel->isBusy() && !panel->resultIsStale() &&
                                         panel->networkName() == choice->currentText(); }, kJobTimeoutMs));
    const QString in_use = panel->networkName();
    {
      QFile damaged(copy);
      QVERIFY(damaged.open(QIODevice::WriteOnly | QIODevice::Truncate));
      damaged.write("not a network");
    }
    choice->setCurrentIndex(choice->findData(QFileInfo(copy).absoluteFilePath()));
    emit choice->activated(choice->currentIndex());
    QVERIFY(panel->resultIsStale());
    QVERIFY(QTest::qWaitFor([&] { return !reports.isEmpty(); }, kJobTimeoutMs));
    QCOMPARE(reports.back(), QStringLiteral("Could not open the style network"));
    QCOMPARE(choice->currentText(), in_use);
    QCOMPARE(panel->networkName(), in_use);
    QVERIFY(!panel->resultIsStale());

    // Before any result, Stylize asked for while the chosen style is read follows the read (no "No
    // style network" report).
    MainWindow second(false);
    second.setErrorReporter([&reports](const QString& title, const QString&) { reports << title; });
    ResultPanel* first_panel = second.resultPanel();
    first_panel->setLookAheadDelay(-1);
    second.show();
    QVERIFY(QTest::qWaitForWindowExposed(&second));
    QCOMPARE(second.openFiles({clip}), 1);
    auto* first_choice = first_panel->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    first_choice->setCurrentIndex(1);
    emit first_choice->activated(1);
    QVERIFY(!first_panel->hasNetwork());  // being read
    const qsizetype reported = reports.size();
    first_panel->stylize();  // (the button itself is enabled once the network is in use)
    QVERIFY(QTest::qWaitFor([&] { return first_panel->result() != nullptr && !first_panel->isBusy(); }, kJobTimeoutMs));
    QCOMPARE(first_panel->networkName(), first_choice->itemText(1));
    QCOMPARE(reports.size(), reported);
  }

  // After a strength change the styles are computed ahead again from their own network output on the
  // clip (only the clean-up runs): the one a switch then shows kept its network output.
  void theLookAheadAfterAnEditRunsOnlyTheCleanUp() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_ahead_again.bvh"));
    MainWindow window(false);
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(0);
    QVERIFY(showStylized(window, clip));
    auto* choice = panel->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    auto* slider = panel->findChild<QSlider*>(QStringLiteral("StrengthSlider"));
    QVERIFY(choice != nullptr && slider != nullptr && choice->currentIndex() + 1 < choice->count());
    const int ahead = std::min(panel->lookAheadStyles(), choice->count() - 1);
    QVERIFY(QTest::qWaitFor([&] { return panel->recentResults().size() == 1 + ahead; }, kJobTimeoutMs));
    const qsizetype looked_ahead = readLogText(log_).count(QStringLiteral("look-ahead: "));
    size_t before = readLiveLog(log_).size();
    slider->setValue(slider->value() - 5);
    QVERIFY(waitForNewResult(panel, before));
    QVERIFY(QTest::qWaitFor([&] { return readLogText(log_).count(QStringLiteral("look-ahead: ")) >= looked_ahead + ahead; },
                            kJobTimeoutMs));
    before = readLiveLog(log_).size();
    choice->setFocus();
    QTest::keyClick(choice, Qt::Key_Down);
    QVERIFY(waitForNewResult(panel, before));
    QVERIFY(readLiveLog(log_).back().remembered);
    QVERIFY2(panel->result()->network_output_kept, "the look-ahead ran the network again after a strength change");
  }

  void paintingAContactReSolvesOnlyWhatItTouches() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_contacts.bvh"));
    MainWindow window(false);
    QVERIFY(showStylized(window, clip));
    ResultPanel* panel = window.resultPanel();

    TrackView* tracks = window.timeline()->trackView();
    QVERIFY(tracks->isVisible());
    const size_t before = readLiveLog(log_).size();
    const int y = tracks->boolTrackRect(0).center().y();
    const auto x = [&](int frame) { return static_cast<int>(tracks->xForFrame(frame)); };
    QTest::mousePress(tracks, Qt::LeftButton, Qt::NoModifier, QPoint(x(420), y));
    for (int frame = 424; frame <= 480; frame += 4) {
      QTest::mouseMove(tracks, QPoint(x(frame), y));
      QTest::qWait(30);
    }
    QTest::mouseRelease(tracks, Qt::LeftButton, Qt::NoModifier, QPoint(x(480), y));
    QVERIFY(QTest::qWaitFor([&] { return !panel->isBusy(); }, kJobTimeoutMs));

    const std::vector<LogEntry> all = readLiveLog(log_);
    std::vector<LogEntry> latencies;
    for (size_t i = before; i < all.size(); ++i) {
      QVERIFY(all[i].change.contains(QStringLiteral("contacts")));
      // The release repeats the stroke's last step: no new inputs, so no result "shown again" for them.
      QVERIFY2(!all[i].remembered, "a stroke's release changed nothing, yet counted as an edit");
      QVERIFY2(all[i].chunks_solved < all[i].chunks,
               qPrintable(QStringLiteral("a late stroke re-solved %1 of %2 chunks").arg(all[i].chunks_solved).arg(all[i].chunks)));
      latencies.push_back(all[i]);
    }
    QVERIFY(!latencies.empty());
    QVERIFY2(lastStatus(log_).startsWith(QStringLiteral("Stylized and cleaned up")), qPrintable(lastStatus(log_)));
    printLatencies("contact stroke, 500 frames at 120 fps", latencies);
  }
};

// The app's own process set-up (app/gui/main.cpp), so that the latencies are the app's.
int main(int argc, char** argv) {
  motionstyle::restartWithHugePages(argv);
  motionstyle::keepLargeAllocationsInHeap();
  motionstyle::SkeletonViewport::installDefaultSurfaceFormat();
  QApplication app(argc, argv);
  app.setAttribute(Qt::AA_Use96Dpi, true);
  LiveTest test;
  return QTest::qExec(&test, argc, argv);
}
#include "test_live.moc"
