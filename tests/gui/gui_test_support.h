#pragma once
// Helpers shared by the QTest GUI programs: fixture and screenshot paths, waiting for jobs, pixel checks,
// and a main() that installs the viewport's OpenGL format before QApplication exists (QTEST_MAIN cannot).

#include <QApplication>
#include <QColor>
#include <QDir>
#include <QImage>
#include <QLabel>
#include <QMainWindow>
#include <QPointF>
#include <QSignalSpy>
#include <QString>
#include <QTest>

#include "skeleton_viewport.h"

namespace motionstyle::test {

inline QString fixture(const QString& name) { return QDir(QStringLiteral(MOTIONSTYLE_TEST_DATA_DIR)).filePath(name); }

// An error the window reported (MainWindow::setErrorReporter): what its dialog would have said.
struct Report {
  QString title;
  QString message;
};

// <build>/screenshots/<name>.png (the folder is created).
inline QString screenshotPath(const QString& name) {
  QDir dir(QStringLiteral(MOTIONSTYLE_SCREENSHOT_DIR));
  dir.mkpath(QStringLiteral("."));
  return dir.filePath(name + QStringLiteral(".png"));
}

// Saves `image` as <build>/screenshots/<name>.png and returns the path (empty on failure).
inline QString saveScreenshot(const QImage& image, const QString& name) {
  const QString path = screenshotPath(name);
  return image.save(path, "PNG") ? path : QString();
}

// Waits until `ended` has seen `jobs` jobs end: a guard against a hang, not a timing (software GL,
// two shared cores).
inline bool waitForJobs(QSignalSpy& ended, int jobs = 1) {
  constexpr int kHangGuardMs = 120000;
  return QTest::qWaitFor([&] { return ended.count() >= jobs; }, kHangGuardMs);
}

// What the window's status bar says (MainWindow's "StatusLine"), empty if it has none.
inline QString statusLine(const QMainWindow& window) {
  const auto* line = window.findChild<QLabel*>(QStringLiteral("StatusLine"));
  return line != nullptr ? line->text() : QString();
}

// "Green-ish" as the tests mean it: green dominates red and blue by a clear margin.
inline bool isGreenish(QRgb pixel) { return qGreen(pixel) > qRed(pixel) + 20 && qGreen(pixel) > qBlue(pixel) + 20; }
inline bool isReddish(QRgb pixel) { return qRed(pixel) > qGreen(pixel) + 30 && qRed(pixel) > qBlue(pixel) + 30; }

// How many pixels in the (2 * radius + 1)^2 square around `centre` (image pixels) satisfy `test`.
template <typename Test>
int countAround(const QImage& image, QPointF centre, int radius, Test test) {
  int count = 0;
  const int cx = static_cast<int>(centre.x());
  const int cy = static_cast<int>(centre.y());
  for (int y = cy - radius; y <= cy + radius; ++y)
    for (int x = cx - radius; x <= cx + radius; ++x)
      if (image.valid(x, y) && test(image.pixel(x, y))) ++count;
  return count;
}

// Variance of the luminance over every 4th pixel: a blank (single-colour) image gives ~0.
inline double luminanceVariance(const QImage& image) {
  double sum = 0.0;
  double sum_squares = 0.0;
  int n = 0;
  for (int y = 0; y < image.height(); y += 4) {
    for (int x = 0; x < image.width(); x += 4) {
      const double v = qGray(image.pixel(x, y));
      sum += v;
      sum_squares += v * v;
      ++n;
    }
  }
  if (n == 0) return 0.0;
  const double mean = sum / n;
  return sum_squares / n - mean * mean;
}

}  // namespace motionstyle::test

#define MOTIONSTYLE_GUI_TEST_MAIN(TestClass)                       \
  int main(int argc, char** argv) {                                 \
    motionstyle::SkeletonViewport::installDefaultSurfaceFormat();   \
    QApplication app(argc, argv);                                   \
    app.setAttribute(Qt::AA_Use96Dpi, true);                        \
    TestClass test;                                                 \
    return QTest::qExec(&test, argc, argv);                         \
  }
