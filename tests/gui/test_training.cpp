// The "Style networks" panel in the real MainWindow: training-database role, bad input reported through
// the ErrorReporter, a short training run with progress, live loss curves and preview, Cancel within the
// issue's bound with a loadable checkpoint, save (never overwriting silently), Retrain as a warm start,
// the optimisation method, and closing the window during training.
//
// The loss network is a tiny loss network trained here on the two fixtures (a fraction of a second); the
// style networks have 8 hidden units, so each epoch takes milliseconds.
#include <QCloseEvent>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QDockWidget>
#include <QFile>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QThread>
#include <QTreeWidget>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/resource_paths.h"
#include "features/feature_layout.h"
#include "gui_test_support.h"
#include "loss_curve_widget.h"
#include "main_window.h"
#include "network_panel.h"
#include "result_panel.h"
#include "job_runner.h"
#include "style/style_training_job.h"
#include "nn/network_file.h"
#include "style/training.h"

using namespace motionstyle;

namespace {

// The bound is 1 s in the optimised build; AddressSanitizer slows every step several times.
#if defined(__SANITIZE_ADDRESS__)
constexpr qint64 kCancelBoundMs = 5000;
#else
constexpr qint64 kCancelBoundMs = 1000;
#endif
constexpr int kJobTimeoutMs = 60000;

using test::Report;

QByteArray readAll(const QString& path) {
  QFile file(path);
  return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray();
}

bool writeAll(const QString& path, const QByteArray& bytes) {
  QFile file(path);
  return file.open(QIODevice::WriteOnly) && file.write(bytes) == bytes.size();
}

// Largest weight difference between two transformation networks (parameters() is non-const: copies).
float maxAbsDifference(const nn::StyleModel& a, const nn::StyleModel& b) {
  float worst = 0.0f;
  nn::TransformationNetwork<float> ta = a.transformation;
  nn::TransformationNetwork<float> tb = b.transformation;
  const auto pa = ta.parameters();
  const auto pb = tb.parameters();
  if (pa.size() != pb.size()) return std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < pa.size(); ++i) {
    if (pa[i]->value.size() != pb[i]->value.size()) return std::numeric_limits<float>::infinity();
    worst = std::max(worst, (pa[i]->value - pb[i]->value).cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace

class TrainingTest : public QObject {
  Q_OBJECT

  QTemporaryDir scratch_;
  QString loss_network_;
  std::vector<Report> reports_;

  QString scratchFile(const QString& name) const { return scratch_.filePath(name); }

  // A window with both fixtures loaded (content cmu_131_01, style zombie), errors collected, and the
  // Confirmer answering `answer` (recorded in `asked`).
  std::unique_ptr<MainWindow> makeWindow() {
    auto window = std::make_unique<MainWindow>(/*persist_settings=*/false);
    window->setErrorReporter([this](const QString& title, const QString& message) { reports_.push_back({title, message}); });
    window->resize(1500, 950);
    window->show();
    if (!QTest::qWaitForWindowExposed(window.get())) return nullptr;
    if (window->openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh")), test::fixture(QStringLiteral("zombie.bvh"))}) != 2)
      return nullptr;
    return window;
  }

  static void setTinyForm(NetworkPanel* panel, int epochs, double learning_rate = 1e-3) {
    NetworkPanel::TrainingForm form = panel->trainingForm();
    form.epochs = epochs;
    form.learning_rate = learning_rate;
    form.hidden_units = 8;
    panel->setTrainingForm(form);
  }

 private slots:
  void initTestCase() {
    QVERIFY(scratch_.isValid());
    // The loss network: 16 hidden units, width 5, one epoch on the fixtures.
    style::LossNetworkTrainingConfig config;
    config.data = {test::fixture(QStringLiteral("cmu_131_01.bvh")).toStdString(),
                   test::fixture(QStringLiteral("zombie.bvh")).toStdString()};
    config.shape = {kFeatureCount, 16, 5};
    config.settings.epochs = 1;
    config.settings.batch_size = 8;
    config.settings.seed = 3;
    config.settings.windows = {60, 30};
    loss_network_ = scratchFile(QStringLiteral("tiny_ae.net"));
    config.settings.output = loss_network_.toStdString();
    const auto result = style::trainLossNetwork(config);
    QCOMPARE(result.status, style::TrainingStatus::Completed);
    QVERIFY(QFile::exists(loss_network_));
  }

  void init() { reports_.clear(); }

  void lossCurveSkipsWhatALogAxisCannotShowAndPaintsEachTerm() {
    LossCurveWidget curve;
    curve.resize(420, 220);
    curve.addPoint(QStringLiteral("style"), 0.5, std::nan(""));
    curve.addPoint(QStringLiteral("style"), 0.5, -1.0);
    curve.addPoint(QStringLiteral("style"), 0.5, 0.0);
    curve.addPoint(QStringLiteral("style"), std::numeric_limits<double>::infinity(), 1.0);
    QCOMPARE(curve.skippedPoints(), 4);
    QCOMPARE(curve.pointCount(QStringLiteral("style")), 0);
    QVERIFY(!curve.grab().toImage().isNull());  // paints "no values" without dividing by zero

    // A history (nn::LossHistory layout, a short row tolerated): one point per epoch and term.
    curve.setHistory({QStringLiteral("content"), QStringLiteral("style")}, {{1.0, 1e-3}, {0.5, 5e-4}, {0.25}});
    QCOMPARE(curve.skippedPoints(), 0);
    QCOMPARE(curve.pointCount(QStringLiteral("content")), 3);
    QCOMPARE(curve.pointCount(QStringLiteral("style")), 2);
    QCOMPARE(curve.terms(), (QStringList{QStringLiteral("content"), QStringLiteral("style")}));
    // Both curves are drawn in their colours, decades apart on the log axis.
    const QImage image = curve.grab().toImage();
    const auto count = [&](QColor colour) {
      int n = 0;
      for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
          const QColor pixel = image.pixelColor(x, y);
          n += std::abs(pixel.red() - colour.red()) + std::abs(pixel.green() - colour.green()) +
                   std::abs(pixel.blue() - colour.blue()) < 40;
        }
      return n;
    };
    QVERIFY(count(LossCurveWidget::termColor(QStringLiteral("content"))) > 50);
    QVERIFY(count(LossCurveWidget::termColor(QStringLiteral("style"))) > 50);
    QVERIFY(LossCurveWidget::termColor(QStringLiteral("content")) != LossCurveWidget::termColor(QStringLiteral("style")));
  }

  void divergenceComesBackAsAnErrorAndKeepsTheCheckpoint() {
    // The job on the runner's thread: a first run leaves a good checkpoint, a run with an absurd learning
    // rate diverges (the weights overflow) and reports it instead of finishing; the checkpoint is intact.
    style::StyleTrainingJob job;
    job.config.loss_network = loss_network_.toStdString();
    job.config.content = {test::fixture(QStringLiteral("cmu_131_01.bvh")).toStdString()};
    job.config.styles = {{std::nullopt, test::fixture(QStringLiteral("zombie.bvh")).toStdString()}};
    job.config.shape.hidden = 8;
    job.config.settings.epochs = 1;
    job.config.settings.batch_size = 1;  // several steps per epoch: the overflow shows within the epoch
    job.config.settings.checkpoint = scratchFile(QStringLiteral("diverge.checkpoint")).toStdString();
    job.config.settings.keep_checkpoint = true;
    const auto run = [](style::StyleTrainingJob config, QStringList* failures) {
      JobRunner runner;
      QSignalSpy finished(&runner, &JobRunner::finished);
      int completions = 0;
      QObject::connect(&runner, &JobRunner::failed, &runner,
                       [failures](const QString& title, const QString& message) { *failures << title + ": " + message; });
      runner.start(QStringLiteral("train"), [config, &completions](const JobRunner::Context& context) {
        const auto result = config.run(context.trainingCallbacks({}, {}));
        return JobRunner::Completion([&completions, result] { completions += result.model != nullptr; });
      });
      const bool ended = finished.wait(kJobTimeoutMs);
      return ended ? completions : -1;
    };
    QStringList failures;
    QCOMPARE(run(job, &failures), 1);
    QVERIFY2(failures.isEmpty(), qPrintable(failures.join(QLatin1Char('\n'))));
    const QByteArray checkpoint = readAll(scratchFile(QStringLiteral("diverge.checkpoint")));
    QVERIFY(!checkpoint.isEmpty());

    job.config.settings.learning_rate = 1e35;
    QCOMPARE(run(job, &failures), 0);
    QCOMPARE(failures.size(), 1);
    QVERIFY2(failures[0].startsWith(QStringLiteral("Training diverged")), qPrintable(failures[0]));
    QVERIFY2(failures[0].contains(QStringLiteral("diverge.checkpoint")), qPrintable(failures[0]));  // where to go back to
    QCOMPARE(readAll(scratchFile(QStringLiteral("diverge.checkpoint"))), checkpoint);
  }

  void trainingDatabaseRoleIsAssignedAndShown() {
    auto window = makeWindow();
    QVERIFY(window);
    QVERIFY(window->trainingClipPaths().isEmpty());
    QSignalSpy changed(window.get(), &MainWindow::clipsChanged);
    window->setTrainingClip(0, true);
    window->setTrainingClip(1, true);
    window->setTrainingClip(5, true);  // out of range: ignored
    QCOMPARE(window->trainingClipPaths().size(), 2);
    QVERIFY(changed.count() >= 2);
    QVERIFY2(window->clipList()->topLevelItem(0)->text(1).contains(QStringLiteral("training")),
             qPrintable(window->clipList()->topLevelItem(0)->text(1)));
    // Removing a clip keeps the role on the right clips.
    window->setTrainingClip(0, false);
    QCOMPARE(window->trainingClipPaths(), QStringList{window->clip(1).path});
    window->removeClip(0);
    QCOMPARE(window->trainingClipPaths(), QStringList{window->clip(0).path});
    QVERIFY(window->isTrainingClip(0));
    QVERIFY(reports_.empty());
  }

  void badInputIsReportedAndNothingStarts() {
    auto window = makeWindow();
    QVERIFY(window);
    NetworkPanel* panel = window->networkPanel();
    QVERIFY(panel != nullptr);
    // A fresh panel offers the shipped loss network when there is one (there is in this repository).
    const auto resources = resourceDirectory();
    const auto shipped = resources ? shippedNetworkFile(*resources, kShippedLossNetworkName) : std::nullopt;
    QCOMPARE(panel->lossNetworkFile(), shipped ? QString::fromStdString(shipped->string()) : QString());

    // Nothing to train on: no clip open (with clips open and none chosen, those but the Style clip are used).
    window->removeClip(1);
    window->removeClip(0);
    QVERIFY(!panel->startTraining(false));
    QCOMPARE(reports_.size(), std::size_t{1});
    QVERIFY(reports_.back().title.contains(QStringLiteral("training set"), Qt::CaseInsensitive));
    QCOMPARE(window->openFiles({test::fixture(QStringLiteral("cmu_131_01.bvh")), test::fixture(QStringLiteral("zombie.bvh"))}), 2);
    // No loss network.
    window->setTrainingClip(0, true);
    panel->setLossNetworkFile({});
    QVERIFY(!panel->startTraining(false));
    QVERIFY(reports_.back().title.contains(QStringLiteral("loss network"), Qt::CaseInsensitive));
    // Retrain without a selected network.
    QVERIFY(!panel->startTraining(true));
    QVERIFY(reports_.back().title.contains(QStringLiteral("network"), Qt::CaseInsensitive));
    QVERIFY(!panel->isBusy());

    // A corrupt and a truncated network file: an error dialog naming the file, not a crash.
    const QString garbage = scratchFile(QStringLiteral("garbage.net"));
    QVERIFY(writeAll(garbage, QByteArray("MSNETxxxx this is not a network\x01\x02\x03", 36)));
    QVERIFY(!panel->networkList()->loadNetworkFile(garbage));
    QVERIFY2(reports_.back().message.contains(QStringLiteral("garbage.net")), qPrintable(reports_.back().message));
    const QByteArray loss_network_bytes = readAll(loss_network_);
    const QString truncated = scratchFile(QStringLiteral("truncated.net"));
    QVERIFY(writeAll(truncated, loss_network_bytes.left(loss_network_bytes.size() / 2)));
    const std::size_t before = reports_.size();
    QVERIFY(!panel->networkList()->loadNetworkFile(truncated));
    QCOMPARE(reports_.size(), before + 1);
    QVERIFY(reports_.back().message.contains(QStringLiteral("truncated.net")));
    QCOMPARE(panel->networkList()->networkCount(), 0);

    // A loss network whose file is corrupt: the worker's error comes back as a dialog, and the panel is
    // idle and usable again.
    panel->setLossNetworkFile(garbage);
    setTinyForm(panel, 1);
    QSignalSpy finished(panel, &NetworkPanel::jobFinished);
    QVERIFY(panel->startTraining(false));
    QVERIFY(finished.wait(kJobTimeoutMs));
    QVERIFY(!panel->isBusy());
    QVERIFY2(reports_.back().message.contains(QStringLiteral("garbage.net")), qPrintable(reports_.back().message));
    QCOMPARE(panel->networkList()->networkCount(), 0);

    // A loss network file loaded in the panel becomes the loss network (it is not a style network).
    QVERIFY(panel->networkList()->loadNetworkFile(loss_network_));
    QCOMPARE(panel->lossNetworkFile(), QFileInfo(loss_network_).absoluteFilePath());
    QCOMPARE(panel->networkList()->networkCount(), 0);
  }

  void trainCancelSaveAndRetrain() {
    auto window = makeWindow();
    QVERIFY(window);
    NetworkPanel* panel = window->networkPanel();
    window->setTrainingClip(0, true);
    window->setTrainingClip(1, true);
    panel->setLossNetworkFile(loss_network_);
    setTinyForm(panel, 100000);  // far more than the test waits for: it ends by Cancel

    QSignalSpy progress(panel, &NetworkPanel::trainingProgress);
    QSignalSpy preview(panel, &NetworkPanel::previewReady);
    QSignalSpy finished(panel, &NetworkPanel::jobFinished);
    QSignalSpy current(panel->networkList(), &NetworkList::currentNetworkChanged);
    QVERIFY(panel->startTraining(false));
    QVERIFY(panel->isBusy());
    QVERIFY(!panel->startTraining(false));  // one job at a time
    reports_.clear();

    // Progress arrives (queued from the worker thread) with sane fields; an epoch completes, so the
    // checkpoint exists and the live preview reached the viewport as the blue output figure.
    QTRY_VERIFY_WITH_TIMEOUT(preview.count() >= 1, kJobTimeoutMs);
    QTRY_VERIFY_WITH_TIMEOUT(progress.count() >= 3, kJobTimeoutMs);
    bool saw_training_step = false;
    for (const QList<QVariant>& call : progress) {
      const auto p = call.at(0).value<style::TrainingProgress>();
      if (p.phase != style::TrainingProgress::Phase::Training) continue;
      saw_training_step = true;
      QCOMPARE(p.epochs, 100000);
      QVERIFY(p.step >= 1 && p.step <= p.steps_per_epoch);
      QCOMPARE(p.terms.size(), std::size_t{5});
      QCOMPARE(QString::fromStdString(p.terms[1].name), QStringLiteral("style"));
      QVERIFY(std::isfinite(p.total) && p.elapsed_seconds >= 0.0);
    }
    QVERIFY(saw_training_step);
    const auto shown = preview.back().at(0).value<FigureData>();
    QCOMPARE(shown.role, FigureRole::Output);
    QCOMPARE(shown.jointCount(), kCanonicalJointCount);
    bool viewport_has_output = false;
    for (int i = 0; i < window->viewport()->figureCount(); ++i)
      viewport_has_output |= window->viewport()->figure(i).role == FigureRole::Output;
    QVERIFY(viewport_has_output);
    QTRY_VERIFY_WITH_TIMEOUT(panel->lossCurve()->pointCount(QStringLiteral("content")) >= 2, kJobTimeoutMs);
    QVERIFY(panel->lossCurve()->terms().contains(QStringLiteral("trajectory")));
    QCOMPARE(panel->lossCurve()->xAxisName(), QStringLiteral("epochs"));
    QVERIFY(panel->progressBar()->maximum() > 0);
    QVERIFY(QFile::exists(panel->lastCheckpointFile()));
    QVERIFY(!test::saveScreenshot(window->grab().toImage(), QStringLiteral("during_training")).isEmpty());

    // Cancel (the button, as the user does) stops the run within the bound, thread joined.
    auto* cancel = panel->findChild<QPushButton*>(QStringLiteral("CancelButton"));
    QVERIFY(cancel != nullptr && cancel->isEnabled());
    QElapsedTimer clock;
    clock.start();
    QTest::mouseClick(cancel, Qt::LeftButton);
    QVERIFY(finished.wait(kJobTimeoutMs));
    const qint64 cancel_ms = clock.elapsed();
    qInfo("cancel took %lld ms", static_cast<long long>(cancel_ms));
    QVERIFY2(cancel_ms < kCancelBoundMs, qPrintable(QStringLiteral("cancel took %1 ms").arg(cancel_ms)));
    QVERIFY(!panel->isBusy());
    QVERIFY2(reports_.empty(), reports_.empty() ? "" : qPrintable(reports_.front().message));
    QVERIFY2(panel->statusText().startsWith(QStringLiteral("Training cancelled")), qPrintable(panel->statusText()));
    QCOMPARE(test::statusLine(*window), panel->statusText());  // the window's status bar says it too

    // The last completed epoch is kept: in the list (unsaved, current, announced) and as a loadable
    // checkpoint holding the same epoch count.
    QCOMPARE(panel->networkList()->networkCount(), 1);
    QVERIFY(!panel->networkList()->isNetworkSaved(0));
    QVERIFY(panel->networkList()->currentNetwork() != nullptr);
    QVERIFY(current.count() >= 1);
    const nn::StyleModel checkpoint = nn::loadStyleModel(panel->lastCheckpointFile().toStdString());
    QVERIFY(checkpoint.metadata.training.epochs >= 1);
    QCOMPARE(checkpoint.transformation.shape().hidden, 8);
    QVERIFY(panel->networkList()->currentNetwork()->metadata.training.epochs >= checkpoint.metadata.training.epochs);

    // The network list shows the metadata, and the result panel got the network to stylize with.
    auto* list = panel->findChild<QTreeWidget*>(QStringLiteral("NetworkList"));
    QVERIFY(list != nullptr && list->topLevelItemCount() == 1);
    QCOMPARE(list->topLevelItem(0)->text(1), QStringLiteral("zombie.bvh"));
    QCOMPARE(list->topLevelItem(0)->text(2), QString::number(panel->networkList()->currentNetwork()->metadata.training.epochs));
    QVERIFY(!list->topLevelItem(0)->text(3).isEmpty());  // created
    QVERIFY(window->resultPanel()->hasNetwork());
    QCOMPARE(window->resultPanel()->networkName(), panel->networkList()->currentNetworkName());

    // Save: atomic, and an existing file is never replaced without a Yes.
    const QString saved = scratchFile(QStringLiteral("trained.net"));
    int questions = 0;
    QMessageBox::StandardButton answer = QMessageBox::No;
    panel->setConfirmer([&](const QString&, const QString&, QMessageBox::StandardButtons) {
      ++questions;
      return answer;
    });
    QVERIFY(panel->networkList()->saveNetwork(0, saved));
    QCOMPARE(questions, 0);
    QVERIFY(panel->networkList()->isNetworkSaved(0));
    const QByteArray saved_bytes = readAll(saved);
    const nn::StyleModel reloaded = nn::loadStyleModel(saved.toStdString());
    QCOMPARE(maxAbsDifference(reloaded, *panel->networkList()->currentNetwork()), 0.0f);
    QVERIFY(!panel->networkList()->saveNetwork(0, saved));  // exists, answer No
    QCOMPARE(questions, 1);
    QCOMPARE(readAll(saved), saved_bytes);
    answer = QMessageBox::Yes;
    QVERIFY(panel->networkList()->saveNetwork(0, saved));
    QCOMPARE(questions, 2);
    const QByteArray resaved = readAll(saved);
    QVERIFY(!resaved.isEmpty());

    // Retrain from the saved network with new weights and a tiny learning rate: the result starts
    // from the saved weights (a fresh initialisation would be far away), keeps the network's shape
    // (hidden units 8 even though the form says 16) and records the new weights.
    NetworkPanel::TrainingForm form = panel->trainingForm();
    form.weights.style = 7.0;
    form.epochs = 2;
    form.learning_rate = 1e-6;
    form.hidden_units = 16;
    panel->setTrainingForm(form);
    panel->networkList()->setCurrentIndex(0);
    QVERIFY(panel->startTraining(true));
    QVERIFY(finished.wait(kJobTimeoutMs));
    QVERIFY2(reports_.empty(), reports_.empty() ? "" : qPrintable(reports_.front().message));
    QCOMPARE(panel->networkList()->networkCount(), 2);
    const auto retrained = panel->networkList()->network(1);
    QCOMPARE(panel->networkList()->currentIndex(), 1);
    QCOMPARE(retrained->metadata.training.epochs, 2);
    QCOMPARE(retrained->metadata.training.weights.style, 7.0);
    QCOMPARE(retrained->transformation.shape().hidden, 8);
    const float moved = maxAbsDifference(*retrained, reloaded);
    QVERIFY2(moved > 0.0f && moved < 1e-3f, qPrintable(QString::number(static_cast<double>(moved))));
    QCOMPARE(readAll(saved), resaved);  // retraining never writes the file it started from

    // Dropping the unsaved retrained network asks first; "Cancel" keeps it.
    answer = QMessageBox::Cancel;
    QVERIFY(!panel->networkList()->removeNetwork(1));
    QCOMPARE(panel->networkList()->networkCount(), 2);
    answer = QMessageBox::Discard;
    QSignalSpy announced(panel->networkList(), &NetworkList::currentNetworkChanged);
    QVERIFY(panel->networkList()->removeNetwork(1));
    QCOMPARE(panel->networkList()->networkCount(), 1);
    QCOMPARE(announced.count(), 1);  // the result panel hears that the saved network is current again
    QCOMPARE(announced.back().at(0).value<std::shared_ptr<const nn::StyleModel>>(), panel->networkList()->network(0));
    QCOMPARE(window->resultPanel()->networkName(), panel->networkList()->currentNetworkName());

    // A saved network goes without a question; loaded again, its loss history is drawn per epoch.
    const int asked_before = questions;
    QVERIFY(panel->networkList()->removeNetwork(0));
    QCOMPARE(questions, asked_before);
    QCOMPARE(panel->networkList()->networkCount(), 0);
    QVERIFY(panel->networkList()->loadNetworkFile(saved));
    QCOMPARE(panel->networkList()->networkCount(), 1);
    QVERIFY(panel->networkList()->isNetworkSaved(0));
    QCOMPARE(panel->networkList()->networkFile(0), QFileInfo(saved).absoluteFilePath());
    const auto epochs = static_cast<int>(panel->networkList()->currentNetwork()->metadata.loss_history.epochs.size());
    QVERIFY(epochs >= 1);
    QCOMPARE(panel->lossCurve()->pointCount(QStringLiteral("content")), epochs);
    QCOMPARE(panel->lossCurve()->pointCount(QStringLiteral("total")), epochs);
  }

  void cancelledTrainingResumesFromItsCheckpoint() {
    // Issue 14: a cancelled training can be resumed in the app, as --resume does in the CLI.
    auto window = makeWindow();
    QVERIFY(window);
    NetworkPanel* panel = window->networkPanel();
    window->setTrainingClip(0, true);
    panel->setLossNetworkFile(loss_network_);
    setTinyForm(panel, 100000);
    auto* resume = panel->findChild<QPushButton*>(QStringLiteral("ResumeButton"));
    auto* cancel = panel->findChild<QPushButton*>(QStringLiteral("CancelButton"));
    QVERIFY(resume != nullptr && cancel != nullptr);
    QVERIFY(!resume->isEnabled());  // nothing to resume yet
    QSignalSpy progress(panel, &NetworkPanel::trainingProgress);
    QSignalSpy finished(panel, &NetworkPanel::jobFinished);
    QVERIFY(panel->startTraining(false));
    QVERIFY(!resume->isEnabled());
    const auto epochs_closed = [&] {
      int last = 0;
      for (const QList<QVariant>& call : progress) {
        const auto p = call.at(0).value<style::TrainingProgress>();
        if (p.phase == style::TrainingProgress::Phase::EpochEnd) last = std::max(last, p.epoch);
      }
      return last;
    };
    QTRY_VERIFY_WITH_TIMEOUT(epochs_closed() >= 2, kJobTimeoutMs);
    QTest::mouseClick(cancel, Qt::LeftButton);
    QVERIFY(finished.wait(kJobTimeoutMs));
    QCOMPARE(panel->networkList()->networkCount(), 1);
    const int kept = panel->networkList()->network(0)->metadata.training.epochs;
    const QString run_name = panel->networkList()->currentNetworkName().section(QStringLiteral(" (epoch"), 0, 0);
    QVERIFY(kept >= 2);
    QVERIFY(resume->isEnabled());

    // Resume: the run goes on from the epoch after the checkpoint, with the same name.
    progress.clear();
    QTest::mouseClick(resume, Qt::LeftButton);
    QVERIFY(panel->isBusy());
    QVERIFY(!resume->isEnabled());
    QTRY_VERIFY_WITH_TIMEOUT(epochs_closed() >= kept + 2, kJobTimeoutMs);
    int first_epoch = 0;
    for (const QList<QVariant>& call : progress) {
      const auto p = call.at(0).value<style::TrainingProgress>();
      if (p.phase != style::TrainingProgress::Phase::Loading) {
        first_epoch = p.epoch;
        break;
      }
    }
    QVERIFY2(first_epoch > kept, qPrintable(QStringLiteral("resumed at epoch %1, kept %2").arg(first_epoch).arg(kept)));
    QTest::mouseClick(cancel, Qt::LeftButton);
    QVERIFY(finished.wait(kJobTimeoutMs));
    QVERIFY2(reports_.empty(), reports_.empty() ? "" : qPrintable(reports_.front().message));
    QCOMPARE(panel->networkList()->networkCount(), 2);
    QVERIFY(panel->networkList()->network(1)->metadata.training.epochs >= kept + 2);
    QCOMPARE(panel->networkList()->currentNetworkName().section(QStringLiteral(" (epoch"), 0, 0), run_name);
  }

  void networksAreRenamedInTheListAndTheNewNameIsShownEverywhere() {
    // Issue 14: names are editable (F2 on the list, as a user does) and shown everywhere: the list,
    // the Result panel's Style choice and its figures, the close prompt.
    auto window = makeWindow();
    QVERIFY(window);
    window->resize(1400, 900);
    window->show();
    QVERIFY(QTest::qWaitForWindowExposed(window.get()));
    NetworkPanel* panel = window->networkPanel();
    window->setTrainingClip(0, true);
    panel->setLossNetworkFile(loss_network_);
    setTinyForm(panel, 1);
    QSignalSpy finished(panel, &NetworkPanel::jobFinished);
    for (int run = 0; run < 2; ++run) {
      QVERIFY(panel->startTraining(false));
      QVERIFY(finished.wait(kJobTimeoutMs));
    }
    QCOMPARE(panel->networkList()->networkCount(), 2);
    panel->networkList()->setCurrentIndex(0);
    const QString first_name = panel->networkList()->currentNetworkName();
    panel->networkList()->setCurrentIndex(1);
    auto* list = panel->findChild<QTreeWidget*>(QStringLiteral("NetworkList"));
    QVERIFY(list != nullptr);
    auto* dock = window->findChild<QDockWidget*>(QStringLiteral("NetworksDock"));
    QVERIFY(dock != nullptr);
    dock->raise();
    panel->findChild<QTabWidget*>()->setCurrentIndex(0);
    QTRY_VERIFY(list->isVisible());
    list->setFocus();
    list->setCurrentItem(list->topLevelItem(1), 0);
    QTest::keyClick(list, Qt::Key_F2);
    auto* editor = list->findChild<QLineEdit*>();
    QVERIFY2(editor != nullptr, "F2 opens no editor on the name");
    QVERIFY(!editor->text().endsWith(QStringLiteral(" *")));  // the name, not the unsaved mark
    editor->selectAll();
    QTest::keyClicks(editor, QStringLiteral("walk fast"));
    QTest::keyClick(editor, Qt::Key_Return);
    QTRY_COMPARE(panel->networkList()->currentNetworkName(), QStringLiteral("walk fast"));
    QCOMPARE(window->resultPanel()->networkName(), QStringLiteral("walk fast"));
    QVERIFY(window->resultPanel()->networkChoice()->findText(QStringLiteral("walk fast")) >= 0);
    QCOMPARE(window->resultPanel()->networkChoice()->currentText(), QStringLiteral("walk fast"));
    QVERIFY(list->topLevelItem(1)->text(0).startsWith(QStringLiteral("walk fast")));

    // A taken or empty name is refused with a reason, and the old name stays.
    reports_.clear();
    QVERIFY(!panel->networkList()->renameNetwork(1, first_name));
    QVERIFY(!panel->networkList()->renameNetwork(1, QStringLiteral("   ")));
    QCOMPARE(reports_.size(), std::size_t{2});
    QCOMPARE(panel->networkList()->currentNetworkName(), QStringLiteral("walk fast"));

    // The close prompt lists the new name.
    QStringList asked;
    panel->setConfirmer([&](const QString&, const QString& text, QMessageBox::StandardButtons) {
      asked << text;
      return QMessageBox::Cancel;
    });
    QVERIFY(!panel->prepareToClose());
    QCOMPARE(asked.size(), 1);
    QVERIFY2(asked[0].contains(QStringLiteral("walk fast")), qPrintable(asked[0]));
    panel->setConfirmer([](const QString&, const QString&, QMessageBox::StandardButtons) { return QMessageBox::Discard; });

    // Saved under a file name, the network is named after the file, everywhere; a name another
    // network has gets a counter. (The Result panel kept the old name, and two networks could share one.)
    QTemporaryDir saved;
    QVERIFY(panel->networkList()->saveNetwork(1, saved.filePath(QStringLiteral("brisk.net"))));
    QCOMPARE(panel->networkList()->currentNetworkName(), QStringLiteral("brisk"));
    QCOMPARE(window->resultPanel()->networkName(), QStringLiteral("brisk"));
    QVERIFY(panel->networkList()->saveNetwork(1, saved.filePath(first_name + QStringLiteral(".net"))));
    QCOMPARE(panel->networkList()->currentNetworkName(), first_name + QStringLiteral(" (2)"));
    QCOMPARE(window->resultPanel()->networkName(), first_name + QStringLiteral(" (2)"));
    QVERIFY(window->resultPanel()->networkChoice()->findText(first_name + QStringLiteral(" (2)")) >= 0);
  }

  void aFolderAsTrainingDatabaseTrainsToCompletion() {
    auto window = makeWindow();
    QVERIFY(window);
    NetworkPanel* panel = window->networkPanel();
    panel->addTrainingFolder(scratchFile(QStringLiteral("no-such-folder")));
    QCOMPARE(reports_.size(), std::size_t{1});
    QVERIFY(reports_.back().message.contains(QStringLiteral("no-such-folder")));
    QVERIFY(panel->trainingFolders().isEmpty());

    // A folder holding one good clip and one broken file: the broken one is skipped (logged), not fatal.
    const QString folder = scratchFile(QStringLiteral("database"));
    QVERIFY(QDir().mkpath(folder));
    QVERIFY(QFile::copy(test::fixture(QStringLiteral("cmu_131_01.bvh")), folder + QStringLiteral("/walk.bvh")));
    QVERIFY(writeAll(folder + QStringLiteral("/broken.bvh"), QByteArray("HIERARCHY\nROOT Hips\n{\n")));
    panel->addTrainingFolder(folder);
    panel->addTrainingFolder(folder);  // listed once
    QCOMPARE(panel->trainingFolders(), QStringList{QDir(folder).absolutePath()});
    QVERIFY(window->trainingClipPaths().isEmpty());
    panel->setLossNetworkFile(loss_network_);
    setTinyForm(panel, 3);
    QSignalSpy finished(panel, &NetworkPanel::jobFinished);
    reports_.clear();
    QVERIFY(panel->startTraining(false));
    QVERIFY(finished.wait(kJobTimeoutMs));
    QVERIFY2(reports_.empty(), reports_.empty() ? "" : qPrintable(reports_.front().message));
    QCOMPARE(panel->networkList()->networkCount(), 1);
    QVERIFY(!panel->networkList()->isNetworkSaved(0));
    QCOMPARE(panel->networkList()->network(0)->metadata.training.epochs, 3);
    QCOMPARE(panel->networkList()->network(0)->metadata.loss_history.epochs.size(), std::size_t{3});
    QVERIFY2(panel->statusText().startsWith(QStringLiteral("Trained")), qPrintable(panel->statusText()));
    QCOMPARE(test::statusLine(*window), panel->statusText());
    QCOMPARE(panel->progressBar()->value(), panel->progressBar()->maximum());
    QCOMPARE(panel->progressBar()->format(), QStringLiteral("Done"));

    // Issue 14: a second run from the same clips gets a name of its own, and the Result panel offers both.
    setTinyForm(panel, 1);
    QVERIFY(panel->startTraining(false));
    QVERIFY(finished.wait(kJobTimeoutMs));
    QCOMPARE(panel->networkList()->networkCount(), 2);
    panel->networkList()->setCurrentIndex(0);
    const QString first = panel->networkList()->currentNetworkName();
    panel->networkList()->setCurrentIndex(1);
    const QString second = panel->networkList()->currentNetworkName();
    QVERIFY2(first != second, qPrintable(first));
    const QComboBox* choice = window->resultPanel()->networkChoice();
    QVERIFY(choice->findText(first) >= 0);
    QVERIFY(choice->findText(second) >= 0);

    // Issue 14: closing asks once for all unsaved networks; "Save All" writes each into one folder.
    QStringList asked;
    panel->setConfirmer([&](const QString& title, const QString&, QMessageBox::StandardButtons buttons) {
      asked << title;
      return buttons.testFlag(QMessageBox::SaveAll) ? QMessageBox::SaveAll : QMessageBox::Cancel;
    });
    const QString saved_folder = scratchFile(QStringLiteral("saved_networks"));
    QVERIFY(QDir().mkpath(saved_folder));
    panel->networkList()->setFolderChooser([&](const QString&) { return saved_folder; });
    QVERIFY(panel->prepareToClose());
    QCOMPARE(asked.size(), 1);
    QVERIFY(panel->networkList()->isNetworkSaved(0) && panel->networkList()->isNetworkSaved(1));
    QCOMPARE(QDir(saved_folder).entryList({QStringLiteral("*.net")}, QDir::Files).size(), 2);
    QVERIFY(panel->prepareToClose());  // nothing unsaved any more: no question
    QCOMPARE(asked.size(), 1);
  }

  void optimisationMethodRunsInTheWorker() {
    auto window = makeWindow();
    QVERIFY(window);
    NetworkPanel* panel = window->networkPanel();
    panel->setLossNetworkFile(loss_network_);
    QSignalSpy ready(panel, &NetworkPanel::stylizedClipReady);
    QSignalSpy finished(panel, &NetworkPanel::jobFinished);
    panel->lossCurve()->addPoint(QStringLiteral("total"), 0.0, 1.0);  // as a previous training leaves it
    QVERIFY(panel->startTransfer(5));
    QCOMPARE(panel->lossCurve()->pointCount(QStringLiteral("total")), 0);  // the plot is this run's
    QVERIFY(finished.wait(kJobTimeoutMs));
    QVERIFY(panel->lossCurve()->pointCount(QStringLiteral("style")) > 0);
    QCOMPARE(panel->lossCurve()->xAxisName(), QStringLiteral("iterations"));  // not "epochs": none here
    QCOMPARE(panel->progressBar()->value(), panel->progressBar()->maximum());  // a run that ended, said so
    QCOMPARE(panel->progressBar()->format(), QStringLiteral("Done"));
    QVERIFY2(reports_.empty(), reports_.empty() ? "" : qPrintable(reports_.front().message));
    QCOMPARE(ready.count(), 1);
    const auto clip = ready.front().at(0).value<style::StylizedClip>();
    QVERIFY(clip.frameCount() > 0);
    QVERIFY(clip.world_positions.allFinite());
    // The result panel takes the optimised clip for its clean-up and shows it.
    QTRY_VERIFY_WITH_TIMEOUT(window->resultPanel()->result() != nullptr, kJobTimeoutMs);
    QTRY_VERIFY_WITH_TIMEOUT(!window->resultPanel()->isBusy(), kJobTimeoutMs);
    const Eigen::MatrixXd few = window->resultPanel()->result()->stylized.world_positions;

    // More iterations move the clip further: the result shown is the new run's (issue 14 found the
    // Iterations field made no difference in the app).
    QVERIFY(panel->startTransfer(60));
    QVERIFY(finished.wait(kJobTimeoutMs));
    QCOMPARE(ready.count(), 2);
    QTRY_VERIFY_WITH_TIMEOUT(!window->resultPanel()->isBusy(), kJobTimeoutMs);
    const Eigen::MatrixXd more = window->resultPanel()->result()->stylized.world_positions;
    QCOMPARE(more.rows(), few.rows());
    const double moved = (more - few).cwiseAbs().maxCoeff();
    qInfo("5 vs 60 iterations: the raw output differs by up to %.3f file units", moved);
    QVERIFY(moved > 1e-3);

    // The style weight is the form's: the same run without style pull gives another clip.
    auto* style_weight = panel->findChild<QDoubleSpinBox*>(QStringLiteral("OptimiseStyleWeight"));
    QVERIFY(style_weight != nullptr);
    style_weight->setValue(0.0);
    QVERIFY(panel->startTransfer(60));
    QVERIFY(finished.wait(kJobTimeoutMs));
    QCOMPARE(ready.count(), 3);
    QTRY_VERIFY_WITH_TIMEOUT(!window->resultPanel()->isBusy(), kJobTimeoutMs);
    QVERIFY((window->resultPanel()->result()->stylized.world_positions - more).cwiseAbs().maxCoeff() > 1e-3);

    // Cancelled at once: no result, no error, idle again.
    QVERIFY(panel->startTransfer(100000));
    panel->cancelJob();
    QVERIFY(finished.wait(kJobTimeoutMs));
    QCOMPARE(ready.count(), 3);
    QVERIFY(!panel->isBusy());
    QVERIFY(reports_.empty());
    QCOMPARE(panel->progressBar()->value(), panel->progressBar()->minimum());  // not a full bar after a cancel
    QCOMPARE(panel->progressBar()->format(), QStringLiteral("Idle"));
  }

  // Train, Retrain, Cancel and Resume under the Optimise and Adapt forms, beside their own Optimise
  // and Adapt buttons, read as the way to run those: they show there only while a training runs.
  void theTrainingButtonsShowWhereTheyApply() {
    auto window = makeWindow();
    QVERIFY(window);
    NetworkPanel* panel = window->networkPanel();
    auto* tabs = panel->findChild<QTabWidget*>();
    auto* train = panel->findChild<QPushButton*>(QStringLiteral("TrainButton"));
    auto* cancel = panel->findChild<QPushButton*>(QStringLiteral("CancelButton"));
    QVERIFY(tabs != nullptr && train != nullptr && cancel != nullptr);
    const auto shownOn = [&](const QString& tab) {
      for (int i = 0; i < tabs->count(); ++i)
        if (tabs->tabText(i).remove(QLatin1Char('&')) == tab) tabs->setCurrentIndex(i);
      return train->isVisibleTo(panel) && cancel->isVisibleTo(panel);
    };
    QVERIFY(shownOn(QStringLiteral("Networks")));
    QVERIFY(shownOn(QStringLiteral("Train")));
    QVERIFY(!shownOn(QStringLiteral("Optimise")));
    QVERIFY(panel->lossCurve()->isVisibleTo(panel));  // it plots the optimisation
    QVERIFY(!shownOn(QStringLiteral("Adapt")));
    QVERIFY(!panel->lossCurve()->isVisibleTo(panel));  // the Adapt form has its own progress and results
    window->setTrainingClip(0, true);
    window->setTrainingClip(1, true);
    panel->setLossNetworkFile(loss_network_);
    setTinyForm(panel, 100000);
    QSignalSpy finished(panel, &NetworkPanel::jobFinished);
    QVERIFY(panel->startTraining(false));  // shows the Train tab
    QVERIFY(shownOn(QStringLiteral("Adapt")));  // its Cancel stays in reach
    cancel->click();
    QVERIFY(finished.wait(kJobTimeoutMs));
    QVERIFY(!shownOn(QStringLiteral("Adapt")));
  }

  void closingDuringTrainingAsksAndStopsCleanly() {
    auto window = makeWindow();
    QVERIFY(window);
    NetworkPanel* panel = window->networkPanel();
    window->setTrainingClip(0, true);
    panel->setLossNetworkFile(loss_network_);
    setTinyForm(panel, 100000);
    QStringList asked;
    QMessageBox::StandardButton stop_answer = QMessageBox::No;
    panel->setConfirmer([&](const QString& title, const QString&, QMessageBox::StandardButtons buttons) {
      asked << title;
      if (buttons.testFlag(QMessageBox::Discard)) return QMessageBox::Discard;  // the unsaved network
      return stop_answer;
    });
    QSignalSpy snapshots(panel, &NetworkPanel::previewReady);
    // Issue 14: the run buttons stay where they were when training starts (a moving Cancel was missed).
    auto* cancel = panel->findChild<QPushButton*>(QStringLiteral("CancelButton"));
    QVERIFY(cancel != nullptr);
    // Where a user clicking Train is: the panel's dock raised, its Train tab shown.
    for (QWidget* ancestor = panel->parentWidget(); ancestor != nullptr; ancestor = ancestor->parentWidget())
      if (ancestor->inherits("QDockWidget")) ancestor->raise();
    panel->findChild<QTabWidget*>()->setCurrentIndex(1);
    QTest::qWait(50);
    const QPoint cancel_before = cancel->mapTo(window.get(), QPoint(0, 0));
    QVERIFY(panel->startTraining(false));
    QTRY_VERIFY_WITH_TIMEOUT(snapshots.count() >= 1, kJobTimeoutMs);
    QCOMPARE(cancel->mapTo(window.get(), QPoint(0, 0)), cancel_before);
    QVERIFY(cancel->isVisible() && cancel->isEnabled());
    const auto outputShown = [&] {
      for (int i = 0; i < window->viewport()->figureCount(); ++i)
        if (window->viewport()->figure(i).role == FigureRole::Output) return true;
      return false;
    };
    QVERIFY(outputShown());
    // Another content clip makes the preview (of the first one) stale: it leaves the viewport.
    window->setContentClip(1);
    QVERIFY(!outputShown());

    // "No": the window stays and training goes on.
    QVERIFY(!window->close());
    QCOMPARE(asked.size(), 1);
    QVERIFY(window->isVisible());
    QVERIFY(panel->isBusy());

    // "Yes": cancel, quit, wait, then the unsaved network of the last epoch is offered (Discard).
    stop_answer = QMessageBox::Yes;
    QElapsedTimer clock;
    clock.start();
    QVERIFY(window->close());
    const qint64 close_ms = clock.elapsed();
    qInfo("close during training took %lld ms", static_cast<long long>(close_ms));
    QVERIFY2(close_ms < kCancelBoundMs, qPrintable(QStringLiteral("closing took %1 ms").arg(close_ms)));
    QVERIFY(!panel->isBusy());
    QCOMPARE(asked.size(), 3);  // stop?, then save the cancelled run's network?
    QCOMPARE(panel->networkList()->networkCount(), 1);
    const nn::StyleModel checkpoint = nn::loadStyleModel(panel->lastCheckpointFile().toStdString());
    QVERIFY(checkpoint.metadata.training.epochs >= 1);
    QVERIFY2(reports_.empty(), reports_.empty() ? "" : qPrintable(reports_.front().message));
  }
};

MOTIONSTYLE_GUI_TEST_MAIN(TrainingTest)
#include "test_training.moc"
