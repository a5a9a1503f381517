// An animator's path through a clean-up warning: the style lifts a heel while the content's contact
// holds it down; the Result panel says so and links the frames; the animator goes there and ends the
// foot's contact on its track (what a drag over it does); the clip is cleaned again, the warning is
// gone and the worst residual is lower. The shipped proud network on the CMU sample (ik/cleanup.h,
// CleanupOptions::held_down_warning_cm).
#include <QLabel>
#include <QSignalSpy>

#include <filesystem>
#include <string>
#include <vector>

#include "common/resource_paths.h"
#include "contact_tracks.h"
#include "gui_test_support.h"
#include "ik/cleanup.h"
#include "main_window.h"
#include "result_panel.h"
#include "timeline_widget.h"
#include "track_view.h"

using namespace motionstyle;

namespace {

constexpr const char* kHeldLeftHeel = "held down by its contact: left heel";

// The first warning of a left heel held under the style's lift, or nullptr.
const CleanupWarning* heldLeftHeel(const std::vector<CleanupWarning>& warnings) {
  for (const CleanupWarning& warning : warnings)
    if (warning.text.rfind(kHeldLeftHeel, 0) == 0) return &warning;
  return nullptr;
}

}  // namespace

class HeldDownTest : public QObject {
  Q_OBJECT

 private slots:
  void aWarnedHeelFollowsTheStyleOnceItsContactIsEnded() {
    const auto resources = resourceDirectory();
    QVERIFY2(resources.has_value(), "the repository's resources/ (shipped networks, samples) were not found");
    const auto proud = shippedNetworkFile(*resources, "proud");
    QVERIFY(proud.has_value());
    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + message)); });
    const std::filesystem::path sample = *resources / "samples" / "cmu_131_01_walk.bvh";
    QCOMPARE(window.openFiles({QString::fromStdString(sample.string())}), 1);
    ResultPanel* panel = window.resultPanel();
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(proud->string())));
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    panel->stylize();
    QVERIFY(test::waitForJobs(ended));
    QVERIFY(panel->result() != nullptr);

    // The panel names the held heel and links its first frame (the clip's own 120 fps).
    const CleanupWarning* held = heldLeftHeel(panel->result()->report.warnings);
    QVERIFY2(held != nullptr, "no warning of a left heel held under the style's lift");
    const int first = held->first_frame, last = held->last_frame;
    QVERIFY(first >= 0 && last >= first && last < window.clip(0).frameCount());
    const double worst_before = panel->result()->cleaned_metrics.residual_max_cm;
    auto* label = panel->findChild<QLabel*>(QStringLiteral("CleanupWarnings"));
    QVERIFY(label != nullptr);
    QVERIFY2(label->text().contains(QString::fromUtf8(kHeldLeftHeel)), qPrintable(label->text()));
    QVERIFY2(label->text().contains(QStringLiteral("<a href=\"%1\"").arg(first)), qPrintable(label->text()));
    emit label->linkActivated(QString::number(first));
    QCOMPARE(window.timeline()->frame(), first);

    // The animator ends the left foot's contact over those frames, as a drag over its track does;
    // the clip is cleaned again with it.
    QVERIFY(window.clip(0).effectiveContacts().col(0).segment(first, last - first + 1).sum() > 0);
    emit window.timeline()->trackView()->trackEdited(ContactTrackController::kLeftFootTrack, first, last, false);
    QVERIFY((window.clip(0).effectiveContacts().col(0).segment(first, last - first + 1).array() == 0).all());
    panel->stylize();
    QVERIFY(test::waitForJobs(ended, 2));
    QVERIFY(panel->result() != nullptr);
    QVERIFY2(heldLeftHeel(panel->result()->report.warnings) == nullptr, qPrintable(label->text()));
    QVERIFY2(!label->text().contains(QString::fromUtf8(kHeldLeftHeel)), qPrintable(label->text()));
    const double worst_after = panel->result()->cleaned_metrics.residual_max_cm;
    qInfo("worst residual %.2f -> %.2f cm (left heel's contact ended over frames %d-%d)", worst_before, worst_after,
          first, last);
    QVERIFY2(worst_after < worst_before,
             qPrintable(QStringLiteral("worst residual %1 -> %2 cm").arg(worst_before).arg(worst_after)));
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(HeldDownTest)
#include "test_held_down.moc"
