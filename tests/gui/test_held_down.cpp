// An animator's path through a clean-up warning: a contact holds a toe down where the style lifts it;
// the Result panel says so and links the frame; the animator goes there and ends the foot's contact on
// its track (what a drag over it does); the clip is cleaned again, the warning is gone and the toe
// follows the style there (ik/cleanup.h, CleanupOptions::held_down_warning_cm). The shipped masculine
// network on the zombie sample, the right toe 5.3 cm under the style's at frame 682: one of the few
// such warnings left (3 of 847 eval pairs), just over the 5 cm threshold; a change that ends it needs
// another case here. Where the style lifts one joint of a foot while the other stays down, the
// clean-up rolls it up on the other instead (cleanup_locks.cpp), with no warning: youthful's left toe
// and proud's left heel on the CMU sample, both named here before.
#include <QLabel>
#include <QSignalSpy>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "common/resource_paths.h"
#include "contact_tracks.h"
#include "gui_test_support.h"
#include "ik/cleanup.h"
#include "ik/metrics.h"
#include "main_window.h"
#include "result_panel.h"
#include "style/stylize_cleanup_job.h"
#include "timeline_widget.h"
#include "track_view.h"

using namespace motionstyle;

namespace {

constexpr const char* kHeldRightToe = "held down by its contact: right toe";
constexpr const char* kHeldLeftToe = "held down by its contact: left toe";
constexpr const char* kHeldHeel = "heel under the style's lift";

// The first warning that starts with `start`, or nullptr.
const CleanupWarning* warningStarting(const std::vector<CleanupWarning>& warnings, const char* start) {
  for (const CleanupWarning& warning : warnings)
    if (warning.text.rfind(start, 0) == 0) return &warning;
  return nullptr;
}

// Opens the sample `sample` (resources/samples) in `window`, loads the shipped network `name` and
// stylizes; the panel's result.
const style::StylizeCleanupResult* stylizeSample(MainWindow& window, const char* name, QSignalSpy& ended,
                                                 const char* sample = "cmu_131_01_walk.bvh") {
  const auto resources = resourceDirectory();
  if (!resources) return nullptr;
  const auto network = shippedNetworkFile(*resources, name);
  const std::filesystem::path clip = *resources / "samples" / sample;
  if (!network || window.openFiles({QString::fromStdString(clip.string())}) != 1) return nullptr;
  ResultPanel* panel = window.resultPanel();
  if (!panel->loadNetworkFile(QString::fromStdString(network->string()))) return nullptr;
  panel->stylize();
  if (!test::waitForJobs(ended)) return nullptr;
  return panel->result();
}

// How far the cleaned right toe stands under the style's (the network's output) at the clip's `frame`,
// cm along the file's up axis.
double toeUnderTheStyle(const MainWindow& window, const style::StylizeCleanupResult& result, int frame) {
  const LoadedClip& clip = window.clip(0);
  const style::StylizedClip& style = result.stylized;
  const int at = std::min(static_cast<int>(std::lround(frame * style.fps / clip.fps())), style.frameCount() - 1);
  const Eigen::Vector3d up = style.anchor.convention.fileUp();
  const int toe = index(CanonicalJoint::RightToe);
  const Eigen::Vector3d target = style.world_positions.block<1, 3>(at, 3 * toe).transpose();
  const Eigen::MatrixXd cleaned = worldPositions(result.cleaned);
  const Eigen::Vector3d placed = cleaned.block<1, 3>(frame, 3 * (*clip.mapping)[CanonicalJoint::RightToe]).transpose();
  return up.dot(target - placed) * style.anchor.convention.cm_per_unit;
}

}  // namespace

class HeldDownTest : public QObject {
  Q_OBJECT

 private slots:
  void aWarnedContactFollowsTheStyleOnceItIsEnded() {
    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + message)); });
    ResultPanel* panel = window.resultPanel();
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    QVERIFY2(stylizeSample(window, "masculine", ended, "zombie_walk.bvh") != nullptr,
             "the repository's resources/ (masculine, the zombie sample) did not load and stylize");

    // The panel names the held toe and links its first frame.
    const CleanupWarning* held = warningStarting(panel->result()->report.warnings, kHeldRightToe);
    QVERIFY2(held != nullptr, "no warning of a right toe held under the style's lift");
    const int first = held->first_frame, last = held->last_frame;
    QVERIFY(first >= 0 && last >= first && last < window.clip(0).frameCount());
    const std::string named = held->text;
    const double held_before = toeUnderTheStyle(window, *panel->result(), first);
    auto* label = panel->findChild<QLabel*>(QStringLiteral("CleanupWarnings"));
    QVERIFY(label != nullptr);
    QVERIFY2(label->text().contains(QString::fromUtf8(kHeldRightToe)), qPrintable(label->text()));
    const size_t at = named.find(" at frame"), until = named.find(" (end");
    QVERIFY(at != std::string::npos && until != std::string::npos && until > at);
    const QString frames = QString::fromStdString(named.substr(at, until - at));  // " at frame a" or " at frames a-b"
    QVERIFY2(label->text().contains(frames), qPrintable(label->text()));
    QVERIFY2(label->text().contains(QStringLiteral("<a href=\"%1\"").arg(first)), qPrintable(label->text()));
    emit label->linkActivated(QString::number(first));
    QCOMPARE(window.timeline()->frame(), first);

    // The animator ends the right foot's contact over those frames, as a drag over its track does;
    // the clip is cleaned again with it, and those frames are no longer named.
    QVERIFY(window.clip(0).effectiveContacts().col(3).segment(first, last - first + 1).sum() > 0);
    emit window.timeline()->trackView()->trackEdited(ContactTrackController::kRightFootTrack, first, last, false);
    QVERIFY((window.clip(0).effectiveContacts().col(3).segment(first, last - first + 1).array() == 0).all());
    panel->stylize();
    QVERIFY(test::waitForJobs(ended, 2));
    QVERIFY(panel->result() != nullptr);
    for (const CleanupWarning& warning : panel->result()->report.warnings)
      QVERIFY2(warning.text != named && !(warning.text.rfind(kHeldRightToe, 0) == 0 && warning.first_frame <= last &&
                                          warning.last_frame >= first),
               warning.text.c_str());
    QVERIFY2(!label->text().contains(frames), qPrintable(label->text()));
    const double held_after = toeUnderTheStyle(window, *panel->result(), first);
    qInfo("right toe under the style's at frame %d: %.2f -> %.2f cm (its contact ended over frames %d-%d)", first,
          held_before, held_after, first, last);
    QVERIFY2(held_before > 5.0 && held_after < held_before - 2.0,
             qPrintable(QStringLiteral("right toe under the style's by %1 -> %2 cm").arg(held_before).arg(held_after)));
  }

  // The youthful network lands the sample's left toe after its heel (and lifts it first) while the
  // heel stays down: the toe rolls up on the heel, no toe is named as held down (it was, 5.0-5.2 cm
  // under the style's lift, until the thirty-eighth session), and the feet do not slide for it.
  void aToeTheStyleLiftsRollsUpOnItsHeel() {
    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + message)); });
    QSignalSpy ended(window.resultPanel(), &ResultPanel::jobEnded);
    const style::StylizeCleanupResult* result = stylizeSample(window, "youthful", ended);
    QVERIFY2(result != nullptr, "the repository's resources/ (youthful, the CMU sample) did not load and stylize");
    QVERIFY2(warningStarting(result->report.warnings, kHeldLeftToe) == nullptr, "a left toe is still held down");
    QVERIFY2(result->report.lifted_contacts.col(1).sum() > 0, "the left toe is never lifted with the style");
    // Where the clean-up lifts a whole foot with the style (its quicker toe-offs), its track is drawn
    // raised, only over the foot's contacts.
    TrackView* tracks = window.timeline()->trackView();
    int raised = 0;
    for (int foot : {ContactTrackController::kLeftFootTrack, ContactTrackController::kRightFootTrack}) {
      const std::vector<bool>& lifted = tracks->liftedFrames(foot);
      QCOMPARE(static_cast<int>(lifted.size()), window.clip(0).frameCount());
      for (size_t f = 0; f < lifted.size(); ++f) {
        raised += lifted[f];
        QVERIFY2(!lifted[f] || tracks->boolValues(foot)[f], qPrintable(QString::number(f)));
      }
    }
    qInfo("youthful on the CMU sample: %d foot-track frames drawn lifted", raised);
    QVERIFY(raised > 0);
    window.resize(1400, 900);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QVERIFY(window.saveScreenshot(test::screenshotPath(QStringLiteral("held_down_lifted"))));
    const ClipMetrics& cleaned = result->cleaned_metrics;
    qInfo("youthful on the CMU sample: worst residual %.2f cm, skate %.3f cm/s", cleaned.residual_max_cm,
          cleaned.foot_skate_cm_s);
    QVERIFY2(cleaned.foot_skate_cm_s <= 0.5, qPrintable(QString::number(cleaned.foot_skate_cm_s)));
    // Held down, the worst residual was 5.93 cm (the thirty-seventh session's test).
    QVERIFY2(cleaned.residual_max_cm < 5.93, qPrintable(QString::number(cleaned.residual_max_cm)));
  }

  // The proud network lifts the sample's left heel while its toe stays down: the heel rolls up on the
  // toe, no heel is named as held down, the feet do not slide for it, and the leg follows the style
  // closer than with the heel held down.
  void aHeelTheStyleLiftsRollsUpOnItsToe() {
    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + message)); });
    QSignalSpy ended(window.resultPanel(), &ResultPanel::jobEnded);
    const style::StylizeCleanupResult* result = stylizeSample(window, "proud", ended);
    QVERIFY2(result != nullptr, "the repository's resources/ (proud, the CMU sample) did not load and stylize");
    for (const CleanupWarning& warning : result->report.warnings)
      QVERIFY2(warning.text.find(kHeldHeel) == std::string::npos, warning.text.c_str());
    const ClipMetrics& cleaned = result->cleaned_metrics;
    qInfo("proud on the CMU sample: worst residual %.2f cm, skate %.3f cm/s", cleaned.residual_max_cm,
          cleaned.foot_skate_cm_s);
    QVERIFY2(cleaned.foot_skate_cm_s <= 0.5, qPrintable(QString::number(cleaned.foot_skate_cm_s)));
    // Held down, the heel was 5.64 cm from the style's at worst (the thirty-sixth session's test).
    QVERIFY2(cleaned.residual_max_cm < 5.64, qPrintable(QString::number(cleaned.residual_max_cm)));
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(HeldDownTest)
#include "test_held_down.moc"
