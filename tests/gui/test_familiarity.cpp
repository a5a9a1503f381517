// Other studios' clips in the real main window: the Result panel reads how familiar the content is
// (a row with the next step, and a timeline track), keeps the content's path unless told otherwise,
// and the Style networks panel's Adapt tab adapts the networks to the user's clips (progress, cancel,
// a before/after table, the adapted networks listed unsaved). Bad input first: nothing checked.
#include <QCheckBox>
#include <QDir>
#include <QElapsedTimer>
#include <QFileInfo>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QScopeGuard>
#include <QSettings>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTableWidget>
#include <QTemporaryDir>

#include <algorithm>
#include <filesystem>
#include <memory>

#include "adapt_tab.h"
#include "network_list.h"
#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "common/resource_paths.h"
#include "contact_tracks.h"
#include "features/feature_statistics.h"
#include "gui_test_support.h"
#include "tiny_style_network.h"
#include "main_window.h"
#include "network_panel.h"
#include "nn/transformation_objective.h"
#include "result_panel.h"
#include "style/familiarity.h"
#include "style/motion_dataset.h"
#include "style/stylizer.h"
#include "style/training.h"
#include "timeline_widget.h"
#include "track_view.h"

using namespace motionstyle;

namespace {

constexpr int kJobTimeoutMs = 120000;  // a hang guard, not a speed test

// A tiny style network (random weights, the fixtures' statistics) that stores a style target, so that
// the Adapt tab can retrain it without its style clip.
std::filesystem::path writeTinyNetwork(const QTemporaryDir& dir) {
  nn::StyleModel model = test::tinyStyleModel();
  model.metadata.training.weights.style = 1.0;
  Eigen::MatrixXd style_clip =
      style::loadMotionClip(test::fixture(QStringLiteral("zombie.bvh")).toStdString()).features.values;
  model.normalisation.normalize(style_clip);
  model.style_targets = {{"", nn::styleGram(model.loss_network, nn::Mat<float>(style_clip.cast<float>()))}};
  return test::saveInto(dir, QStringLiteral("tiny_style"), model);
}

}  // namespace

class FamiliarityTest : public QObject {
  Q_OBJECT

  QTemporaryDir settings_dir_;
  QTemporaryDir scratch_;
  std::filesystem::path network_;

 private slots:
  void initTestCase() {
    QVERIFY(settings_dir_.isValid() && scratch_.isValid());
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settings_dir_.path());
    QCoreApplication::setOrganizationName(QStringLiteral("MotionStyleTests"));
    QCoreApplication::setApplicationName(QStringLiteral("test_gui_familiarity"));
    network_ = writeTinyNetwork(scratch_);
  }

  void theResultPanelReadsFamiliarityAndKeepsThePath() {
    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + ": " + message)); });
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh"))}), 1);
    ResultPanel* panel = window.resultPanel();
    auto* label = panel->findChild<QLabel*>(QStringLiteral("FamiliarityLabel"));
    QVERIFY(label != nullptr);
    // No style chosen yet: the shipped loss network reads the clip (familiar), on the timeline too.
    QVERIFY(panel->familiarity().has_value());
    QCOMPARE(panel->familiarity()->level, style::FamiliarityLevel::Familiar);
    QVERIFY2(label->text().contains(QStringLiteral("familiar")), qPrintable(label->text()));
    QVERIFY(!window.timeline()->trackView()->floatValues(ContactTrackController::kFamiliarityTrack).empty());
    QSignalSpy familiarity(panel, &ResultPanel::familiarityChanged);
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(network_.string())));
    QVERIFY(familiarity.count() >= 1);
    QVERIFY(panel->familiarity().has_value());
    const char* level = style::familiarityName(panel->familiarity()->level);
    QVERIFY2(label->text().contains(QLatin1String(level)), qPrintable(label->text()));
    // An untrained network reconstructs nothing: far, with the next step offered.
    QVERIFY2(label->text().contains(QStringLiteral("Adapt")), qPrintable(label->text()));
    // Its per-frame figure is a timeline row, before any result.
    const TrackView* tracks = window.timeline()->trackView();
    const std::vector<float>& row = tracks->floatValues(ContactTrackController::kFamiliarityTrack);
    QCOMPARE(static_cast<int>(row.size()), tracks->frameCount());
    QVERIFY(*std::max_element(row.begin(), row.end()) > 0.0f);

    // Keep the content's path (default): the output's root velocities are the content's.
    auto* keep = panel->findChild<QCheckBox*>(QStringLiteral("KeepPathCheck"));
    QVERIFY(keep != nullptr && keep->isChecked());
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    QTest::mouseClick(panel->findChild<QPushButton*>(QStringLiteral("StylizeButton")), Qt::LeftButton);
    QVERIFY(test::waitForJobs(ended, 1));
    const MotionFeatures content = extractFeatures(window.clip(0).motion, *window.clip(0).mapping);
    const auto velocities = [](const Eigen::MatrixXd& f) { return Eigen::MatrixXd(f.middleRows<3>(kSidewaysVelocity)); };
    QVERIFY(panel->result() != nullptr);
    QVERIFY(velocities(panel->result()->stylized.features) == velocities(content.values));
    // Unticking it runs again and lets the network set the pace.
    QTest::mouseClick(keep, Qt::LeftButton, {}, QPoint(8, keep->height() / 2));
    QVERIFY(!keep->isChecked());
    QVERIFY(test::waitForJobs(ended, 2));
    QVERIFY(panel->pathMode() == style::PathMode::Style);
    QVERIFY(velocities(panel->result()->stylized.features) != velocities(content.values));

    // The reading's next step: "Adapt..." opens the Style networks panel's Adapt tab with this clip.
    QVERIFY(label->text().contains(QStringLiteral("href")));
    emit label->linkActivated(QStringLiteral("adapt"));
    auto* tabs = window.networkPanel()->findChild<QTabWidget*>();
    QVERIFY(tabs != nullptr);
    QVERIFY(tabs->currentWidget()->isAncestorOf(window.networkPanel()->adaptTab()));  // its page scrolls it
    auto* clips = window.networkPanel()->adaptTab()->findChild<QListWidget*>(QStringLiteral("AdaptClips"));
    QCOMPARE(clips->count(), 1);
    QCOMPARE(clips->item(0)->checkState(), Qt::Checked);

    // With a shipped style chosen, the link checks that style (and only it) to retrain.
    const auto resources = resourceDirectory();
    QVERIFY2(resources.has_value(), "the repository's resources/ (shipped networks) were not found");
    const auto masculine = shippedNetworkFile(*resources, "masculine");
    QVERIFY(masculine.has_value());
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(masculine->string())));
    emit label->linkActivated(QStringLiteral("adapt"));
    auto* styles = window.networkPanel()->adaptTab()->findChild<QListWidget*>(QStringLiteral("AdaptStyles"));
    QVERIFY(styles->count() >= 9);
    QStringList checked;
    for (int i = 0; i < styles->count(); ++i)
      if (styles->item(i)->checkState() == Qt::Checked) checked << styles->item(i)->text();
    QCOMPARE(checked, QStringList{QStringLiteral("masculine")});
  }

  // The reading follows the loss network, not the style: every shipped style (trained against the
  // shipped loss network) reads the clip as it is read before a style is chosen, and is not measured
  // again on a switch; a network with another loss network reads it anew, and so does another clip.
  void stylesOfOneLossNetworkReadTheClipAlike() {
    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + ": " + message)); });
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh"))}), 1);
    ResultPanel* panel = window.resultPanel();
    panel->setLookAheadDelay(-1);
    QVERIFY(panel->familiarity().has_value());
    const std::vector<double> shipped = panel->familiarity()->per_frame_cm;
    const auto resources = resourceDirectory();
    QVERIFY2(resources.has_value(), "the repository's resources/ (shipped networks) were not found");
    for (const char* name : {"elderly", "sad", "elderly"}) {
      const auto file = shippedNetworkFile(*resources, name);
      QVERIFY(file.has_value());
      QVERIFY(panel->loadNetworkFile(QString::fromStdString(file->string())));
      QVERIFY(panel->familiarity().has_value());
      QVERIFY2(panel->familiarity()->per_frame_cm == shipped, name);
      // Measured afresh through this network's own projection: the same figures.
      const MotionFeatures features = extractFeatures(window.clip(0).motion, *window.clip(0).mapping);
      const style::Stylizer stylizer(style::loadCompatibleStyleModel(*file));
      QVERIFY(style::measureFamiliarity(stylizer, features.values).per_frame_cm == shipped);
    }
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(network_.string())));  // another loss network
    QVERIFY(panel->familiarity().has_value() && panel->familiarity()->per_frame_cm != shipped);
    QVERIFY(panel->familiarity()->level == style::FamiliarityLevel::Far);
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("zombie.bvh"))}), 1);
    window.setContentClip(1);
    QVERIFY(panel->familiarity().has_value());
    QVERIFY(panel->familiarity()->per_frame_cm.size() != shipped.size());
  }

  // The Adapt tab retrains the style the user works with: it checks the one chosen in the Result panel,
  // until the user checks or unchecks a style there; then it keeps the user's choice.
  void theAdaptTabFollowsTheChosenStyleUntilTheUserChooses() {
    MainWindow window(false);
    ResultPanel* panel = window.resultPanel();
    const auto resources = resourceDirectory();
    QVERIFY2(resources.has_value(), "the repository's resources/ (shipped networks) were not found");
    auto* styles = window.networkPanel()->adaptTab()->findChild<QListWidget*>(QStringLiteral("AdaptStyles"));
    QVERIFY(styles != nullptr && styles->count() >= 9);
    const auto checked = [&] {
      QStringList names;
      for (int i = 0; i < styles->count(); ++i)
        if (styles->item(i)->checkState() == Qt::Checked) names << styles->item(i)->text();
      return names;
    };
    const auto choose = [&](const char* name) {
      const auto file = shippedNetworkFile(*resources, name);
      return file && panel->loadNetworkFile(QString::fromStdString(file->string()));
    };
    QVERIFY(choose("sad"));
    QCOMPARE(checked(), QStringList{QStringLiteral("sad")});
    QVERIFY(choose("elderly"));
    QCOMPARE(checked(), QStringList{QStringLiteral("elderly")});
    window.networkPanel()->adaptTab()->refresh();  // a rebuild of the lists is not the user's choice
    QVERIFY(choose("proud"));
    QCOMPARE(checked(), QStringList{QStringLiteral("proud")});
    styles->findItems(QStringLiteral("angry"), Qt::MatchExactly).front()->setCheckState(Qt::Checked);  // the user's
    QVERIFY(choose("happy"));
    QCOMPARE(checked(), (QStringList{QStringLiteral("angry"), QStringLiteral("proud")}));
  }

  // A CMU file as published opens with its rig's rest pose (features/rest_pose_frames.h): the panel
  // says so, and the cleaned result keeps that frame as it was while the motion after it is styled.
  void aClipThatOpensWithItsRestPoseKeepsIt() {
    Motion motion = readBvh(test::fixture(QStringLiteral("cmu_131_01.bvh")).toStdString());
    const Eigen::Index frames = motion.values.rows();
    MatrixRowMajor values(frames + 1, motion.values.cols());
    values.bottomRows(frames) = motion.values;
    values.row(0).setZero();
    values.row(0).head<3>() = motion.values.row(0).head<3>();  // the root's position; every rotation zero
    motion.values = values;
    const QString file = scratch_.filePath(QStringLiteral("rest_pose.bvh"));
    writeBvh(motion, file.toStdString());

    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + ": " + message)); });
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QCOMPARE(window.openFiles({file}), 1);
    QCOMPARE(window.clip(0).rest_pose_frames, 1);
    QVERIFY2(window.clip(0).mappingStatus().contains(QStringLiteral("frame 0 rest pose")),
             qPrintable(window.clip(0).mappingStatus()));
    ResultPanel* panel = window.resultPanel();
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(network_.string())));
    auto* label = panel->findChild<QLabel*>(QStringLiteral("FamiliarityLabel"));
    QVERIFY2(label->text().contains(QStringLiteral("rest pose")), qPrintable(label->text()));
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    QTest::mouseClick(panel->findChild<QPushButton*>(QStringLiteral("StylizeButton")), Qt::LeftButton);
    QVERIFY(test::waitForJobs(ended, 1));
    QVERIFY(panel->result() != nullptr);
    const Motion& cleaned = panel->result()->cleaned;
    QCOMPARE(cleaned.frameCount(), motion.frameCount());
    QVERIFY(cleaned.values.row(0) == motion.values.row(0));
    QVERIFY(cleaned.values.row(1) != motion.values.row(1));  // the motion is styled
  }

  void theAdaptTabAdaptsTheNetworksToTheUsersClips() {
    // The session's temporary folder, to see what the app leaves in it.
    QTemporaryDir temp;
    QVERIFY(temp.isValid());
    const QByteArray tmpdir = qgetenv("TMPDIR");
    qputenv("TMPDIR", temp.path().toLocal8Bit());
    const auto restore = qScopeGuard([tmpdir] {
      if (tmpdir.isNull()) qunsetenv("TMPDIR");
      else qputenv("TMPDIR", tmpdir);
    });
    auto window_owner = std::make_unique<MainWindow>(false);
    MainWindow& window = *window_owner;
    std::vector<QString> reports;
    window.setErrorReporter([&](const QString& title, const QString& message) { reports.push_back(title + ": " + message); });
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    NetworkPanel* networks = window.networkPanel();
    QVERIFY(networks->networkList()->loadNetworkFile(QString::fromStdString(network_.string())));
    const int listed = networks->networkList()->networkCount();
    AdaptTab* tab = networks->adaptTab();
    auto* adapt = tab->findChild<QPushButton*>(QStringLiteral("AdaptButton"));
    QVERIFY(adapt != nullptr);

    // Nothing loaded: nothing to adapt to, said so.
    networks->showAdaptTab(QString());
    QTest::mouseClick(adapt, Qt::LeftButton);
    QCOMPARE(reports.size(), size_t{1});
    QVERIFY2(reports[0].contains(QStringLiteral("clips")), qPrintable(reports[0]));

    // The user's clips: both fixtures (another studio each). The tiny network is the style to retrain.
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh")), test::fixture(QStringLiteral("zombie.bvh"))}), 2);
    auto* styles = tab->findChild<QListWidget*>(QStringLiteral("AdaptStyles"));
    auto* clips = tab->findChild<QListWidget*>(QStringLiteral("AdaptClips"));
    QCOMPARE(clips->count(), 2);
    for (int i = 0; i < styles->count(); ++i) styles->item(i)->setCheckState(Qt::Unchecked);
    tab->setStyleChecked(QStringLiteral("tiny_style"), true);
    tab->setEpochs(3, 2);
    QSignalSpy adapted(tab, &AdaptTab::adapted);
    QTest::mouseClick(adapt, Qt::LeftButton);
    QVERIFY(tab->isBusy());
    QVERIFY(!adapt->isEnabled());
    QVERIFY(QTest::qWaitFor([&] { return adapted.count() >= 1 || reports.size() > 1; }, kJobTimeoutMs));
    QVERIFY2(reports.size() == 1, qPrintable(reports.back()));
    QVERIFY(QTest::qWaitFor([&] { return !tab->isBusy(); }, kJobTimeoutMs));
    // Before/after per clip and for all, and the retrained network listed unsaved and selected.
    const QTableWidget* table = tab->familiarityTable();
    QCOMPARE(table->rowCount(), 3);
    QVERIFY2(tab->statusText().contains(QStringLiteral("Adapted")), qPrintable(tab->statusText()));
    QCOMPARE(test::statusLine(window), tab->statusText());  // the window's status bar says it too
    QCOMPARE(networks->networkList()->networkCount(), listed + 1);
    QVERIFY(!networks->networkList()->isNetworkSaved(networks->networkList()->networkCount() - 1));
    QVERIFY(networks->networkList()->currentNetworkName().startsWith(QStringLiteral("tiny_style adapted")));
    QVERIFY(test::saveScreenshot(window.grab().toImage(), QStringLiteral("adapt_tab")).size() > 0);
    // The tiny network has no memory of what it learnt from, and the status says what that means.
    QVERIFY2(tab->statusText().contains(QStringLiteral("may be forgotten")), qPrintable(tab->statusText()));

    // A shipped style: its loss network's shipped memory keeps what it knew, and the status says so.
    tab->setStyleChecked(QStringLiteral("tiny_style"), false);
    tab->setStyleChecked(QStringLiteral("elderly"), true);
    tab->setEpochs(2, 1);
    QTest::mouseClick(adapt, Qt::LeftButton);
    QVERIFY(QTest::qWaitFor([&] { return adapted.count() >= 2 || reports.size() > 1; }, kJobTimeoutMs));
    QVERIFY2(reports.size() == 1, qPrintable(reports.back()));
    QVERIFY(QTest::qWaitFor([&] { return !tab->isBusy(); }, kJobTimeoutMs));
    QVERIFY2(tab->statusText().contains(QStringLiteral("What it knew is kept (its memory of the Bandai")),
             qPrintable(tab->statusText()));
    QCOMPARE(networks->networkList()->networkCount(), listed + 2);
    // The adapted network carries its own memory (the Bandai clips' and the user's), saved beside it and
    // read back with it, and adapting it again keeps both.
    NetworkList* list = networks->networkList();
    const int adapted_index = list->networkCount() - 1;
    QVERIFY(list->networkMemory(adapted_index) != nullptr);
    QTemporaryDir saved;
    const QString file = saved.filePath(QStringLiteral("elderly_mine.net"));
    QVERIFY(list->saveNetwork(adapted_index, file));
    QVERIFY(QFileInfo::exists(saved.filePath(QStringLiteral("elderly_mine.memory"))));
    QVERIFY(list->removeNetwork(adapted_index));
    QVERIFY(list->loadNetworkFile(file));
    QVERIFY(list->networkMemory(list->networkCount() - 1) != nullptr);
    tab->refresh();
    tab->setStyleChecked(QStringLiteral("elderly"), false);
    tab->setStyleChecked(QStringLiteral("elderly_mine"), true);
    QTest::mouseClick(adapt, Qt::LeftButton);
    QVERIFY(QTest::qWaitFor([&] { return adapted.count() >= 3 || reports.size() > 1; }, kJobTimeoutMs));
    QVERIFY(QTest::qWaitFor([&] { return !tab->isBusy(); }, kJobTimeoutMs));
    QVERIFY2(tab->statusText().contains(QStringLiteral("the 2 clip(s) it was adapted on")), qPrintable(tab->statusText()));
    QCOMPARE(list->networkCount(), listed + 3);
    QVERIFY(saved.remove());  // the user's folder, not the app's leftovers checked below

    // Cancel stops a run within a second and changes nothing.
    tab->setEpochs(1000, 2);
    QTest::mouseClick(adapt, Qt::LeftButton);
    QTest::qWait(300);
    QElapsedTimer timer;
    timer.start();
    tab->cancel();
    QVERIFY(QTest::qWaitFor([&] { return !tab->isBusy(); }, 5000));
    qInfo("adaptation stopped %lld ms after Cancel", static_cast<long long>(timer.elapsed()));
    QVERIFY(QTest::qWaitFor([&] { return test::statusLine(window).startsWith(QStringLiteral("Adaptation stopped")); }, 5000));
    QCOMPARE(networks->networkList()->networkCount(), listed + 3);

    // The adaptation's checkpoints go with the window (they piled up in /tmp, one folder per session).
    QVERIFY(!QDir(temp.path()).entryList({QStringLiteral("motionstyle-adapt-*")}, QDir::Dirs).isEmpty());
    window_owner.reset();
    const QStringList left = QDir(temp.path()).entryList(QDir::AllEntries | QDir::NoDotAndDotDot);
    QVERIFY2(left.isEmpty(), qPrintable(left.join(QStringLiteral(", "))));
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(FamiliarityTest)
#include "test_familiarity.moc"
