// motionstyle-filmstrip: a style result as a picture, rendered off-screen by the app's own viewport.
//
//   motionstyle-filmstrip --content C.bvh --style-clip S.bvh --net N.net --out PICTURE.png
//                         [--times 0.8,1.6,2.4,3.2] [--tile 400x300] [--title TEXT]
//
// Stylizes C with N and cleans it up (the Result panel's job, style::StylizeCleanupJob), then poses content
// (green), style (red) and output (blue) side by side at each time (seconds on the content's clock; a
// shorter clip holds its last pose) and writes one tile per time, left to right, under a caption.
// (Not "--style": QApplication takes that for its widget style.) Needs a display: run it under xvfb-run on a machine without one. Used by
// resources/models/render_pictures.sh for the per-style pictures. Exit codes: 0 written, 1 failed
// (the reason on stderr), 2 bad arguments.
#include <QApplication>
#include <QCommandLineParser>
#include <QFileInfo>
#include <QFont>
#include <QImage>
#include <QPainter>
#include <QSaveFile>

#include <cmath>
#include <cstdio>
#include <exception>
#include <memory>
#include <stdexcept>
#include <vector>

#include "clip_loader.h"
#include "common/allocator_tuning.h"
#include "error_text.h"
#include "nn/network_file.h"
#include "result_figures.h"
#include "skeleton_viewport.h"
#include "style/stylize_cleanup_job.h"

namespace motionstyle {
namespace {

constexpr int kCaptionHeight = 34;
constexpr int kTimeLabelHeight = 22;

struct FilmstripRequest {
  QString content, style, network, out, title;
  std::vector<double> times;  // seconds
  QSize tile;
};

struct Scene {
  std::vector<FigureData> figures;  // content, style, output at the content's rate
  double fps = 0.0;                 // the content's rate
  QString caption;
};

Scene resultScene(const FilmstripRequest& request) {
  const LoadedClip content = loadClip(request.content.toStdString());
  const LoadedClip style = loadClip(request.style.toStdString());
  if (!content.mapping)
    throw std::runtime_error(request.content.toStdString() + ": " + content.mappingStatus().toStdString());
  style::StylizeCleanupJob job;
  job.content = content.motion;
  job.mapping = *content.mapping;
  job.stylizer = std::make_shared<const style::Stylizer>(nn::loadStyleModel(request.network.toStdString()));
  const style::StylizeCleanupResult result = job.run();
  Scene scene;
  scene.fps = content.fps();
  const QString network = QFileInfo(request.network).completeBaseName();
  scene.caption = request.title.isEmpty() ? QStringLiteral("%1   content %2 (green), style %3 (red), output (blue)")
                                                .arg(network, content.name, style.name)
                                          : request.title;
  scene.figures = {figureFromClip(content, FigureRole::Content, scene.fps), figureFromClip(style, FigureRole::Style, scene.fps),
                   cleanedOutputFigure(result, content, network, scene.fps)};
  return scene;
}

QImage renderFilmstrip(const FilmstripRequest& request) {
  Scene scene = resultScene(request);
  SkeletonViewport viewport;
  viewport.setAntialiasing(true);  // a picture, not playback: worth the extra pass on a software renderer
  viewport.setLayout(SkeletonViewport::Layout::SideBySide);
  viewport.setCameraMode(SkeletonViewport::CameraMode::Follow);
  viewport.setTrajectoriesVisible(false);  // paths would cross the other figures in a still
  viewport.resize(request.tile);
  viewport.show();
  viewport.setFigures(std::move(scene.figures));
  QApplication::processEvents();

  const int columns = static_cast<int>(request.times.size());
  QImage strip(request.tile.width() * columns, kCaptionHeight + kTimeLabelHeight + request.tile.height(),
               QImage::Format_RGB32);
  strip.fill(QColor(40, 42, 48));
  QPainter painter(&strip);
  painter.setPen(QColor(230, 232, 236));
  QFont font = painter.font();
  font.setPixelSize(15);
  painter.setFont(font);
  painter.drawText(QRect(10, 0, strip.width() - 20, kCaptionHeight), Qt::AlignVCenter | Qt::AlignLeft, scene.caption);
  font.setPixelSize(13);
  painter.setFont(font);
  for (int c = 0; c < columns; ++c) {
    const int frame = static_cast<int>(std::lround(request.times[static_cast<size_t>(c)] * scene.fps));
    viewport.setFrame(frame);
    viewport.resetCamera();  // frames the poses at this time, as close as they fit
    const QImage tile = viewport.grabFrame().scaled(request.tile, Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
    const int x = c * request.tile.width();
    painter.drawText(QRect(x, kCaptionHeight, request.tile.width(), kTimeLabelHeight), Qt::AlignCenter,
                     QStringLiteral("t = %1 s (frame %2)").arg(request.times[static_cast<size_t>(c)], 0, 'f', 1).arg(frame));
    painter.drawImage(x, kCaptionHeight + kTimeLabelHeight, tile);
  }
  return strip;
}

// Written atomically: a temporary file renamed over `file` only once the PNG is complete.
void savePng(const QImage& image, const QString& file) {
  QSaveFile out(file);
  if (!out.open(QIODevice::WriteOnly) || !image.save(&out, "PNG") || !out.commit())
    throw std::runtime_error("could not write " + file.toStdString() + ": " + out.errorString().toStdString());
}

}  // namespace
}  // namespace motionstyle

int main(int argc, char** argv) {
  using namespace motionstyle;
  keepLargeAllocationsInHeap();
  SkeletonViewport::installDefaultSurfaceFormat();  // before QApplication (skeleton_viewport.h)
  QApplication app(argc, argv);
  QCommandLineParser parser;
  parser.setApplicationDescription(QStringLiteral("Render a style result (content, style, output) at a few times."));
  parser.addHelpOption();
  const QCommandLineOption content({QStringLiteral("content")}, QStringLiteral("Content BVH clip."), QStringLiteral("file"));
  const QCommandLineOption style({QStringLiteral("style-clip")}, QStringLiteral("Style BVH clip (shown only)."), QStringLiteral("file"));
  const QCommandLineOption network({QStringLiteral("net")}, QStringLiteral("Style network file."), QStringLiteral("file"));
  const QCommandLineOption out({QStringLiteral("out")}, QStringLiteral("PNG to write."), QStringLiteral("file"));
  const QCommandLineOption times({QStringLiteral("times")}, QStringLiteral("Seconds, comma-separated."), QStringLiteral("list"),
                                 QStringLiteral("0.8,1.6,2.4,3.2"));
  const QCommandLineOption tile({QStringLiteral("tile")}, QStringLiteral("Tile size WxH in pixels."), QStringLiteral("size"),
                                QStringLiteral("400x300"));
  const QCommandLineOption title({QStringLiteral("title")}, QStringLiteral("Caption (default: names)."), QStringLiteral("text"));
  for (const auto* option : {&content, &style, &network, &out, &times, &tile, &title}) parser.addOption(*option);
  parser.process(app);

  FilmstripRequest request{parser.value(content), parser.value(style), parser.value(network), parser.value(out),
                           parser.value(title), {}, {}};
  bool ok = !request.content.isEmpty() && !request.style.isEmpty() && !request.network.isEmpty() && !request.out.isEmpty();
  for (const QString& value : parser.value(times).split(QLatin1Char(','), Qt::SkipEmptyParts)) {
    bool number = false;
    const double t = value.toDouble(&number);
    ok = ok && number && t >= 0.0;
    request.times.push_back(t);
  }
  const QStringList size = parser.value(tile).split(QLatin1Char('x'));
  if (size.size() == 2) request.tile = QSize(size[0].toInt(), size[1].toInt());
  ok = ok && !request.times.empty() && request.tile.width() >= 64 && request.tile.height() >= 64;
  if (!ok) {
    std::fprintf(stderr, "motionstyle-filmstrip: need --content, --style-clip, --net, --out; times >= 0; tile >= 64x64\n");
    return 2;
  }
  try {
    savePng(renderFilmstrip(request), request.out);
  } catch (...) {
    std::fprintf(stderr, "motionstyle-filmstrip: %s\n", qPrintable(errorText(std::current_exception())));
    return 1;
  }
  std::printf("motionstyle-filmstrip: wrote %s\n", qPrintable(request.out));
  return 0;
}
