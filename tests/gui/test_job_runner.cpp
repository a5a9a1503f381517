// JobRunner (app/gui/job_runner.h), the one way the app runs a long job: invalid use first (a second
// start while busy), then its properties: the completion runs on the GUI thread, posts of a dropped job
// never arrive, cancel() still delivers what the job returns, abandon()/restart() drop it at once, a
// failure arrives once through the one translation (error_text.h), the destructor waits.
#include <QSignalSpy>
#include <QTest>
#include <QThread>
#include <QLabel>
#include <QVBoxLayout>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "common/errors.h"
#include "gui_test_support.h"
#include "busy_indicator.h"
#include "job_runner.h"

using namespace motionstyle;

namespace {

// Spins until the job's cancel flag is set (or 10 s pass), as a core job polls it.
void waitForCancel(const JobRunner::Context& context) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!context.cancelled() && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

}  // namespace

class JobRunnerTest : public QObject {
  Q_OBJECT

 private slots:
  // The panels' busy bar: work shorter than the delay never shows it (a live edit's job), longer work
  // does until it ends; shown or hidden, it keeps its place in the layout.
  void theBusyBarAppearsOnlyForWorkThatOutlastsItsDelay() {
    QWidget panel;
    auto* layout = new QVBoxLayout(&panel);
    auto* bar = new BusyIndicator(&panel, 150);
    auto* below = new QLabel(QStringLiteral("status"), &panel);
    layout->addWidget(bar);
    layout->addWidget(below);
    panel.show();
    QVERIFY(QTest::qWaitForWindowExposed(&panel));
    const int status_y = below->y();
    QVERIFY(!bar->isVisible());
    bar->setBusy(true);
    QTest::qWait(60);
    bar->setBusy(false);  // a short job
    QTest::qWait(250);
    QVERIFY(!bar->isVisible());
    bar->setBusy(true);  // a long one
    QVERIFY(QTest::qWaitFor([&] { return bar->isVisible(); }, 2000));
    QCOMPARE(below->y(), status_y);
    bar->setBusy(false);
    QVERIFY(!bar->isVisible());
    QCOMPARE(below->y(), status_y);
  }

  void aSecondStartWhileBusyIsRefused() {
    JobRunner runner;
    QSignalSpy finished(&runner, &JobRunner::finished);
    QVERIFY(runner.start(QStringLiteral("one"), [](const JobRunner::Context& context) {
      waitForCancel(context);
      return JobRunner::Completion();
    }));
    QVERIFY(runner.isBusy());
    QVERIFY(!runner.start(QStringLiteral("two"), [](const JobRunner::Context&) { return JobRunner::Completion(); }));
    runner.cancel();
    QVERIFY(finished.wait(10000));
    QCOMPARE(finished.front().at(0).toBool(), false);
    QVERIFY(!runner.isBusy());
  }

  void theCompletionRunsOnTheGuiThreadAfterThePosts() {
    JobRunner runner;
    QSignalSpy finished(&runner, &JobRunner::finished);
    QStringList order;
    QThread* completion_thread = nullptr;
    runner.start(QStringLiteral("job"), [&](const JobRunner::Context& context) {
      context.post([&] { order << QStringLiteral("progress"); });
      return JobRunner::Completion([&] {
        order << QStringLiteral("done");
        completion_thread = QThread::currentThread();
      });
    });
    QVERIFY(finished.wait(10000));
    QCOMPARE(finished.front().at(0).toBool(), true);
    QCOMPARE(order, (QStringList{QStringLiteral("progress"), QStringLiteral("done")}));
    QCOMPARE(completion_thread, QThread::currentThread());
  }

  void cancelStillDeliversWhatTheJobReturns() {
    JobRunner runner;
    QSignalSpy finished(&runner, &JobRunner::finished);
    bool delivered = false;
    std::atomic<bool> started{false};
    runner.start(QStringLiteral("training"), [&](const JobRunner::Context& context) {
      started = true;
      waitForCancel(context);  // a training keeps its last epoch's network when cancelled
      return JobRunner::Completion([&] { delivered = true; });
    });
    QTRY_VERIFY(started.load());  // (cancelled before it starts, a job never runs and returns nothing)
    runner.cancel();
    QVERIFY(runner.isCancelling());
    QVERIFY(finished.wait(10000));
    QVERIFY(delivered);
    QCOMPARE(finished.front().at(0).toBool(), false);  // not completed: cancelled
  }

  void restartDropsTheStaleJobAndRunsTheNewest() {
    JobRunner runner;
    QSignalSpy finished(&runner, &JobRunner::finished);
    int stale_posts = 0;
    int stale_completions = 0;
    int newest = 0;
    std::atomic<bool> old_started{false};
    runner.start(QStringLiteral("old"), [&](const JobRunner::Context& context) {
      old_started = true;
      waitForCancel(context);
      context.post([&] { ++stale_posts; });
      return JobRunner::Completion([&] { ++stale_completions; });
    });
    QTRY_VERIFY(old_started.load());
    runner.restart(QStringLiteral("new"), [&](const JobRunner::Context&) {
      return JobRunner::Completion([&] { ++newest; });
    });
    QVERIFY(runner.isBusy());
    QTRY_COMPARE_WITH_TIMEOUT(newest, 1, 10000);
    QTest::qWait(50);
    QCOMPARE(stale_posts, 0);
    QCOMPARE(stale_completions, 0);
    QCOMPARE(finished.size(), 2);  // the drop (false), then the newest (true)
    QCOMPARE(finished.back().at(0).toBool(), true);
  }

  void aFailureArrivesOnceWithItsTranslation() {
    JobRunner runner;
    QSignalSpy failed(&runner, &JobRunner::failed);
    QSignalSpy finished(&runner, &JobRunner::finished);
    runner.start(QStringLiteral("Could not read"), [](const JobRunner::Context&) -> JobRunner::Completion {
      throw InputError("clip.bvh", 12, "a number was expected");
    });
    QVERIFY(finished.wait(10000));
    QCOMPARE(failed.size(), 1);
    QCOMPARE(failed.front().at(0).toString(), QStringLiteral("Could not read"));
    QCOMPARE(failed.front().at(1).toString(), QStringLiteral("clip.bvh:12: a number was expected"));
    runner.start(QStringLiteral("Training"), [](const JobRunner::Context&) -> JobRunner::Completion {
      throw TrainingDiverged("the loss is not finite");
    });
    QVERIFY(finished.wait(10000));
    QCOMPARE(failed.size(), 2);
    QCOMPARE(failed.back().at(0).toString(), QStringLiteral("Training diverged"));  // its own title
  }

  void theDestructorCancelsAndWaits() {
    std::atomic<bool> ended{false};
    {
      JobRunner runner;
      std::atomic<bool> started{false};
      runner.start(QStringLiteral("long"), [&](const JobRunner::Context& context) {
        started = true;
        waitForCancel(context);
        ended = true;
        return JobRunner::Completion();
      });
      QTRY_VERIFY(started.load());
    }
    QVERIFY(ended.load());  // joined, not left running
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(JobRunnerTest)
#include "test_job_runner.moc"
