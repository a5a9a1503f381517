// The Result panel in the real main window: a tiny style network made here (random weights, fixture
// statistics) stylizes the CMU fixture, the IK clean-up runs in the worker thread, the metrics table
// fills, the output figures appear, and the export round-trips through the BVH reader. Bad input
// first: corrupt clips and networks, nothing to stylize or export, an existing export target.
#include <QComboBox>
#include <QFile>
#include <QLabel>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTemporaryDir>
#include <QTreeWidget>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "common/resource_paths.h"
#include "contact_tracks.h"
#include "demo_scene.h"
#include "features/feature_statistics.h"
#include "features/representation.h"
#include "gui_test_support.h"
#include "tiny_style_network.h"
#include "ik/cleanup.h"
#include "ik/contact_file.h"
#include "main_window.h"
#include "mapping/canonical_joints.h"
#include "network_panel.h"
#include "network_list.h"
#include "mapping/mapping_file.h"
#include "motion/kinematics.h"
#include "nn/network_file.h"
#include "result_metrics_view.h"
#include "result_panel.h"
#include "style/motion_dataset.h"
#include "style/stylizer.h"
#include "style/training.h"
#include "timeline_widget.h"
#include "track_view.h"

using namespace motionstyle;

namespace {

using test::Report;

// An untrained but valid tiny style network (16 hidden units, width 5) with the fixtures' statistics.
std::filesystem::path writeTinyNetwork(const QTemporaryDir& dir, const QString& name = QStringLiteral("tiny_style"),
                                       unsigned seed = 5) {
  return test::saveInto(dir, name, test::tinyStyleModel(seed));
}

QString copyInto(const QTemporaryDir& dir, const QString& source, const QString& name) {
  const QString target = dir.filePath(name);
  QFile::remove(target);
  return QFile::copy(source, target) ? target : QString();
}

double cellValue(const QTableWidget* table, int row, int column) {
  bool ok = false;
  const double value = table->item(row, column)->text().toDouble(&ok);
  return ok ? value : std::nan("");
}

}  // namespace

class ResultTest : public QObject {
  Q_OBJECT

  QTemporaryDir settings_dir_;
  QTemporaryDir scratch_;
  std::filesystem::path network_;

 private slots:
  void initTestCase() {
    QVERIFY(settings_dir_.isValid() && scratch_.isValid());
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settings_dir_.path());
    QSettings::setPath(QSettings::IniFormat, QSettings::UserScope, settings_dir_.path());
    QCoreApplication::setOrganizationName(QStringLiteral("MotionStyleTests"));
    QCoreApplication::setApplicationName(QStringLiteral("test_gui_result"));
    network_ = writeTinyNetwork(scratch_);
  }

  void corruptInputsGiveErrorDialogsNotCrashes() {
    MainWindow window(/*persist_settings=*/false);
    std::vector<Report> reports;
    window.setErrorReporter([&](const QString& title, const QString& message) { reports.push_back({title, message}); });
    ResultPanel* panel = window.resultPanel();

    // Nothing to stylize or export yet.
    panel->stylize();
    QCOMPARE(reports.size(), size_t{1});
    QVERIFY(!panel->exportResult(scratch_.filePath(QStringLiteral("never.bvh")), true));
    QCOMPARE(reports.size(), size_t{2});
    QVERIFY(!QFile::exists(scratch_.filePath(QStringLiteral("never.bvh"))));

    // A truncated BVH (hierarchy cut off mid-joint).
    QFile corrupt(scratch_.filePath(QStringLiteral("corrupt.bvh")));
    QVERIFY(corrupt.open(QIODevice::WriteOnly));
    corrupt.write("HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 6 Xposition Yposition");
    corrupt.close();
    QCOMPARE(window.openFiles({corrupt.fileName()}), 0);
    QCOMPARE(reports.size(), size_t{3});
    QVERIFY2(reports.back().message.contains(QStringLiteral("corrupt.bvh")), qPrintable(reports.back().message));

    // A corrupt network: a real one with its middle overwritten.
    QFile bytes(QString::fromStdString(network_.string()));
    QVERIFY(bytes.open(QIODevice::ReadOnly));
    QByteArray data = bytes.readAll();
    data.replace(data.size() / 2, 64, QByteArray(64, '\x5a'));
    QFile damaged(scratch_.filePath(QStringLiteral("damaged.net")));
    QVERIFY(damaged.open(QIODevice::WriteOnly));
    damaged.write(data);
    damaged.close();
    QVERIFY(!panel->loadNetworkFile(damaged.fileName()));
    QCOMPARE(reports.size(), size_t{4});
    QVERIFY2(reports.back().message.contains(QStringLiteral("damaged.net")), qPrintable(reports.back().message));
    QVERIFY(!panel->hasNetwork());

    // Still usable: a good clip loads after all that.
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh"))}), 1);
    QCOMPARE(reports.size(), size_t{4});
  }

  void clipsOfDifferentRatesPlayInSyncAndShowTheirMapping() {
    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + message)); });
    // CMU fixture: 720 frames at 120 fps; zombie: 300 frames at 30 fps, Z-up in a small unit.
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh")), test::fixture(QStringLiteral("zombie.bvh"))}), 2);
    QCOMPARE(window.contentClip(), 0);
    QCOMPARE(window.styleClip(), 1);
    for (int i = 0; i < 2; ++i) {
      const QString status = window.clipList()->topLevelItem(i)->text(5);
      QVERIFY2(!status.startsWith(QStringLiteral("unmapped")), qPrintable(status));
    }
    QVERIFY(window.clipList()->topLevelItem(1)->text(5).contains(QStringLiteral("+Z up")));
    // The style is shown at the content's 120 fps: 10 s of it span (300 - 1) * 4 + 1 frames.
    QCOMPARE(window.viewport()->figure(1).frame_count, 299 * 4 + 1);
    QCOMPARE(window.timeline()->frameRate(), window.clip(0).fps());
    // Display space: centimetres, Y-up, floor at 0: both characters are person-sized and stand on it.
    for (int i = 0; i < 2; ++i) {
      const FigureData& figure = window.viewport()->figure(i);
      double low = 1e9;
      double high = -1e9;
      for (int j = 0; j < figure.jointCount(); ++j) {
        low = std::min(low, figure.y(0, j));
        high = std::max(high, figure.y(0, j));
      }
      QVERIFY2(std::abs(low) < 10.0, qPrintable(QString::number(low)));
      QVERIFY2(high > 80.0 && high < 250.0, qPrintable(QString::number(high)));
    }
    // The detected contacts of the content fill the foot tracks.
    const std::vector<bool>& left = window.timeline()->trackView()->boolValues(ContactTrackController::kLeftFootTrack);
    QVERIFY(std::count(left.begin(), left.end(), true) > 20);
    QVERIFY(std::count(left.begin(), left.begin() + 720, false) > 20);
  }

  void unmappableRigIsFlaggedAndAMappingFileFixesIt() {
    // The CMU fixture with every joint renamed: no alias matches any more.
    Motion motion = readBvh(test::fixture(QStringLiteral("cmu_131_01.bvh")).toStdString());
    const JointMapping original = mapJoints(motion.skeleton);
    int n = 0;
    for (Joint& joint : motion.skeleton.joints)
      if (!joint.end_site) joint.name = "bone" + std::to_string(n++);
    const std::filesystem::path renamed = scratch_.filePath(QStringLiteral("renamed.bvh")).toStdString();
    writeBvh(motion, renamed);
    const Skeleton reread = readBvh(renamed).skeleton;
    const std::filesystem::path mapping = scratch_.filePath(QStringLiteral("renamed.json")).toStdString();
    saveJointMapping(original, reread, mapping);

    MainWindow window(false);
    std::vector<Report> reports;
    window.setErrorReporter([&](const QString& title, const QString& message) { reports.push_back({title, message}); });
    QCOMPARE(window.openFiles({QString::fromStdString(renamed.string())}), 1);
    QVERIFY(!window.clip(0).isMapped());
    QVERIFY2(window.clipList()->topLevelItem(0)->text(5).startsWith(QStringLiteral("unmapped: missing")),
             qPrintable(window.clipList()->topLevelItem(0)->text(5)));
    // Stylizing an unmapped clip explains itself.
    QVERIFY(window.resultPanel()->loadNetworkFile(QString::fromStdString(network_.string())));
    window.resultPanel()->stylize();
    QCOMPARE(reports.size(), size_t{1});
    QVERIFY(reports[0].message.contains(QStringLiteral("mapping")));

    // A mapping file for another rig is refused; the right one maps the clip.
    const std::filesystem::path foreign = scratch_.filePath(QStringLiteral("foreign.json")).toStdString();
    saveJointMapping(original, readBvh(test::fixture(QStringLiteral("cmu_131_01.bvh")).toStdString()).skeleton, foreign);
    QVERIFY(!window.loadMappingFile(0, QString::fromStdString(foreign.string())));
    QCOMPARE(reports.size(), size_t{2});
    QVERIFY(!window.clip(0).isMapped());
    QVERIFY(window.loadMappingFile(0, QString::fromStdString(mapping.string())));
    QVERIFY(window.clip(0).isMapped());
    QVERIFY2(window.clipList()->topLevelItem(0)->text(5).startsWith(QStringLiteral("file:")),
             qPrintable(window.clipList()->topLevelItem(0)->text(5)));
    QCOMPARE(reports.size(), size_t{2});
  }

  void stylizeCleanUpShowAndExport() {
    MainWindow window(false);
    std::vector<Report> reports;
    window.setErrorReporter([&](const QString& title, const QString& message) { reports.push_back({title, message}); });
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    const QString content_file = test::fixture(QStringLiteral("cmu_131_01.bvh"));
    QCOMPARE(window.openFiles({content_file, test::fixture(QStringLiteral("zombie.bvh"))}), 2);
    ResultPanel* panel = window.resultPanel();
    QCOMPARE(window.viewport()->figureCount(), 2);  // content and the Style clip
    QVERIFY(window.viewport()->figure(1).role == FigureRole::Style);
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(network_.string())));
    QCOMPARE(panel->networkName(), QStringLiteral("tiny_style"));
    // Issue 14: with a style network chosen the Style clip plays no part: it is not drawn, and the loop
    // is the content's, not the longer style clip's.
    QCOMPARE(window.viewport()->figureCount(), 1);
    QCOMPARE(window.timeline()->trackView()->frameCount(), window.clip(0).frameCount());

    auto* button = panel->findChild<QPushButton*>(QStringLiteral("StylizeButton"));
    QVERIFY(button != nullptr && button->isEnabled());
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    QTest::mouseClick(button, Qt::LeftButton);
    QVERIFY(panel->isBusy());  // the click returned while the worker runs
    QVERIFY(test::waitForJobs(ended));
    QCOMPARE(ended.count(), 1);
    QVERIFY2(ended.at(0).at(0).toBool(), reports.empty() ? "" : qPrintable(reports.back().message));
    QVERIFY(reports.empty());
    const style::StylizeCleanupResult* result = panel->result();
    QVERIFY(result != nullptr);

    // Metrics: both columns filled; the cleaned clip's bones are exact, its feet stay put.
    const QTableWidget* metrics = panel->metricsTable();
    for (int row = ResultPanel::kSkateRow; row <= ResultPanel::kBoneErrorRow; ++row)
      for (int column : {ResultPanel::kRawColumn, ResultPanel::kCleanedColumn})
        QVERIFY2(std::isfinite(cellValue(metrics, row, column)), qPrintable(metrics->item(row, column)->text()));
    QCOMPARE(cellValue(metrics, ResultPanel::kSkateRow, ResultPanel::kCleanedColumn),
             std::round(result->cleaned_metrics.foot_skate_cm_s * 100.0) / 100.0);
    QVERIFY(cellValue(metrics, ResultPanel::kBoneErrorRow, ResultPanel::kCleanedColumn) < 1e-3);
    // Skate over the contact tracks shown: a stance this barely trained network moved 20 cm or more is
    // not locked and counts (the shipped network's demo below, and the unit tests, hold the locks).
    QVERIFY2(result->cleaned_metrics.foot_skate_cm_s < result->raw_metrics.foot_skate_cm_s,
             qPrintable(QStringLiteral("skate %1 -> %2 cm/s").arg(result->raw_metrics.foot_skate_cm_s).arg(result->cleaned_metrics.foot_skate_cm_s)));
    QVERIFY(result->cleaned_metrics.penetration_max_cm < 0.5);
    // The residual cell: the mean, then the worst joint at the worst frame, as the clean-up measured them.
    QCOMPARE(metrics->item(ResultPanel::kResidualRow, ResultPanel::kCleanedColumn)->text(),
             QStringLiteral("%1 (max %2)").arg(result->cleaned_metrics.residual_mean_cm, 0, 'f', 2).arg(result->cleaned_metrics.residual_max_cm, 0, 'f', 1));
    qInfo("metrics raw -> cleaned: skate %.2f -> %.2f cm/s, penetration %.2f -> %.2f cm, bone %.3f -> %.1e cm, "
          "residual %.2f cm, %.2f s",
          result->raw_metrics.foot_skate_cm_s, result->cleaned_metrics.foot_skate_cm_s,
          result->raw_metrics.penetration_max_cm, result->cleaned_metrics.penetration_max_cm,
          result->raw_metrics.bone_error_mean_cm, result->cleaned_metrics.bone_error_mean_cm,
          result->cleaned_metrics.residual_mean_cm, result->seconds);

    // Figures: content and the cleaned output (blue); the raw output (grey) at a toggle.
    QCOMPARE(window.viewport()->figureCount(), 2);
    QVERIFY(window.viewport()->figure(1).role == FigureRole::Output);
    QCOMPARE(window.viewport()->figure(1).frame_count, window.clip(0).frameCount());
    QVERIFY(!window.viewport()->figure(1).contacts.empty());
    window.setRawOutputVisible(true);
    QCOMPARE(window.viewport()->figureCount(), 3);
    QVERIFY(window.viewport()->figure(2).role == FigureRole::RawOutput);
    QCOMPARE(window.viewport()->figure(2).jointCount(), kCanonicalJointCount);
    // The timeline's quality rows: the cleaned output's skate and the raw output's bone error, one
    // value per frame of the content (the loop); the stylizer sets the raw output's bones to the
    // skeleton's lengths, so its bone error stays under a millimetre.
    const TrackView* tracks = window.timeline()->trackView();
    QCOMPARE(tracks->floatTrackCount(), 3);  // skate, raw bone error, familiarity
    const std::vector<float>& skate = tracks->floatValues(ContactTrackController::kSkateTrack);
    const std::vector<float>& bone = tracks->floatValues(ContactTrackController::kRawBoneErrorTrack);
    QCOMPARE(static_cast<int>(skate.size()), tracks->frameCount());
    QCOMPARE(static_cast<int>(bone.size()), tracks->frameCount());
    QCOMPARE(tracks->frameCount(), window.clip(0).frameCount());
    QVERIFY(std::all_of(bone.begin(), bone.end(), [](float v) { return v >= 0.0f && v < 0.1f; }));
    QVERIFY(std::all_of(skate.begin(), skate.end(), [](float v) { return std::isfinite(v) && v >= 0.0f; }));
    window.timeline()->setFrame(300);
    QTest::qWait(50);
    QVERIFY(window.saveScreenshot(test::screenshotPath(QStringLiteral("with_result"))));
    window.setRawOutputVisible(false);
    QCOMPARE(window.viewport()->figureCount(), 2);

    // Export, then read it back: the content's skeleton and timing, finite values.
    const QString exported = scratch_.filePath(QStringLiteral("styled.bvh"));
    QVERIFY(panel->exportResult(exported, /*overwrite=*/false));
    const Motion content = readBvh(content_file.toStdString());
    const Motion out = readBvh(exported.toStdString());
    QCOMPARE(out.skeleton.jointCount(), content.skeleton.jointCount());
    for (int j = 0; j < content.skeleton.jointCount(); ++j) {
      const Joint& a = content.skeleton.joints[static_cast<size_t>(j)];
      const Joint& b = out.skeleton.joints[static_cast<size_t>(j)];
      QVERIFY(b.name == a.name);
      QCOMPARE(b.parent, a.parent);
      QCOMPARE(b.end_site, a.end_site);
      QVERIFY((b.offset - a.offset).norm() < 1e-4);
      QVERIFY(b.channels == a.channels);
    }
    QCOMPARE(out.frameCount(), content.frameCount());
    QVERIFY(std::abs(out.frame_time - content.frame_time) < 1e-6);
    QVERIFY(out.values.allFinite());
    QVERIFY((out.values - content.values).cwiseAbs().maxCoeff() > 1e-3);  // it is not the content again

    // An existing file is not overwritten without the flag; with it, it is.
    QFile::resize(exported, 10);
    QVERIFY(!panel->exportResult(exported, /*overwrite=*/false));
    QCOMPARE(reports.size(), size_t{1});
    QVERIFY(reports[0].message.contains(QStringLiteral("already exists")));
    QCOMPARE(QFileInfo(exported).size(), qint64{10});
    QVERIFY(panel->exportResult(exported, /*overwrite=*/true));
    QCOMPARE(readBvh(exported.toStdString()).frameCount(), content.frameCount());
  }

  void contactEditsReachTheCleanUpAndSurviveBesideTheClip() {
    // A copy, so that the contact file lands in the temp dir, not beside the fixture.
    const QString clip = copyInto(scratch_, test::fixture(QStringLiteral("cmu_131_01.bvh")), QStringLiteral("walk.bvh"));
    QVERIFY(!clip.isEmpty());
    // A trained network (the shipped demo one): the clean-up locks a foot only where the output's
    // foot rests, which a random network's never does.
    const auto resources = resourceDirectory();
    QVERIFY2(resources.has_value(), "the repository's resources/ (shipped networks) were not found");
    const auto trained = shippedNetworkFile(*resources, kDemoNetwork);
    QVERIFY(trained.has_value());
    MainWindow window(false);
    std::vector<Report> reports;
    window.setErrorReporter([&](const QString& title, const QString& message) { reports.push_back({title, message}); });
    QCOMPARE(window.openFiles({clip}), 1);
    ResultPanel* panel = window.resultPanel();
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(trained->string())));
    ContactTrackController* contacts = window.contactTracks();

    // Paint the left foot off over the whole clip (as a drag over its track would).
    const int frames = window.clip(0).frameCount();
    QSignalSpy changed(contacts, &ContactTrackController::overridesChanged);
    emit window.timeline()->trackView()->trackEdited(ContactTrackController::kLeftFootTrack, 0, frames - 1, false);
    QCOMPARE(changed.count(), 1);
    const std::vector<bool>& left = window.timeline()->trackView()->boolValues(ContactTrackController::kLeftFootTrack);
    QVERIFY(std::count(left.begin(), left.end(), true) == 0);
    QVERIFY((window.clip(0).effectiveContacts().col(0).array() == 0).all());

    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    panel->stylize();
    QVERIFY(test::waitForJobs(ended));
    QVERIFY(panel->result() != nullptr);
    const Eigen::MatrixXi& locked = panel->result()->contacts;
    QCOMPARE(locked.col(0).sum() + locked.col(1).sum(), 0);  // the left foot was never locked
    QVERIFY(locked.col(2).sum() + locked.col(3).sum() > 0);  // the right one was

    // Exporting over the content clip itself (even with the overwrite confirmed) is refused.
    const QByteArray original = [&] { QFile f(clip); f.open(QIODevice::ReadOnly); return f.readAll(); }();
    QVERIFY(!panel->exportResult(clip, /*overwrite=*/true));
    QCOMPARE(reports.size(), size_t{1});
    QVERIFY2(reports.back().message.contains(QStringLiteral("refusing to overwrite an input")),
             qPrintable(reports.back().message));
    QCOMPARE([&] { QFile f(clip); f.open(QIODevice::ReadOnly); return f.readAll(); }(), original);
    reports.clear();

    // Saved beside the clip, reset, and loaded back.
    QVERIFY(contacts->saveTracks());
    QVERIFY(QFile::exists(clip + QStringLiteral(".contacts.json")));
    contacts->resetOverrides();
    QVERIFY((window.clip(0).effectiveContacts().col(0).array() != 0).any());
    QVERIFY(contacts->loadTracks());
    QVERIFY((window.clip(0).effectiveContacts().col(0).array() == 0).all());
    QVERIFY(reports.empty());

    // A damaged contact file is reported, and the edits stay as they were.
    QFile damaged(clip + QStringLiteral(".contacts.json"));
    QVERIFY(damaged.open(QIODevice::WriteOnly | QIODevice::Truncate));
    damaged.write("{\"format\": \"motionstyle-contacts\", \"version\": 1, \"fps\": ");
    damaged.close();
    contacts->resetOverrides();
    QVERIFY(!contacts->loadTracks());
    QCOMPARE(reports.size(), size_t{1});
    QVERIFY((window.clip(0).contact_overrides.array() == -1).all());
  }

  // The clean-up's warnings name the clip's own frames (120 fps here, solved at 60) and each links
  // there: a click puts the timeline on its first frame. So does a click on the cleaned residual, to
  // its worst frame, which its tooltip names with the joint.
  // The youthful network: it lifts the swinging foot well over the 5 cm a held-down warning needs
  // (9.3 cm at frames 640-662); the demo's elderly shuffles it lower since its refinement aims at the
  // style's walk (locomotion_kind.h), not its run.
  void cleanUpWarningsAndTheWorstResidualLinkToTheirFrames() {
    const auto resources = resourceDirectory();
    QVERIFY2(resources.has_value(), "the repository's resources/ (shipped networks) were not found");
    const auto trained = shippedNetworkFile(*resources, "youthful");
    QVERIFY(trained.has_value());
    MainWindow window(false);
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh"))}), 1);
    ResultPanel* panel = window.resultPanel();
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(trained->string())));
    // The left foot held down through half a second of walking late in the clip: far from its targets.
    constexpr int kFirst = 630, kLast = 689;
    QVERIFY(window.clip(0).frameCount() > kLast);
    emit window.timeline()->trackView()->trackEdited(ContactTrackController::kLeftFootTrack, kFirst, kLast, true);
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    panel->stylize();
    QVERIFY(test::waitForJobs(ended));
    QVERIFY(panel->result() != nullptr);
    // (The network's own output also leaves the kneel, frames 370-400, far off: not this check's.)
    int linked = -1;
    for (const CleanupWarning& warning : panel->result()->report.warnings)
      if (warning.text.find("large residual: Left") != std::string::npos && warning.first_frame >= kFirst - 8 &&
          warning.last_frame <= kLast + 8 && linked < 0)
        linked = warning.first_frame;
    QVERIFY2(linked >= 0, "no residual warning at the held foot's frames (at the clip's 120 fps)");
    auto* label = panel->findChild<QLabel*>(QStringLiteral("CleanupWarnings"));
    QVERIFY(label != nullptr);
    // What to do about it comes first: the forced contact holds the swinging foot under the style's
    // lift, and the panel's first line says so with its fix (its residuals follow).
    const QString first_line = label->text().section(QStringLiteral("<br>"), 0, 0);
    QVERIFY2(first_line.contains(QStringLiteral("held down by its contact: left")) &&
                 first_line.contains(QStringLiteral("end the contact there")),
             qPrintable(label->text()));
    QVERIFY2(label->text().contains(QStringLiteral("<a href=\"%1\"").arg(linked)), qPrintable(label->text()));
    window.timeline()->setFrame(0);
    emit label->linkActivated(QString::number(linked));
    QCOMPARE(window.timeline()->frame(), linked);

    // The worst residual: clicked as a user clicks the cell.
    const ClipMetrics& cleaned = panel->result()->cleaned_metrics;
    QVERIFY(cleaned.residual_max_frame >= 0 && cleaned.residual_max_joint >= 0);
    const int worst = static_cast<int>(std::floor(cleaned.residual_max_frame * 120.0 / panel->result()->cleanup_fps));
    auto* table = panel->findChild<QTableWidget*>(QStringLiteral("MetricsTable"));
    QVERIFY(table != nullptr);
    QTableWidgetItem* cell = table->item(ResultMetricsView::kResidualRow, ResultMetricsView::kCleanedColumn);
    QVERIFY(cell != nullptr);
    const QString joint = QString::fromUtf8(canonicalJointName(static_cast<CanonicalJoint>(cleaned.residual_max_joint)));
    QVERIFY2(cell->toolTip().contains(QStringLiteral("%1 at frame %2 ").arg(joint).arg(worst)), qPrintable(cell->toolTip()));
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.timeline()->setFrame(0);
    const QRect rect = table->visualItemRect(cell);
    QVERIFY2(table->viewport()->rect().contains(rect.center()), "the residual cell is out of sight");
    QTest::mouseClick(table->viewport(), Qt::LeftButton, {}, rect.center());
    QCOMPARE(window.timeline()->frame(), worst);
  }

  void strengthZeroKeepsTheContentAndAStylizedClipIsCleanedAsGiven() {
    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + message)); });
    const QString content_file = test::fixture(QStringLiteral("cmu_131_01.bvh"));
    QCOMPARE(window.openFiles({content_file}), 1);
    ResultPanel* panel = window.resultPanel();
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(network_.string())));
    panel->setStrength(0.0);
    QCOMPARE(panel->strength(), 0.0);
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    panel->stylize();
    QVERIFY(test::waitForJobs(ended));
    QVERIFY(panel->result() != nullptr);
    // Strength 0 is the content itself: the clean-up hands back nearly the same clip (issue 4: a clean
    // real clip changes by at most 1 cm on average).
    const Motion& content = window.clip(0).motion;
    const Eigen::MatrixXd before = worldPositions(content);
    const Eigen::MatrixXd after = worldPositions(panel->result()->cleaned);
    QCOMPARE(after.rows(), before.rows());
    double change = 0.0;
    for (Eigen::Index f = 0; f < before.rows(); ++f)
      for (Eigen::Index j = 0; j < before.cols() / 3; ++j)
        change += (after.row(f).segment<3>(3 * j) - before.row(f).segment<3>(3 * j)).norm();
    change *= window.clip(0).display_space.convention.cm_per_unit / double(before.rows() * (before.cols() / 3));
    qInfo("strength 0: mean joint change %.3f cm", change);
    QVERIFY(change < 1.0);

    // A clip stylized elsewhere (the optimisation method's output) is cleaned up as it is.
    const MotionFeatures features = extractFeatures(content, *window.clip(0).mapping);
    const style::Stylizer stylizer(nn::loadStyleModel(network_));
    style::StylizedClip half = stylizer.stylize(features, 0.5);
    const Eigen::MatrixXd targets = half.world_positions;
    panel->setStylizedClip(std::move(half), QStringLiteral("optimised"));
    QVERIFY(panel->isBusy());
    QVERIFY(test::waitForJobs(ended, 2));
    QVERIFY(panel->result() != nullptr);
    QCOMPARE(panel->networkName(), QStringLiteral("optimised"));
    QVERIFY(panel->result()->stylized.world_positions == targets);
  }

  // Issue 14: a result always matches its inputs, or says that it does not.
  // Found as a user: with a result of clip A shown, A removed from the Clips list (or another clip made
  // the content) drops the result, and the window's status line went on saying "Stylized and cleaned
  // up ... frames" of A under clip B with nothing stylized. It now says what happened to the result.
  void aResultDroppedWithItsClipIsNotClaimedInTheStatusLine() {
    MainWindow window(false);
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh")), test::fixture(QStringLiteral("zombie.bvh"))}), 2);
    ResultPanel* panel = window.resultPanel();
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(network_.string())));
    for (const bool remove : {false, true}) {
      QSignalSpy ended(panel, &ResultPanel::jobEnded);
      panel->stylize();
      QVERIFY(test::waitForJobs(ended));
      QVERIFY(panel->result() != nullptr);
      const QString stylized = window.clip(window.contentClip()).name;
      QVERIFY2(test::statusLine(window).startsWith(QStringLiteral("Stylized")), qPrintable(test::statusLine(window)));
      if (remove) window.removeClip(window.contentClip());
      else window.setContentClip(1 - window.contentClip());
      QVERIFY(panel->result() == nullptr);
      const QString status = test::statusLine(window);
      QVERIFY2(!status.startsWith(QStringLiteral("Stylized")) && status.contains(stylized) &&
                   status.contains(window.clip(window.contentClip()).name),
               qPrintable(status));
    }
  }

  void switchingTheStyleRedoesTheResultAndTheOldOneSaysItIsOutOfDate() {
    const std::filesystem::path other = writeTinyNetwork(scratch_, QStringLiteral("other_style"), 9);
    MainWindow window(false);
    std::vector<Report> reports;
    window.setErrorReporter([&](const QString& title, const QString& message) { reports.push_back({title, message}); });
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh"))}), 1);
    ResultPanel* panel = window.resultPanel();
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(network_.string())));
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    panel->stylize();
    QVERIFY(test::waitForJobs(ended));
    const style::StylizeCleanupResult* first = panel->result();
    QVERIFY(first != nullptr && !panel->resultIsStale());
    QVERIFY(panel->resultFigures(false).front().name.contains(QStringLiteral("tiny_style")));

    // Another style: the shown result is out of date at once (figures, Export) and is being redone.
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(other.string())));
    QVERIFY(panel->isBusy());
    QVERIFY(panel->resultIsStale());
    const QString stale_name = window.viewport()->figure(window.viewport()->figureCount() - 1).name;
    QVERIFY2(stale_name.contains(QStringLiteral("tiny_style")) && stale_name.contains(QStringLiteral("out of date")),
             qPrintable(stale_name));
    // Before any event is processed (the new result arrives through the event loop: the clean-up now
    // takes milliseconds, so showing the window first would let it in).
    const QString exported = scratch_.filePath(QStringLiteral("switched.bvh"));
    QVERIFY(!panel->exportResult(exported, false));
    QVERIFY(!reports.empty() && reports.back().message.contains(QStringLiteral("out of date")));
    QVERIFY(!QFile::exists(exported));
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QVERIFY(window.saveScreenshot(test::screenshotPath(QStringLiteral("result_out_of_date"))));

    // The new style's result replaces it.
    QVERIFY(test::waitForJobs(ended, 2));
    QVERIFY(ended.at(1).at(0).toBool());
    QVERIFY(panel->result() != nullptr && panel->result() != first);
    QVERIFY(!panel->resultIsStale());
    const QString name = window.viewport()->figure(window.viewport()->figureCount() - 1).name;
    QVERIFY2(name.contains(QStringLiteral("other_style")) && !name.contains(QStringLiteral("out of date")), qPrintable(name));
    QVERIFY(panel->exportResult(exported, false));

    // Changes while the update runs: that job ends (its result shown, out of date), then ONE job for
    // the latest inputs; the inputs in between are dropped, never queued. (At another strength: with
    // nothing else changed, each style's result would be shown again from the recent results.)
    panel->setStrength(0.8);
    QVERIFY(panel->isBusy());
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(network_.string())));
    QVERIFY(panel->isBusy());
    for (int i = 0; i < 3; ++i) {
      QVERIFY(panel->loadNetworkFile(QString::fromStdString(other.string())));
      QVERIFY(panel->loadNetworkFile(QString::fromStdString(network_.string())));
    }
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(other.string())));
    QCOMPARE(ended.count(), 2);
    QVERIFY(test::waitForJobs(ended, 4));
    QVERIFY(ended.at(2).at(0).toBool() && ended.at(3).at(0).toBool());
    QTest::qWait(300);
    QCOMPARE(ended.count(), 4);  // no job for the inputs in between
    QVERIFY(!panel->isBusy());
    QVERIFY(!panel->resultIsStale());
    QVERIFY(window.viewport()->figure(window.viewport()->figureCount() - 1).name.contains(QStringLiteral("other_style")));
  }

  // A network file chosen again is taken prepared from the cache: the same network, no new job, and
  // its result for the same inputs is shown again. A file rewritten since (another network under the
  // same name) is read again and redoes the result.
  void aNetworkFileIsReadAgainOnlyWhenItChanged() {
    const std::filesystem::path file = writeTinyNetwork(scratch_, QStringLiteral("rewritten_style"), 5);
    const std::filesystem::path other = writeTinyNetwork(scratch_, QStringLiteral("another_style"), 9);
    MainWindow window(false);
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh"))}), 1);
    ResultPanel* panel = window.resultPanel();
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(file.string())));
    panel->stylize();
    QVERIFY(test::waitForJobs(ended));
    const Eigen::MatrixXd first = panel->result()->stylized.features;

    QVERIFY(panel->loadNetworkFile(QString::fromStdString(file.string())));  // the same network: nothing to redo
    QVERIFY(!panel->isBusy());
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(other.string())));
    QVERIFY(test::waitForJobs(ended, 2));
    // Back: the network from the cache, and its result for these inputs remembered: shown, no job.
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(file.string())));
    QVERIFY(!panel->isBusy());
    QVERIFY(!panel->resultIsStale());
    QCOMPARE(panel->result()->stylized.features, first);
    QCOMPARE(ended.count(), 2);

    nn::StyleModel changed = test::tinyStyleModel(11);
    nn::saveStyleModel(changed, file);  // another network in the same file
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(other.string())));
    QVERIFY(!panel->isBusy());  // its result is remembered too
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(file.string())));
    QVERIFY2(panel->isBusy(), "a rewritten network file must be read again, and its result redone");
    QVERIFY(test::waitForJobs(ended, 3));
    QVERIFY(panel->result()->stylized.features != first);
  }

  // A network opened by hand (Open..., a drop) is read on the reader, as a picked entry is: the window
  // never waits for the file. One that reads is listed and used; one that does not is reported, its
  // entry removed, and the chooser stays on the network in use.
  void aNetworkOpenedByHandIsReadWithoutTheWindowWaiting() {
    const std::filesystem::path good = writeTinyNetwork(scratch_, QStringLiteral("opened_style"), 5);
    const QString bad = scratch_.filePath(QStringLiteral("not_a_network.net"));
    QFile garbage(bad);
    QVERIFY(garbage.open(QIODevice::WriteOnly) && garbage.write("not a network") > 0);
    garbage.close();
    MainWindow window(false);
    std::vector<Report> reports;
    window.setErrorReporter([&](const QString& title, const QString& message) { reports.push_back({title, message}); });
    ResultPanel* panel = window.resultPanel();
    const QComboBox* choice = panel->networkChoice();
    panel->openNetworkFile(QString::fromStdString(good.string()));
    QCOMPARE(choice->currentText(), QStringLiteral("opened_style"));  // listed at once
    QTRY_COMPARE_WITH_TIMEOUT(panel->networkName(), QStringLiteral("opened_style"), 10000);
    QVERIFY(reports.empty());
    const int entries = choice->count();
    panel->openNetworkFile(bad);
    QVERIFY(reports.empty());  // the read's outcome comes later, from the reader: the call did not wait
    QTRY_COMPARE_WITH_TIMEOUT(reports.size(), size_t{1}, 10000);
    QVERIFY2(reports[0].message.contains(QStringLiteral("not_a_network.net")), qPrintable(reports[0].message));
    QCOMPARE(choice->count(), entries);
    QCOMPARE(choice->currentText(), QStringLiteral("opened_style"));
    QCOMPARE(panel->networkName(), QStringLiteral("opened_style"));
  }

  // A network without a file (trained in the session, from the Networks panel) keeps its entry in the
  // style chooser: picking that entry again, after another style, uses it again (the chooser once
  // showed it while the panel went on with the other style).
  void aNetworkWithoutAFileIsChosenAgainFromTheChooser() {
    const std::filesystem::path file = writeTinyNetwork(scratch_, QStringLiteral("filed_style"), 5);
    MainWindow window(false);
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh"))}), 1);
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(-1);
    panel->setStyleNetwork(std::make_shared<const nn::StyleModel>(test::tinyStyleModel(7)), QStringLiteral("trained here"));
    QCOMPARE(panel->networkName(), QStringLiteral("trained here"));
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(file.string())));
    QCOMPARE(panel->networkName(), QStringLiteral("filed_style"));
    QComboBox* choice = panel->networkChoice();
    const int entry = choice->findText(QStringLiteral("trained here"));
    QVERIFY(entry >= 0);
    choice->setCurrentIndex(entry);
    emit choice->activated(entry);
    QCOMPARE(panel->networkName(), QStringLiteral("trained here"));
    QCOMPARE(choice->currentText(), QStringLiteral("trained here"));
    // Renamed in the Networks panel: its entry follows, and still chooses it.
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(file.string())));
    panel->renameNetwork(QStringLiteral("trained here"), QStringLiteral("my walk"));
    const int renamed = choice->findText(QStringLiteral("my walk"));
    QVERIFY(renamed >= 0);
    choice->setCurrentIndex(renamed);
    emit choice->activated(renamed);
    QCOMPARE(panel->networkName(), QStringLiteral("my walk"));

    // Removed from the Networks panel: its entry leaves the chooser, which shows the network in use.
    NetworkList* list = window.networkPanel()->networkList();
    list->setConfirmer([](const QString&, const QString&, QMessageBox::StandardButtons) { return QMessageBox::Discard; });
    list->addNetwork(std::make_shared<const nn::StyleModel>(test::tinyStyleModel(8)), QStringLiteral("scratch net"));
    QCOMPARE(panel->networkName(), QStringLiteral("scratch net"));
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(file.string())));
    QVERIFY(choice->findText(QStringLiteral("scratch net")) >= 0);
    QVERIFY(list->removeNetwork(list->currentIndex()));
    QCOMPARE(choice->findText(QStringLiteral("scratch net")), -1);
    QCOMPARE(choice->currentText(), panel->networkName());
  }

  void cancelDropsTheJobAndClosingStaysClean() {
    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + message)); });
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh"))}), 1);
    ResultPanel* panel = window.resultPanel();
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(network_.string())));
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    QSignalSpy changed(panel, &ResultPanel::resultChanged);
    panel->stylize();
    QVERIFY(panel->isBusy());
    panel->cancel();
    QVERIFY(!panel->isBusy());
    QCOMPARE(ended.count(), 1);
    QVERIFY(!ended.at(0).at(0).toBool());
    QTest::qWait(200);  // a late answer from the worker must not resurrect the job
    QVERIFY(panel->result() == nullptr);
    QCOMPARE(changed.count(), 0);
    // A second job starts at once, and the window is destroyed while it may still run.
    panel->stylize();
    QVERIFY(panel->isBusy());
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(ResultTest)
#include "test_result.moc"
