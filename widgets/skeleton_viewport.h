#pragma once
// SkeletonViewport: the 3-D view of up to four characters played in sync (content, style, output,
// raw output), drawn with VTK. This header names no VTK type (pimpl).
//
// How VTK is hosted: Debian 12's VTK 9.1 Qt module is built against Qt5, so QVTKOpenGLNativeWidget is
// out. A vtkGenericOpenGLRenderWindow renders into a framebuffer object of the widget's own OpenGL
// context (on an offscreen surface); the frame is read back once per render and painted as an image.
// Why not a QOpenGLWidget: one in a window makes Qt compose the WHOLE window with OpenGL at every
// repaint of any widget in it (a label, the slider), which under a software OpenGL (llvmpipe, Xvfb)
// cost more CPU than the work the window shows (docs/decisions.md, "The viewport as an image").
// A repaint that does not change the scene (an overlay, an exposed region) only repaints the image.
// The widget handles the mouse itself (no vtkRenderWindowInteractor):
//   left drag: orbit   middle drag or Shift+left drag: pan   right drag or wheel: zoom
//   F or double-click: reset the camera   C: toggle follow / fixed camera
// A legend (role colours and clip names) and the camera mode are child widgets over the view: they
// appear on screen and in QWidget::grab(), not in grabFrame().
//
// Call installDefaultSurfaceFormat() in main() BEFORE constructing QApplication (VTK needs a 3.2
// core-profile context with depth and stencil buffers).
//
// Space: figure data are world cm, Y-up (see figure_data.h). Coordinates returned by
// projectToWidget() are widget pixels (logical, origin top-left).

#include <QImage>
#include <QString>
#include <QPointF>
#include <QWidget>

#include <memory>
#include <optional>
#include <vector>

#include "figure_data.h"

namespace motionstyle {

class SkeletonViewport : public QWidget {
  Q_OBJECT

 public:
  static constexpr int kMaxFigures = 4;
  enum class Layout { SideBySide, Overlay };
  enum class CameraMode { Follow, Fixed };

  explicit SkeletonViewport(QWidget* parent = nullptr);
  ~SkeletonViewport() override;

  // Sets the OpenGL 3.2 core profile, 24-bit depth and 8-bit stencil format as Qt's default.
  static void installDefaultSurfaceFormat();

  // Replaces every figure, shows the current frame (clamped) and frames the camera on them.
  // Throws std::invalid_argument (figures unchanged) for more than kMaxFigures figures or invalid data
  // (FigureData::validate).
  void setFigures(std::vector<FigureData> figures);
  void clearFigures();
  // Renames figure `index` (the legend only: nothing is rebuilt or rendered). Throws std::out_of_range.
  void renameFigure(int index, const QString& name);
  int figureCount() const;
  const FigureData& figure(int index) const;
  int frameCount() const;  // the longest figure's frames
  int currentFrame() const;

  Layout layout() const;
  CameraMode cameraMode() const;
  bool trajectoriesVisible() const;

  // The 3-D view as it is now (rendered first if anything changed since the last render), device
  // pixels, without the overlay widgets. Works before the widget is shown (at its current size).
  QImage grabFrame();
  // Where joint `joint` of figure `figure` at frame `frame` (clamped to that figure) appears, in widget
  // pixels, with the CURRENT camera (in follow mode the camera moves with the current frame). Empty for
  // an out-of-range figure or joint, or before the widget has a size.
  std::optional<QPointF> projectToWidget(int figure, int joint, int frame) const;
  // Edge smoothing (FXAA). Default: on, except on a software OpenGL renderer (llvmpipe, as under
  // Xvfb), where the extra full-screen pass halves the frame rate; the first setAntialiasing() call
  // overrides the default.
  bool antialiasing() const;
  // Whether the OpenGL renderer is a software rasteriser (known after the first render).
  bool softwareRenderer() const;
  // Time the last render spent in VTK's Render(), milliseconds (for the status bar and benchmarks).
  double lastRenderMilliseconds() const;
  // Renders so far (a repaint that changed nothing in the scene does not render): for tests.
  int renderCount() const;
  // While on (the user's hand is on a control whose every step brings a new result), frames render at
  // half the pixels across and down and are scaled up, with coarser joint spheres, bones and contact
  // discs: a quarter of the software rasteriser's pixels and about half its vertices per result (the
  // spheres' vertices were half of a render's time). Turning it off renders at full resolution again
  // at the next paint.
  void setReducedResolution(bool on);
  bool reducedResolution() const;

 public slots:
  // Poses every figure at `frame` (a shorter figure holds its last frame): only point coordinates of
  // existing VTK data change, then a repaint is scheduled.
  void setFrame(int frame);
  void setLayout(Layout layout);
  void setCameraMode(CameraMode mode);
  void setTrajectoriesVisible(bool visible);
  // Shown in the middle of the view while it has no figure (rich text; empty: nothing).
  void setEmptyMessage(const QString& message);
  void setAntialiasing(bool on);
  // Frames the figures: the current poses in follow mode, their whole paths in fixed mode.
  void resetCamera();

 signals:
  void layoutChanged(Layout layout);
  void cameraModeChanged(CameraMode mode);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void mouseDoubleClickEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

 private:
  void refreshOverlay();
  void requestRender();  // the scene changed: render at the next paint
  QSize renderSize() const;  // device pixels, halved across and down at reduced resolution
  QSize syncRenderSize();    // the render window set to renderSize(), which it returns
  void render();         // VTK's Render() into the framebuffer object, then read back into the frame
  void renderIfStale();  // render() if the scene or the render size changed since the last frame
  bool ensureGraphics();
  void releaseGraphics();

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace motionstyle
