// An animator's path through "Aim at" (AimChoice, style/locomotion_kind.h): the shipped elderly network
// on the CMU walk sample aims at the style's walk, read from the clip; the animator picks the style's
// run from the control with the keyboard, as a user does; the result follows at once, is the one
// `motionstyle-cli stylize --kind run` gives (the same network told the kind), and the status says it
// was chosen; the choice stays with the clip, not with the next one opened; back to "Read from the
// clip", the first result comes back. Before any result, the first entry names the kind read ("Read
// from the clip: walk"), the one the result then aims at.
#include <QComboBox>
#include <QSignalSpy>

#include <filesystem>

#include "aim_choice.h"
#include "common/resource_paths.h"
#include "features/representation.h"
#include "gui_test_support.h"
#include "main_window.h"
#include "result_panel.h"
#include "style/locomotion_kind.h"
#include "style/training.h"
#include "tiny_style_network.h"

using namespace motionstyle;

class AimTest : public QObject {
  Q_OBJECT

 private slots:
  void theStyleClipAimedAtIsReadFromTheClipOrChosen() {
    const auto resources = resourceDirectory();
    QVERIFY2(resources.has_value(), "the repository's resources/ was not found");
    const auto network = shippedNetworkFile(*resources, "elderly");
    QVERIFY(network.has_value());
    const std::filesystem::path sample = *resources / "samples" / "cmu_131_01_walk.bvh";

    MainWindow window(false);
    window.setErrorReporter([](const QString& title, const QString& message) { QFAIL(qPrintable(title + message)); });
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    ResultPanel* panel = window.resultPanel();
    QSignalSpy ended(panel, &ResultPanel::jobEnded);
    QCOMPARE(window.openFiles({QString::fromStdString(sample.string())}), 1);
    QVERIFY(panel->loadNetworkFile(QString::fromStdString(network->string())));
    // Before any result the control says what it reads from the clip, as `info` does.
    auto* aim = panel->findChild<QComboBox*>(QStringLiteral("AimChoice"));
    QVERIFY(aim != nullptr && aim->isEnabled());
    QCOMPARE(aim->currentText(), QStringLiteral("Read from the clip: walk"));
    panel->stylize();
    QVERIFY(test::waitForJobs(ended));
    QVERIFY2(test::statusLine(window).contains(QStringLiteral("Aimed at the style's walk (read from the clip).")),
             qPrintable(test::statusLine(window)));
    const auto read = panel->result();
    QCOMPARE(read->stylized.kind, std::string("walk"));
    const Eigen::MatrixXd walk_features = read->stylized.features;

    // The animator picks the style's run: focus on the control, two steps down (walk, run).
    aim->setFocus();
    const int jobs = static_cast<int>(ended.count());
    QTest::keyClick(aim, Qt::Key_Down);
    QTest::keyClick(aim, Qt::Key_Down);
    QCOMPARE(aim->currentText(), QStringLiteral("The style's run"));
    QCOMPARE(panel->aimKind(), std::string("run"));
    QVERIFY(test::waitForJobs(ended, jobs + 1));
    QTRY_VERIFY_WITH_TIMEOUT(!panel->isBusy() && panel->result()->stylized.kind == "run", 60000);
    QVERIFY2(test::statusLine(window).contains(QStringLiteral("Aimed at the style's run (chosen under Aim at).")),
             qPrintable(test::statusLine(window)));

    // What the CLI's --kind run gives: the same network told the kind, on the same clip.
    const style::Stylizer told(style::loadCompatibleStyleModel(*network), network->string());
    const LoadedClip& clip = window.clip(0);
    const MotionFeatures features = extractFeatures(clip.motion, *clip.mapping);
    const Eigen::MatrixXd run_features = panel->result()->stylized.features;
    QVERIFY(run_features == told.stylize(features, 1.0, style::PathMode::Content, "run").features);
    const double moved = (run_features - walk_features).cwiseAbs().maxCoeff();
    qInfo("elderly on the CMU walk sample, aimed at the style's run: features move up to %.2f from the walk's", moved);
    QVERIFY2(moved > 1.0, "aiming at the style's run changed nothing");

    // The kind belongs to the clip: another content clip is read from itself, and the first one, made
    // the content again, has its choice back.
    const std::filesystem::path zombie = *resources / "samples" / "zombie_walk.bvh";
    QCOMPARE(window.openFiles({QString::fromStdString(zombie.string())}), 1);
    window.setContentClip(1);
    const LoadedClip& zombie_clip = window.clip(1);
    const MotionFeatures zombie_features = extractFeatures(zombie_clip.motion, *zombie_clip.mapping);
    const std::string zombie_kind = style::locomotionKind(zombie_features.values, zombie_features.contacts);
    QCOMPARE(aim->currentText(),
             QStringLiteral("Read from the clip: ") + QString::fromStdString(style::locomotionKindText(zombie_kind)));
    QCOMPARE(panel->aimKind(), std::string());
    window.setContentClip(0);
    QCOMPARE(aim->currentText(), QStringLiteral("The style's run"));
    panel->stylize();
    QTRY_VERIFY_WITH_TIMEOUT(!panel->isBusy() && panel->result() && panel->result()->stylized.kind == "run", 60000);
    QVERIFY(panel->result()->stylized.features == run_features);

    // Back to the clip's own reading: the first result again, bit for bit (computed again: the panel
    // remembers one result per network, RecentResults).
    QTest::keyClick(aim, Qt::Key_Up);
    QTest::keyClick(aim, Qt::Key_Up);
    QCOMPARE(panel->aimKind(), std::string());
    QTRY_VERIFY_WITH_TIMEOUT(!panel->isBusy() && panel->result()->stylized.kind == "walk", 60000);
    QVERIFY(panel->result()->stylized.features == walk_features);
    QVERIFY2(test::statusLine(window).contains(QStringLiteral("(read from the clip).")), qPrintable(test::statusLine(window)));
  }

  // The first entry names the kind read from the clip, whichever it is, and only that: no clip, no kind.
  void theFirstEntryNamesTheKindReadFromTheClip() {
    AimChoice aim;
    aim.showChoiceFor(QStringLiteral("/clips/turn.bvh"), "walk-turn-left");
    QCOMPARE(aim.currentText(), QStringLiteral("Read from the clip: walk turning left"));
    QCOMPARE(aim.kind(), std::string());
    aim.setCurrentIndex(aim.findData(QStringLiteral("run")));
    QCOMPARE(aim.kind(), std::string("run"));
    aim.showChoiceFor(QStringLiteral("/clips/stand.bvh"), "walk");
    QCOMPARE(aim.currentText(), QStringLiteral("Read from the clip: walk"));
    aim.showChoiceFor(QString(), "");
    QCOMPARE(aim.currentText(), QStringLiteral("Read from the clip"));
    aim.showChoiceFor(QStringLiteral("/clips/turn.bvh"), "walk-turn-left");
    QCOMPARE(aim.currentText(), QStringLiteral("The style's run"));
    QCOMPARE(aim.itemText(0), QStringLiteral("Read from the clip: walk turning left"));
  }

  // A network without stored style targets (a file before format 3) has no refinement to aim: the
  // control is greyed while it is the chosen style.
  void aNetworkWithoutStyleTargetsHasNothingToAim() {
    MainWindow window(false);
    ResultPanel* panel = window.resultPanel();
    auto* aim = panel->findChild<QComboBox*>(QStringLiteral("AimChoice"));
    QVERIFY(aim != nullptr && aim->isEnabled());
    nn::StyleModel model = test::tinyStyleModel();
    QVERIFY(model.style_targets.empty());
    panel->setStyleNetwork(std::make_shared<const nn::StyleModel>(model), QStringLiteral("no targets"));
    QVERIFY(!aim->isEnabled());
    model.style_targets.push_back({"walk", nn::Mat<float>::Zero(model.loss_network.shape().hidden,
                                                                  model.loss_network.shape().hidden)});
    panel->setStyleNetwork(std::make_shared<const nn::StyleModel>(model), QStringLiteral("a walk target"));
    QVERIFY(aim->isEnabled());
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(AimTest)
#include "test_aim.moc"
