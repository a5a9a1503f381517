// The Result panel's look-ahead as a user meets it, in the real window under Xvfb (the shipped
// networks, clips written from the fixtures): while the user looks at a clip or a result, the chosen
// style and those near it in the chooser are computed ahead, so Stylize and a switch show a result
// without a job; before any clip the shipped networks are read; a drag let go starts it at once; a
// result it is computing is waited for; any change or job of the Style networks panel drops or holds
// it. Latencies come from the app's own log and are printed, not asserted.
#include <QComboBox>
#include <QElapsedTimer>
#include <QFile>
#include <QPushButton>
#include <QSignalSpy>

#include "live_test_support.h"
#include "network_panel.h"

using namespace motionstyle;
using namespace motionstyle::live_test;

class LookAheadTest : public LiveTestBase {
  Q_OBJECT

 private slots:
  void initTestCase() { initLogAndNetwork(); }
  void cleanupTestCase() { app_log::setFile(QString()); }

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

  // A key pressed and let go on the slider is a whole edit: its result, which comes with the hand away,
  // starts the look-ahead at once. A key held down (the slider's arrow repeating) is a drag: its
  // results wait for the rest, and the key's release starts it.
  void aKeyLetGoStartsTheLookAheadAndAKeyHeldWaits() {
    const QString clip = writeClip(scratch_, QStringLiteral("cmu_131_01.bvh"), QStringLiteral("clip_keys.bvh"));
    MainWindow window(false);
    QVERIFY(showStylized(window, clip));
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(2 * kJobTimeoutMs);  // the rest never ends within the test
    auto* slider = panel->findChild<QSlider*>(QStringLiteral("StrengthSlider"));
    QVERIFY(slider != nullptr);
    slider->setFocus();
    const QString computed = QStringLiteral("computed for the current inputs");
    const auto settled = [&] { return !panel->isBusy() && !panel->resultIsStale(); };

    qsizetype before = readLogText(log_).count(computed);
    QTest::keyClick(slider, Qt::Key_Left);
    QVERIFY(QTest::qWaitFor(settled, kJobTimeoutMs));
    QVERIFY(!window.viewport()->reducedResolution());
    QVERIFY2(QTest::qWaitFor([&] { return readLogText(log_).count(computed) > before; }, kJobTimeoutMs),
             "a key pressed and let go: the look-ahead waited for the rest");

    QTest::keyPress(slider, Qt::Key_Left);  // held: no release yet
    QVERIFY(QTest::qWaitFor(settled, kJobTimeoutMs));
    QVERIFY(window.viewport()->reducedResolution());  // its result came with the hand on the control
    QTest::qWait(300);
    before = readLogText(log_).count(computed);
    QTest::qWait(300);
    QCOMPARE(readLogText(log_).count(computed), before);  // nothing computed ahead while it is held
    QTest::keyRelease(slider, Qt::Key_Left);
    QVERIFY(!window.viewport()->reducedResolution());
    QVERIFY2(QTest::qWaitFor([&] { return readLogText(log_).count(computed) > before; }, kJobTimeoutMs),
             "the key let go: the look-ahead waited for the rest");
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
};

MOTIONSTYLE_LIVE_TEST_MAIN(LookAheadTest)
#include "test_look_ahead.moc"
