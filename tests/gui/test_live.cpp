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
#include <QSignalSpy>

#include "live_test_support.h"
#include "timeline_widget.h"
#include "track_view.h"

using namespace motionstyle;
using namespace motionstyle::live_test;

class LiveTest : public LiveTestBase {
  Q_OBJECT

 private slots:
  void initTestCase() { initLogAndNetwork(); }
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

MOTIONSTYLE_LIVE_TEST_MAIN(LiveTest)
#include "test_live.moc"
