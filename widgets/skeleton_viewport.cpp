#include "skeleton_viewport.h"

#include <QElapsedTimer>
#include <QGridLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QMouseEvent>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFramebufferObject>
#include <QOpenGLFunctions>
#include <QPainter>
#include <QSurfaceFormat>
#include <QWheelEvent>

#include <vtkCamera.h>
#include <vtkCommand.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkOpenGLState.h>
#include <vtkRenderer.h>

#include <cmath>
#include <stdexcept>

#include "viewport_camera.h"
#include "viewport_scene.h"

namespace motionstyle {
namespace {

// The default view: from the front (+Z), a little to the right and above, like a camera on a tripod.
constexpr double kDefaultAzimuthDegrees = 28.0;
constexpr double kDefaultElevationDegrees = 12.0;
constexpr double kOrbitDegreesPerPixel = 0.4;
constexpr double kWheelStepFactor = 1.15;

}  // namespace

struct SkeletonViewport::Impl {
  enum class Drag { None, Orbit, Pan, Zoom };

  explicit Impl(SkeletonViewport* owner) : self(owner) {
    window->AddRenderer(scene.renderer());
    window->SetMultiSamples(0);  // edge smoothing is FXAA on the renderer: cheaper than MSAA
    // The render window asks its host to manage the context: answer with the widget's own.
    observers.push_back(window->AddObserver(vtkCommand::WindowMakeCurrentEvent, this, &Impl::onWindowEvent));
    observers.push_back(window->AddObserver(vtkCommand::WindowIsCurrentEvent, this, &Impl::onWindowEvent));
    observers.push_back(window->AddObserver(vtkCommand::WindowFrameEvent, this, &Impl::onWindowEvent));
  }

  void onWindowEvent(vtkObject*, unsigned long event, void* call_data) {
    switch (event) {
      case vtkCommand::WindowMakeCurrentEvent:
        // VTK asks for this many times per render: only switch when another context is current.
        if (context && QOpenGLContext::currentContext() != context.get()) context->makeCurrent(&surface);
        break;
      case vtkCommand::WindowIsCurrentEvent: {
        const QOpenGLContext* current = QOpenGLContext::currentContext();
        *static_cast<bool*>(call_data) = current != nullptr && current == context.get();
        break;
      }
      case vtkCommand::WindowFrameEvent:
        if (!in_render) self->requestRender();  // VTK rendered outside render(): render and show it
        break;
      default: break;
    }
  }

  void removeObservers() {
    for (const unsigned long id : observers) window->RemoveObserver(id);
    observers.clear();
  }

  vtkCamera* camera() const { return scene.renderer()->GetActiveCamera(); }
  double aspect() const { return self->height() > 0 ? double(self->width()) / double(self->height()) : 1.0; }

  void follow() {
    if (mode != CameraMode::Follow || scene.figures().empty()) return;
    const detail::Vec3 anchor = scene.anchor(scene.frame());
    // Horizontal only: bobbing the camera with the hips is tiring to watch.
    detail::translateCamera(camera(), {anchor[0] - followed[0], 0.0, anchor[2] - followed[2]});
    followed = anchor;
    // Figures that walk at different speeds spread along their lanes: back off to keep them all. One
    // figure never pushes the camera back, so that the user may follow it close up.
    if (scene.figures().size() >= 2) detail::keepBoxInView(camera(), scene.bounds(scene.frame()), aspect());
  }

  SkeletonViewport* self;
  // Declared before the render window, so that it is destroyed after it.
  QOffscreenSurface surface;
  std::unique_ptr<QOpenGLContext> context;
  std::unique_ptr<QOpenGLFramebufferObject> target;  // device pixels, depth and stencil
  QImage frame;               // the last render, device pixels, top row first
  QString graphics_problem;   // why there is no 3-D view (no OpenGL 3.2 context), else empty
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  detail::ViewportScene scene;
  std::vector<unsigned long> observers;
  Layout layout = Layout::SideBySide;
  CameraMode mode = CameraMode::Follow;
  detail::Vec3 followed{};  // the anchor the camera was last moved with
  QLabel* legend = nullptr;
  QLabel* empty_message = nullptr;
  QLabel* mode_label = nullptr;
  bool gl_ready = false;
  bool software_gl = false;
  bool antialiasing_chosen = false;  // the user decided: no automatic default any more
  bool in_render = false;
  bool needs_render = true;  // the scene changed since `frame` was rendered
  bool reduced = false;       // setReducedResolution
  double renderScale() const { return reduced ? 0.5 : 1.0; }  // render pixels per device pixel
  int renders = 0;
  Drag drag = Drag::None;
  QPointF last_mouse;
  double last_render_ms = 0.0;
};

SkeletonViewport::SkeletonViewport(QWidget* parent) : QWidget(parent), impl_(std::make_unique<Impl>(this)) {
  setFocusPolicy(Qt::StrongFocus);
  setAttribute(Qt::WA_OpaquePaintEvent);  // paintEvent covers every pixel
  setMinimumSize(200, 150);

  impl_->legend = new QLabel(this);
  impl_->legend->setObjectName(QStringLiteral("ViewportLegend"));
  impl_->legend->setTextFormat(Qt::RichText);
  impl_->legend->setStyleSheet(QStringLiteral(
      "QLabel { background: rgba(22, 24, 28, 165); color: #ebeef2; border-radius: 6px; padding: 6px 10px; }"));
  impl_->mode_label = new QLabel(this);
  impl_->mode_label->setStyleSheet(QStringLiteral("QLabel { color: rgba(230, 233, 237, 190); background: transparent; }"));
  impl_->empty_message = new QLabel(this);
  impl_->empty_message->setObjectName(QStringLiteral("ViewportEmptyMessage"));
  impl_->empty_message->setTextFormat(Qt::RichText);
  impl_->empty_message->setAlignment(Qt::AlignCenter);
  impl_->empty_message->setStyleSheet(QStringLiteral(
      "QLabel { background: rgba(22, 24, 28, 150); color: #ebeef2; border-radius: 8px; padding: 14px 20px; }"));
  auto* hint = new QLabel(tr("Drag: orbit    Shift/middle drag: pan    Wheel/right drag: zoom    F: frame    C: follow"), this);
  hint->setStyleSheet(QStringLiteral("QLabel { color: rgba(230, 233, 237, 150); background: transparent; }"));
  for (QLabel* label : {impl_->legend, impl_->mode_label, impl_->empty_message, hint})
    label->setAttribute(Qt::WA_TransparentForMouseEvents);
  auto* overlay = new QGridLayout(this);
  overlay->setContentsMargins(10, 10, 12, 8);
  overlay->addWidget(impl_->legend, 0, 0, Qt::AlignLeft | Qt::AlignTop);
  overlay->addWidget(impl_->mode_label, 0, 1, Qt::AlignRight | Qt::AlignTop);
  overlay->addWidget(impl_->empty_message, 1, 0, 1, 2, Qt::AlignCenter);
  overlay->addWidget(hint, 2, 0, 1, 2, Qt::AlignLeft | Qt::AlignBottom);
  overlay->setRowStretch(1, 1);
  refreshOverlay();
  resetCamera();
}

SkeletonViewport::~SkeletonViewport() {
  releaseGraphics();
  impl_->removeObservers();
}

void SkeletonViewport::installDefaultSurfaceFormat() {
  QSurfaceFormat format;
  format.setRenderableType(QSurfaceFormat::OpenGL);
  format.setVersion(3, 2);
  format.setProfile(QSurfaceFormat::CoreProfile);
  format.setDepthBufferSize(24);
  format.setStencilBufferSize(8);
  format.setRedBufferSize(8);
  format.setGreenBufferSize(8);
  format.setBlueBufferSize(8);
  format.setAlphaBufferSize(8);
  format.setSamples(0);
  format.setSwapBehavior(QSurfaceFormat::DoubleBuffer);
  QSurfaceFormat::setDefaultFormat(format);
}

void SkeletonViewport::setFigures(std::vector<FigureData> figures) {
  if (static_cast<int>(figures.size()) > kMaxFigures)
    throw std::invalid_argument("the viewport shows at most " + std::to_string(kMaxFigures) + " figures, got " +
                                std::to_string(figures.size()));
  for (const FigureData& figure : figures) figure.validate();
  const int frame = impl_->scene.frame();
  impl_->scene.setFigures(std::move(figures));
  impl_->scene.setFrame(std::clamp(frame, 0, std::max(0, frameCount() - 1)));
  refreshOverlay();
  resetCamera();
}

void SkeletonViewport::clearFigures() { setFigures({}); }

void SkeletonViewport::renameFigure(int index, const QString& name) {
  impl_->scene.renameFigure(index, name);
  refreshOverlay();
}

int SkeletonViewport::figureCount() const { return static_cast<int>(impl_->scene.figures().size()); }

const FigureData& SkeletonViewport::figure(int index) const {
  return impl_->scene.figures().at(static_cast<size_t>(index));
}

int SkeletonViewport::frameCount() const { return impl_->scene.frameCount(); }
int SkeletonViewport::currentFrame() const { return impl_->scene.frame(); }
SkeletonViewport::Layout SkeletonViewport::layout() const { return impl_->layout; }
SkeletonViewport::CameraMode SkeletonViewport::cameraMode() const { return impl_->mode; }
double SkeletonViewport::lastRenderMilliseconds() const { return impl_->last_render_ms; }
int SkeletonViewport::renderCount() const { return impl_->renders; }

void SkeletonViewport::setReducedResolution(bool on) {
  if (on == impl_->reduced) return;
  impl_->reduced = on;
  impl_->scene.setCoarseGlyphs(on);
  syncRenderSize();
  requestRender();
}

bool SkeletonViewport::reducedResolution() const { return impl_->reduced; }

void SkeletonViewport::requestRender() {
  impl_->needs_render = true;
  update();
}

void SkeletonViewport::setFrame(int frame) {
  impl_->scene.setFrame(std::clamp(frame, 0, std::max(0, frameCount() - 1)));
  impl_->follow();
  requestRender();
}

void SkeletonViewport::setLayout(Layout layout) {
  if (layout == impl_->layout) return;
  impl_->layout = layout;
  impl_->scene.setLayout(layout == Layout::SideBySide ? detail::SceneLayout::SideBySide : detail::SceneLayout::Overlay);
  impl_->scene.setFrame(impl_->scene.frame());
  resetCamera();
  emit layoutChanged(layout);
}

void SkeletonViewport::setCameraMode(CameraMode mode) {
  if (mode == impl_->mode) return;
  impl_->mode = mode;
  impl_->followed = impl_->scene.anchor(impl_->scene.frame());
  refreshOverlay();
  requestRender();
  emit cameraModeChanged(mode);
}

bool SkeletonViewport::trajectoriesVisible() const { return impl_->scene.trajectoriesVisible(); }

void SkeletonViewport::setTrajectoriesVisible(bool visible) {
  impl_->scene.setTrajectoriesVisible(visible);
  requestRender();
}

bool SkeletonViewport::antialiasing() const { return impl_->scene.antialiasing(); }
bool SkeletonViewport::softwareRenderer() const { return impl_->software_gl; }

void SkeletonViewport::setAntialiasing(bool on) {
  impl_->antialiasing_chosen = true;
  impl_->scene.setAntialiasing(on);
  requestRender();
}

void SkeletonViewport::resetCamera() {
  std::array<double, 6> box = impl_->scene.bounds(impl_->mode == CameraMode::Follow ? impl_->scene.frame() : -1);
  box[2] = std::min(box[2], 0.0);  // keep the floor under the feet in view
  detail::frameBox(impl_->camera(), box, kDefaultAzimuthDegrees, kDefaultElevationDegrees, impl_->aspect());
  impl_->followed = impl_->scene.anchor(impl_->scene.frame());
  requestRender();
}

QImage SkeletonViewport::grabFrame() {
  renderIfStale();
  return impl_->frame;
}

void SkeletonViewport::renderIfStale() {
  if (impl_->needs_render || impl_->frame.size() != renderSize()) render();
}

QSize SkeletonViewport::renderSize() const {
  return (QSizeF(size()) * devicePixelRatioF() * impl_->renderScale()).toSize().expandedTo(QSize(1, 1));
}

QSize SkeletonViewport::syncRenderSize() {
  const QSize size = renderSize();
  impl_->window->SetSize(size.width(), size.height());
  return size;
}

std::optional<QPointF> SkeletonViewport::projectToWidget(int figure, int joint, int frame) const {
  if (figure < 0 || figure >= figureCount()) return std::nullopt;
  if (joint < 0 || joint >= impl_->scene.figures()[static_cast<size_t>(figure)].jointCount()) return std::nullopt;
  if (!impl_->gl_ready || width() <= 0 || height() <= 0) return std::nullopt;
  const detail::Vec3 world = impl_->scene.drawnJoint(figure, joint, frame);
  vtkRenderer* renderer = impl_->scene.renderer();
  renderer->SetWorldPoint(world[0], world[1], world[2], 1.0);
  renderer->WorldToDisplay();
  const double* display = renderer->GetDisplayPoint();  // device pixels, origin bottom-left
  const double ratio = devicePixelRatioF() * impl_->renderScale();  // render pixels per widget pixel
  const int render_height = impl_->window->GetSize()[1];
  return QPointF(display[0] / ratio, (render_height - display[1]) / ratio);
}

bool SkeletonViewport::ensureGraphics() {
  if (impl_->gl_ready) return true;
  if (!impl_->graphics_problem.isEmpty()) return false;
  const QSurfaceFormat format = QSurfaceFormat::defaultFormat();
  impl_->surface.setFormat(format);
  impl_->surface.create();
  impl_->context = std::make_unique<QOpenGLContext>();
  impl_->context->setFormat(format);
  if (!impl_->surface.isValid() || !impl_->context->create() || !impl_->context->makeCurrent(&impl_->surface) ||
      impl_->context->format().version() < qMakePair(3, 2)) {
    impl_->context.reset();
    impl_->graphics_problem = tr("The 3-D view needs OpenGL 3.2, which this display does not offer.");
    return false;
  }
  vtkGenericOpenGLRenderWindow* window = impl_->window;
  window->SetOwnContext(false);
  window->SetFrameBlitModeToBlitToCurrent();  // into the framebuffer object bound when Render() starts
  window->OpenGLInitContext();
  window->SetReadyForRendering(true);
  impl_->gl_ready = true;
  const auto* renderer_name = reinterpret_cast<const char*>(impl_->context->functions()->glGetString(GL_RENDERER));
  const QByteArray name = QByteArray(renderer_name != nullptr ? renderer_name : "").toLower();
  impl_->software_gl = name.contains("llvmpipe") || name.contains("softpipe") || name.contains("swrast");
  if (!impl_->antialiasing_chosen) impl_->scene.setAntialiasing(!impl_->software_gl);
  return true;
}

void SkeletonViewport::render() {
  impl_->needs_render = false;
  if (!ensureGraphics()) {
    impl_->frame = QImage();
    return;
  }
  QOpenGLContext& context = *impl_->context;
  context.makeCurrent(&impl_->surface);
  const QSize size = syncRenderSize();
  if (!impl_->target || impl_->target->size() != size)
    impl_->target = std::make_unique<QOpenGLFramebufferObject>(size, QOpenGLFramebufferObject::CombinedDepthStencil);
  // The render window re-applies its cached GL state at every Start() (it does not own the context);
  // the framebuffer binding is the exception VTK must READ: it blits into the one bound now.
  impl_->target->bind();
  impl_->in_render = true;
  impl_->window->GetState()->ResetFramebufferBindings();
  std::array<double, 6> drawn = impl_->scene.drawnBounds();  // not VTK's per-render bounds of every actor
  impl_->scene.renderer()->ResetCameraClippingRange(drawn.data());
  QElapsedTimer timer;
  timer.start();
  impl_->window->Render();
  impl_->last_render_ms = static_cast<double>(timer.nsecsElapsed()) / 1e6;
  impl_->in_render = false;
  ++impl_->renders;

  // Read back as 0xffRRGGBB words (QImage::Format_RGB32): alpha forced to 1 first, since Mesa leaves
  // alpha = 0 in VTK's blit; OpenGL's rows run bottom-up.
  QOpenGLFunctions* gl = context.functions();
  gl->glBindFramebuffer(GL_FRAMEBUFFER, impl_->target->handle());
  gl->glViewport(0, 0, size.width(), size.height());
  gl->glDisable(GL_SCISSOR_TEST);
  gl->glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
  gl->glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  gl->glClear(GL_COLOR_BUFFER_BIT);
  gl->glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  if (impl_->frame.size() != size || impl_->frame.format() != QImage::Format_RGB32)
    impl_->frame = QImage(size, QImage::Format_RGB32);
  gl->glPixelStorei(GL_PACK_ALIGNMENT, 4);
  gl->glReadPixels(0, 0, size.width(), size.height(), GL_BGRA, GL_UNSIGNED_BYTE, impl_->frame.bits());
  impl_->frame.mirror(false, true);
  impl_->frame.setDevicePixelRatio(devicePixelRatioF() * impl_->renderScale());
}

void SkeletonViewport::paintEvent(QPaintEvent*) {
  renderIfStale();
  QPainter painter(this);
  if (impl_->frame.isNull()) {
    painter.fillRect(rect(), QColor(34, 36, 41));
    painter.setPen(QColor(235, 238, 242));
    painter.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap, impl_->graphics_problem);
    return;
  }
  // Into the whole widget, explicitly: QPainter::drawImage(point, image) scales by the image's device
  // pixel ratio only when that is above 1, so a reduced frame would come out at half size. Clipped to
  // the region being repainted.
  if (impl_->reduced) painter.setRenderHint(QPainter::SmoothPixmapTransform);
  painter.drawImage(QRectF(rect()), impl_->frame, QRectF(impl_->frame.rect()));
}

void SkeletonViewport::resizeEvent(QResizeEvent*) {
  syncRenderSize();  // projectToWidget answers for the new size before the next render
  impl_->needs_render = true;
}

void SkeletonViewport::refreshOverlay() {
  // Child widgets, not QPainter on the GL framebuffer: Qt composites them over the 3-D view, they
  // stay crisp, and VTK's GL state never meets the paint engine's.
  QString legend;
  for (const FigureData& figure : impl_->scene.figures()) {
    if (!legend.isEmpty()) legend += QStringLiteral("<br>");
    legend += QStringLiteral("<span style='color:%1'>&#9679;</span>&nbsp;&nbsp;%2&nbsp;&nbsp;<span style='color:#aeb4bc'>%3</span>")
                  .arg(figureColor(figure.role).name(), figureRoleName(figure.role), figure.name.toHtmlEscaped());
  }
  if (legend != impl_->legend->text()) {  // a live result keeps its names: no new rich-text layout
    impl_->legend->setText(legend);
    impl_->legend->adjustSize();
  }
  impl_->legend->setVisible(!legend.isEmpty());
  impl_->mode_label->setText(impl_->mode == CameraMode::Follow ? tr("Follow camera") : tr("Fixed camera"));
  impl_->empty_message->setVisible(impl_->scene.figures().empty() && !impl_->empty_message->text().isEmpty());
}

void SkeletonViewport::setEmptyMessage(const QString& message) {
  impl_->empty_message->setText(message);
  refreshOverlay();
}

void SkeletonViewport::releaseGraphics() {
  if (!impl_->gl_ready) return;
  impl_->context->makeCurrent(&impl_->surface);
  impl_->window->Finalize();
  impl_->window->SetReadyForRendering(false);
  impl_->target.reset();
  impl_->gl_ready = false;
  impl_->context->doneCurrent();
}

void SkeletonViewport::mousePressEvent(QMouseEvent* event) {
  impl_->last_mouse = event->position();
  const bool shift = event->modifiers() & Qt::ShiftModifier;
  if (event->button() == Qt::LeftButton) impl_->drag = shift ? Impl::Drag::Pan : Impl::Drag::Orbit;
  else if (event->button() == Qt::MiddleButton) impl_->drag = Impl::Drag::Pan;
  else if (event->button() == Qt::RightButton) impl_->drag = Impl::Drag::Zoom;
  event->accept();
}

void SkeletonViewport::mouseMoveEvent(QMouseEvent* event) {
  if (impl_->drag == Impl::Drag::None) return;
  const QPointF delta = event->position() - impl_->last_mouse;
  impl_->last_mouse = event->position();
  const double height_cm = impl_->scene.characterHeight();
  switch (impl_->drag) {
    case Impl::Drag::Orbit:
      detail::orbitCamera(impl_->camera(), -delta.x() * kOrbitDegreesPerPixel, delta.y() * kOrbitDegreesPerPixel);
      break;
    case Impl::Drag::Pan: detail::panCamera(impl_->camera(), delta.x(), delta.y(), height()); break;
    case Impl::Drag::Zoom:
      detail::dollyCamera(impl_->camera(), std::pow(1.01, -delta.y()), 0.1 * height_cm, 60.0 * height_cm);
      break;
    case Impl::Drag::None: break;
  }
  requestRender();
}

void SkeletonViewport::mouseReleaseEvent(QMouseEvent* event) {
  impl_->drag = Impl::Drag::None;
  event->accept();
}

void SkeletonViewport::mouseDoubleClickEvent(QMouseEvent* event) {
  if (event->button() == Qt::LeftButton) resetCamera();
}

void SkeletonViewport::wheelEvent(QWheelEvent* event) {
  const double steps = event->angleDelta().y() / 120.0;
  const double height_cm = impl_->scene.characterHeight();
  detail::dollyCamera(impl_->camera(), std::pow(kWheelStepFactor, steps), 0.1 * height_cm, 60.0 * height_cm);
  requestRender();
  event->accept();
}

void SkeletonViewport::keyPressEvent(QKeyEvent* event) {
  switch (event->key()) {
    case Qt::Key_F: resetCamera(); break;
    case Qt::Key_C:
      setCameraMode(impl_->mode == CameraMode::Follow ? CameraMode::Fixed : CameraMode::Follow);
      break;
    default: QWidget::keyPressEvent(event); return;
  }
  event->accept();
}

}  // namespace motionstyle
