// Files the app reads are hostile (issue 13): a shipped network file that cannot be read is listed
// disabled, with the reason, in the Result panel's Style choice and the Adapt tab, and choosing it is
// impossible; a clip that fails validation (no frames, a flat skeleton) is reported and not listed as
// loaded. Bad files first, then the good one beside them still works.
#include <QComboBox>
#include <QFile>
#include <QListWidget>
#include <QStandardItemModel>
#include <QTemporaryDir>

#include "adapt_tab.h"
#include "common/resource_paths.h"
#include "gui_test_support.h"
#include "main_window.h"
#include "network_panel.h"
#include "result_panel.h"

using namespace motionstyle;

namespace {

using test::Report;

// A copy of `fixture` whose text is changed by `edit`.
QString editedCopy(const QTemporaryDir& dir, const QString& fixture, const QString& name,
                   const std::function<QByteArray(QByteArray)>& edit) {
  QFile in(test::fixture(fixture));
  if (!in.open(QIODevice::ReadOnly)) return {};
  QFile out(dir.filePath(name));
  if (!out.open(QIODevice::WriteOnly)) return {};
  out.write(edit(in.readAll()));
  return out.fileName();
}

}  // namespace

class UntrustedFilesTest : public QObject {
  Q_OBJECT

 private slots:
  void initTestCase() {
    QVERIFY(resources_.isValid());
    QDir(resources_.path()).mkpath(QStringLiteral("models"));
    QDir(resources_.path()).mkpath(QStringLiteral("samples"));  // a resources folder has both
    const auto shipped = resourceDirectory();
    QVERIFY2(shipped.has_value(), "the repository's resources/ were not found");
    QVERIFY(QFile::copy(QString::fromStdString((*shipped / "models" / "elderly.net").string()),
                        resources_.filePath(QStringLiteral("models/elderly.net"))));
    QFile broken(resources_.filePath(QStringLiteral("models/broken.net")));
    QVERIFY(broken.open(QIODevice::WriteOnly));
    broken.write("MSNETWORK but not really");
    broken.close();
    qputenv(kResourcesEnvironmentVariable, resources_.path().toUtf8());
  }

  void cleanupTestCase() { qunsetenv(kResourcesEnvironmentVariable); }

  void aNetworkThatCannotBeReadIsListedDisabledWithTheReason() {
    MainWindow window(false);
    std::vector<Report> reports;
    window.setErrorReporter([&](const QString& title, const QString& message) { reports.push_back({title, message}); });
    auto* choice = window.resultPanel()->findChild<QComboBox*>(QStringLiteral("NetworkChoice"));
    QVERIFY(choice);
    const int broken = choice->findText(QStringLiteral("Broken (cannot be read)"));
    const int elderly = choice->findText(QStringLiteral("Elderly"));
    QStringList items;
    for (int i = 0; i < choice->count(); ++i) items << choice->itemText(i);
    QVERIFY2(broken >= 0 && elderly >= 0, qPrintable(QStringLiteral("both shipped files are listed: ") + items.join(", ")));
    auto* model = qobject_cast<QStandardItemModel*>(choice->model());
    QVERIFY(model);
    QVERIFY(!model->item(broken)->isEnabled());
    QVERIFY(model->item(elderly)->isEnabled());
    const QString reason = choice->itemData(broken, Qt::ToolTipRole).toString();
    QVERIFY2(reason.contains(QStringLiteral("broken.net")), qPrintable(reason));
    QVERIFY(reports.empty());

    window.networkPanel()->adaptTab()->refresh();
    auto* styles = window.networkPanel()->adaptTab()->findChild<QListWidget*>(QStringLiteral("AdaptStyles"));
    QVERIFY(styles);
    const QList<QListWidgetItem*> listed = styles->findItems(QStringLiteral("broken"), Qt::MatchStartsWith);
    QCOMPARE(listed.size(), 1);
    QVERIFY(!(listed[0]->flags() & Qt::ItemIsEnabled));
    QCOMPARE(listed[0]->checkState(), Qt::Unchecked);
    QVERIFY(listed[0]->toolTip().contains(QStringLiteral("broken.net")));
  }

  void aClipThatFailsValidationIsNotListedAsLoaded() {
    MainWindow window(false);
    std::vector<Report> reports;
    window.setErrorReporter([&](const QString& title, const QString& message) { reports.push_back({title, message}); });
    QTemporaryDir dir;
    const QString no_frames = editedCopy(dir, QStringLiteral("zombie.bvh"), QStringLiteral("no_frames.bvh"), [](QByteArray text) {
      const qsizetype motion = text.indexOf("MOTION");
      return text.left(motion) + "MOTION\nFrames: 0\nFrame Time: 0.0333333\n";
    });
    // Every OFFSET zero: a skeleton with no height, whose unit and proportions cannot be read.
    const QString flat = editedCopy(dir, QStringLiteral("zombie.bvh"), QStringLiteral("flat.bvh"), [](QByteArray text) {
      QList<QByteArray> lines = text.split('\n');
      for (QByteArray& line : lines)
        if (line.trimmed().startsWith("OFFSET")) line = line.left(line.indexOf("OFFSET")) + "OFFSET 0 0 0";
      return lines.join('\n');
    });
    QVERIFY(!no_frames.isEmpty() && !flat.isEmpty());
    QCOMPARE(window.openFiles({no_frames}), 0);
    QCOMPARE(window.openFiles({flat}), 0);
    QCOMPARE(window.clipCount(), 0);
    QCOMPARE(reports.size(), size_t{2});
    QVERIFY2(reports[0].message.contains(QStringLiteral("no_frames.bvh")), qPrintable(reports[0].message));
    QVERIFY2(reports[1].message.contains(QStringLiteral("flat.bvh")), qPrintable(reports[1].message));
    QCOMPARE(window.openFiles({test::fixture(QStringLiteral("zombie.bvh"))}), 1);  // a good clip still loads
  }

 private:
  QTemporaryDir resources_;
};

MOTIONSTYLE_GUI_TEST_MAIN(UntrustedFilesTest)
#include "test_untrusted_files.moc"
