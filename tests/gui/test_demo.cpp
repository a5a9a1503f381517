// Help > Open Demo as a new user meets it: the two samples and the shipped elderly network, one click
// to a result whose feet the clean-up holds, a hatched stance a drag holds; and the question it asks
// before it changes a user's own clips and roles.
#include <QComboBox>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QTemporaryDir>

#include <algorithm>
#include <vector>

#include "common/resource_paths.h"
#include "contact_tracks.h"
#include "demo_scene.h"
#include "features/representation.h"
#include "gui_test_support.h"
#include "main_window.h"
#include "nn/network_file.h"
#include "result_panel.h"
#include "sliding_stance.h"
#include "style/stylizer.h"
#include "timeline_widget.h"
#include "track_view.h"

using namespace motionstyle;

namespace {

using test::Report;

}  // namespace

class DemoTest : public QObject {
  Q_OBJECT

  QTemporaryDir settings_dir_;

 private slots:
  void initTestCase() {
    QVERIFY(settings_dir_.isValid());
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settings_dir_.path());
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, settings_dir_.path());
    QCoreApplication::setOrganizationName(QStringLiteral("MotionStyleTests"));
    QCoreApplication::setApplicationName(QStringLiteral("test_gui_demo"));
  }

  // Issue 14: Open Demo asks before it changes the user's roles and result, and never lists a clip twice.
  void openDemoAsksFirstAndReusesOpenSamples() {
    if (!resourceDirectory()) QSKIP("no resources directory next to this build");
    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + message)); });
    int asked = 0;
    bool answer = false;
    QString question;
    window.setConfirmer([&](const QString&, const QString& text) {
      ++asked;
      question = text;
      return answer;
    });
    QVERIFY(window.openDemoScene());  // nothing of the user's yet: no question
    QCOMPARE(asked, 0);
    QCOMPARE(window.clipCount(), 2);

    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("zombie.bvh"))}), 1);
    window.setContentClip(2);
    QVERIFY(!window.openDemoScene());  // declined: nothing changes
    QCOMPARE(asked, 1);
    QVERIFY(question.contains(QStringLiteral("lose their roles")));
    QCOMPARE(window.contentClip(), 2);
    QCOMPARE(window.clipCount(), 3);

    answer = true;
    QVERIFY(window.openDemoScene());
    QCOMPARE(asked, 2);
    QCOMPARE(window.clipCount(), 3);  // the samples already open were reused
    QCOMPARE(window.clip(window.contentClip()).name, QStringLiteral("cmu_131_01_walk.bvh"));
    QCOMPARE(window.clip(window.styleClip()).name, QStringLiteral("zombie_walk.bvh"));
  }

  void demoLoadsTheSamplesAndTheBundledNetworkWhenPresent() {
    const auto resources = resourceDirectory();
    if (!resources) QSKIP("no resources directory next to this build");
    MainWindow window(false);
    std::vector<Report> reports;
    window.setErrorReporter([&](const QString& title, const QString& message) { reports.push_back({title, message}); });
    const DemoOutcome outcome = openDemo(window, *window.resultPanel());
    QVERIFY2(outcome.clips_loaded, qPrintable(outcome.message));
    QCOMPARE(window.clipCount(), 2);
    QCOMPARE(window.clip(window.contentClip()).name, QStringLiteral("cmu_131_01_walk.bvh"));
    QCOMPARE(window.clip(window.styleClip()).name, QStringLiteral("zombie_walk.bvh"));
    const bool bundled = shippedNetworkFile(*resources, kDemoNetwork).has_value();
    QCOMPARE(outcome.network_loaded, bundled);
    QCOMPARE(window.resultPanel()->hasNetwork(), bundled);
    QVERIFY(!outcome.message.isEmpty());
    QVERIFY(reports.empty());
    if (!bundled) return;
    // The network goes by its label in the style list ("Elderly"), as one chosen there or computed ahead.
    const auto* choice = window.resultPanel()->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    QVERIFY(choice != nullptr);
    QCOMPARE(window.resultPanel()->networkName(), choice->currentText());
    // One click gives a result with the shipped network.
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QSignalSpy ended(window.resultPanel(), &ResultPanel::jobEnded);
    QTest::mouseClick(window.resultPanel()->findChild<QPushButton*>(QStringLiteral("StylizeButton")), Qt::LeftButton);
    QVERIFY(test::waitForJobs(ended));
    QVERIFY2(window.resultPanel()->result() != nullptr, reports.empty() ? "" : qPrintable(reports.back().message));
    const ClipMetrics& cleaned = window.resultPanel()->result()->cleaned_metrics;
    qInfo("demo with the bundled network: skate %.2f -> %.2f cm/s, residual %.2f cm",
          window.resultPanel()->result()->raw_metrics.foot_skate_cm_s, cleaned.foot_skate_cm_s, cleaned.residual_mean_cm);
    QVERIFY(cleaned.foot_skate_cm_s < 0.2 * window.resultPanel()->result()->raw_metrics.foot_skate_cm_s);
    // The stylizer plants the content's contacts (contact_projection.h), so the clean-up holds every one:
    // nothing is hatched on the foot tracks.
    TrackView* tracks = window.timeline()->trackView();
    const auto firstUnheld = [&](int& track, int& first, int& last) {
      track = first = last = -1;
      for (int t : {ContactTrackController::kLeftFootTrack, ContactTrackController::kRightFootTrack}) {
        const std::vector<bool>& unheld = tracks->unheldFrames(t);
        const auto begin = std::find(unheld.begin(), unheld.end(), true);
        if (begin == unheld.end()) continue;
        track = t;
        first = static_cast<int>(begin - unheld.begin());
        last = static_cast<int>(std::find(begin, unheld.end(), false) - unheld.begin()) - 1;
        return;
      }
    };
    int track = -1, first = -1, last = -1;
    firstUnheld(track, first, last);
    QVERIFY2(track < 0, qPrintable(QStringLiteral("frames %1-%2 are not held").arg(first).arg(last)));
    QVERIFY(cleaned.foot_skate_cm_s < 0.5);
    // A clip stylized elsewhere, whose feet were not planted (this network without its contact
    // projection) and whose left foot slides 50 cm through its first long stance and swings back after
    // it (its ends 25 cm from its middle: more than a lock holds, kLockableSpreadCm; 30 cm, 15 cm from
    // it, leaned on the network's own slide and stopped being enough when that changed), is cleaned as
    // given: that stance is hatched, and dragging over it holds the foot there.
    const MotionFeatures features =
        extractFeatures(window.clip(window.contentClip()).motion, *window.clip(window.contentClip()).mapping);
    style::ContactProjection unplanted;
    unplanted.iterations = 0;
    const style::Stylizer elsewhere(nn::loadStyleModel(*shippedNetworkFile(*resources, kDemoNetwork)), "elsewhere", {},
                                    unplanted);
    style::StylizedClip sliding = elsewhere.stylize(features, 1.0);
    QVERIFY(test::slideTheLeftFootThroughAStance(sliding, 50.0));
    window.resultPanel()->setStylizedClip(sliding, QStringLiteral("stylized elsewhere"));
    QVERIFY(test::waitForJobs(ended, 2));
    QVERIFY(window.resultPanel()->result() != nullptr);
    firstUnheld(track, first, last);
    QVERIFY2(track >= 0, "the unplanted clip's result holds every contact: the hatch has nothing to show");
    const double skate_before = window.resultPanel()->result()->cleaned_metrics.foot_skate_cm_s;
    const int y = tracks->boolTrackRect(track).center().y();
    QTest::mousePress(tracks, Qt::LeftButton, Qt::NoModifier, QPoint(static_cast<int>(tracks->xForFrame(first)), y));
    QTest::mouseMove(tracks, QPoint(static_cast<int>(tracks->xForFrame(last)), y));
    QTest::mouseRelease(tracks, Qt::LeftButton, Qt::NoModifier, QPoint(static_cast<int>(tracks->xForFrame(last)), y));
    QVERIFY(QTest::qWaitFor([&] { return !window.resultPanel()->isBusy() && !window.resultPanel()->resultIsStale(); }, 20000));
    for (int f = first; f <= last; ++f) QVERIFY2(!tracks->unheldFrames(track)[static_cast<size_t>(f)], qPrintable(QString::number(f)));
    QVERIFY(window.resultPanel()->result()->cleaned_metrics.foot_skate_cm_s < skate_before);
    window.timeline()->setFrame(200);
    QTest::qWait(50);
    QVERIFY(window.saveScreenshot(test::screenshotPath(QStringLiteral("demo_result"))));
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(DemoTest)
#include "test_demo.moc"
