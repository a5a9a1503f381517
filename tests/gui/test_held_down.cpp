// An animator's path through a clean-up warning: a contact holds a toe down where the style lifts it;
// the Result panel says so and links the frame; the animator goes there and clicks the warning's fix,
// "End it" after its advice, which ends the foot's contact on its track (what a drag over it does);
// the clip is cleaned again at once, the warning is gone and the toe follows the style there
// (ik/cleanup.h, CleanupOptions::held_down_warning_cm). The shipped elderly
// network on the CMU sample, the left toe 6.4 cm under the style's at frames 136-142: one of the few
// such warnings left (3 of 847 eval pairs, 5.3-6.4 cm); a change that ends it needs another case here
// (it was masculine on the zombie until the refinement aimed at the clip's own kind, locomotion_kind.h,
// then proud's left toe until the refinement ran to convergence). Where the style lifts one joint of
// a foot while the other stays down, the clean-up rolls it up on the other instead (cleanup_locks.cpp),
// with no warning: youthful's left toe and proud's left heel on the CMU sample, both named here before.
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

// The heights of `joint` in the style (the network's output) and in the cleaned clip (`cleaned`: its
// worldPositions) at the clip's `frame`, cm along the file's up axis.
struct Heights {
  double style = 0.0, cleaned = 0.0;
  double underTheStyle() const { return style - cleaned; }
};
Heights heightsAt(const MainWindow& window, const style::StylizeCleanupResult& result, const Eigen::MatrixXd& cleaned,
                  int frame, CanonicalJoint joint) {
  const LoadedClip& clip = window.clip(0);
  const style::StylizedClip& style = result.stylized;
  const int at = std::min(static_cast<int>(std::lround(frame * style.fps / clip.fps())), style.frameCount() - 1);
  const Eigen::Vector3d up = style.anchor.convention.fileUp();
  const double cm = style.anchor.convention.cm_per_unit;
  return {up.dot(style.world_positions.block<1, 3>(at, 3 * index(joint)).transpose()) * cm,
          up.dot(cleaned.block<1, 3>(frame, 3 * (*clip.mapping)[joint]).transpose()) * cm};
}

// How far the cleaned `joint` stands under the style's at the clip's `frame`, cm.
double underTheStyle(const MainWindow& window, const style::StylizeCleanupResult& result, int frame, CanonicalJoint joint) {
  return heightsAt(window, result, worldPositions(result.cleaned), frame, joint).underTheStyle();
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
    QVERIFY2(stylizeSample(window, "elderly", ended) != nullptr,
             "the repository's resources/ (elderly, the CMU sample) did not load and stylize");

    // The status says which of the style's clips the refinement aimed at: the sample walks.
    QVERIFY2(test::statusLine(window).contains(QStringLiteral("Aimed at the style's walk (read from the clip).")),
             qPrintable(test::statusLine(window)));

    // The panel names the held toe and links its first frame.
    const CleanupWarning* held = warningStarting(panel->result()->report.warnings, kHeldLeftToe);
    QVERIFY2(held != nullptr, "no warning of a left toe held under the style's lift");
    const int first = held->first_frame, last = held->last_frame;
    QVERIFY(first >= 0 && last >= first && last < window.clip(0).frameCount());
    const std::string named = held->text;
    const double held_before = underTheStyle(window, *panel->result(), first, CanonicalJoint::LeftToe);
    auto* label = panel->findChild<QLabel*>(QStringLiteral("CleanupWarnings"));
    QVERIFY(label != nullptr);
    QVERIFY2(label->text().contains(QString::fromUtf8(kHeldLeftToe)), qPrintable(label->text()));
    const size_t at = named.find(" at frame"), until = named.find(" (end");
    QVERIFY(at != std::string::npos && until != std::string::npos && until > at);
    const QString frames = QString::fromStdString(named.substr(at, until - at));  // " at frame a" or " at frames a-b"
    QVERIFY2(label->text().contains(frames), qPrintable(label->text()));
    QVERIFY2(label->text().contains(QStringLiteral("<a href=\"%1\"").arg(first)), qPrintable(label->text()));
    emit label->linkActivated(QString::number(first));
    QCOMPARE(window.timeline()->frame(), first);

    // The warning offers its fix: the animator clicks "End it". The left foot's contact
    // ends over those frames on its track (as a drag over it would), the timeline shows the first, the
    // clip is cleaned again at once (a live edit), and those frames are no longer named.
    QVERIFY(window.clip(0).effectiveContacts().col(1).segment(first, last - first + 1).sum() > 0);
    const QString fix = QStringLiteral("end:%1:%2:%3").arg(static_cast<int>(ContactLabel::LeftToe)).arg(first).arg(last);
    QVERIFY2(label->text().contains(QStringLiteral("<a href=\"%1\">").arg(fix)), qPrintable(label->text()));
    QVERIFY2(label->text().contains(QStringLiteral(">End it<")), qPrintable(label->text()));
    window.timeline()->setFrame(0);
    emit label->linkActivated(fix);
    QCOMPARE(window.timeline()->frame(), first);
    for (const int foot_label : {static_cast<int>(ContactLabel::LeftHeel), static_cast<int>(ContactLabel::LeftToe)})
      QVERIFY((window.clip(0).effectiveContacts().col(foot_label).segment(first, last - first + 1).array() == 0).all());
    QVERIFY(window.clip(0).effectiveContacts().col(1).segment(0, first).sum() > 0);  // only there
    QVERIFY(test::waitForJobs(ended, 2));
    QTRY_VERIFY_WITH_TIMEOUT(!panel->isBusy(), 60000);
    QVERIFY(panel->result() != nullptr);
    for (const CleanupWarning& warning : panel->result()->report.warnings)
      QVERIFY2(warning.text != named && !(warning.text.rfind(kHeldLeftToe, 0) == 0 && warning.first_frame <= last &&
                                          warning.last_frame >= first),
               warning.text.c_str());
    QVERIFY2(!label->text().contains(frames), qPrintable(label->text()));
    const double held_after = underTheStyle(window, *panel->result(), first, CanonicalJoint::LeftToe);
    qInfo("left toe under the style's at frame %d: %.2f -> %.2f cm (its contact ended over frames %d-%d)", first,
          held_before, held_after, first, last);
    QVERIFY2(held_before > 5.0 && held_after < held_before - 2.0,
             qPrintable(QStringLiteral("left toe under the style's by %1 -> %2 cm").arg(held_before).arg(held_after)));
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
  // toe, no heel is named as held down, the feet do not slide for it, and the heel follows the style
  // closer than it would held down (until the refinement aimed at the clip's kind this read the whole
  // clip's worst residual, 5.64 cm held down; that is now the toe the first test ends the contact of).
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
    // Over the frames it rolls, the heel rises with the style's: held down, it would stay at the height
    // it had where the roll starts.
    const Eigen::MatrixXi& lifted = result->report.lifted_contacts;
    const LoadedClip& clip = window.clip(0);
    const Eigen::MatrixXd placed = worldPositions(result->cleaned);
    double style_rise = 0.0, cleaned_rise = 0.0;
    Heights start;
    int rolled = 0;
    for (int f = 0; f < lifted.rows(); ++f) {
      const int frame = std::min(static_cast<int>(std::lround(f * clip.fps() / result->cleanup_fps)), clip.frameCount() - 1);
      if (lifted(f, static_cast<int>(ContactLabel::LeftHeel)) == 0) continue;
      const Heights now = heightsAt(window, *result, placed, frame, CanonicalJoint::LeftAnkle);
      if (f == 0 || lifted(f - 1, static_cast<int>(ContactLabel::LeftHeel)) == 0) start = now;
      ++rolled;
      if (now.style - start.style > style_rise) {
        style_rise = now.style - start.style;
        cleaned_rise = now.cleaned - start.cleaned;
      }
    }
    qInfo("proud on the CMU sample: left heel rolled on %d frames; where the style raises it most over a roll "
          "(%.2f cm), the cleaned heel rises %.2f cm", rolled, style_rise, cleaned_rise);
    QVERIFY2(rolled > 0 && style_rise > 2.0, "the left heel is not lifted with the style");
    QVERIFY2(cleaned_rise > 0.5 * style_rise, qPrintable(QString::number(cleaned_rise)));
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(HeldDownTest)
#include "test_held_down.moc"
