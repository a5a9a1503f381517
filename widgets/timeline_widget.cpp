#include "timeline_widget.h"

#include <QComboBox>
#include <QElapsedTimer>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QMouseEvent>
#include <QShortcut>
#include <QSignalBlocker>
#include <QSlider>
#include <QSpinBox>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QTimer>
#include <QToolButton>

#include <algorithm>
#include <array>
#include <cmath>

#include "playback_clock.h"
#include "track_view.h"

namespace motionstyle {
namespace {

constexpr std::array<double, 7> kSpeeds = {0.25, 0.5, 0.75, 1.0, 1.25, 1.5, 2.0};
constexpr int kTickMilliseconds = 8;  // faster than any display; the clock decides the frame

// The scrub bar: a click beside the handle jumps the handle there and starts dragging it, as a
// timeline's does (QSlider's own click moves it one page towards the click: ten frames at a time).
class ScrubSlider : public QSlider {
 public:
  using QSlider::QSlider;

 protected:
  void mousePressEvent(QMouseEvent* event) override {
    if (event->button() == Qt::LeftButton && maximum() > minimum()) {
      QStyleOptionSlider option;
      initStyleOption(&option);
      const QRect handle = style()->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderHandle, this);
      const QPoint at = event->position().toPoint();
      if (!handle.contains(at)) {
        const QRect groove = style()->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderGroove, this);
        setValue(QStyle::sliderValueFromPosition(minimum(), maximum(), at.x() - groove.x() - handle.width() / 2,
                                                 groove.width() - handle.width(), option.upsideDown));
      }
    }
    QSlider::mousePressEvent(event);  // the handle is under the pointer now: a drag follows
  }
};

QToolButton* makeButton(QWidget* parent, QStyle::StandardPixmap icon, const QString& tip) {
  auto* button = new QToolButton(parent);
  button->setIcon(parent->style()->standardIcon(icon));
  button->setToolTip(tip);
  button->setAutoRaise(true);
  button->setFocusPolicy(Qt::NoFocus);  // Space must reach the play shortcut, not "click" a button
  button->setIconSize(QSize(18, 18));
  return button;
}

}  // namespace

struct TimelineWidget::Impl {
  int frames = 0;
  int frame = 0;
  double fps = 30.0;
  bool playing = false;
  bool looping = true;
  PlaybackClock clock;
  QElapsedTimer wall;
  QTimer timer;

  QToolButton* start_button = nullptr;
  QToolButton* back_button = nullptr;
  QToolButton* play_button = nullptr;
  QToolButton* forward_button = nullptr;
  QToolButton* end_button = nullptr;
  QToolButton* loop_button = nullptr;
  QComboBox* speed_box = nullptr;
  QSpinBox* frame_box = nullptr;
  QLabel* frame_total = nullptr;
  QLabel* time_label = nullptr;
  QSlider* slider = nullptr;
  TrackView* tracks = nullptr;

  double now() const { return static_cast<double>(wall.nsecsElapsed()) / 1e9; }
};

TimelineWidget::TimelineWidget(QWidget* parent) : QWidget(parent), impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.wall.start();
  d.timer.setTimerType(Qt::PreciseTimer);
  d.timer.setInterval(kTickMilliseconds);
  connect(&d.timer, &QTimer::timeout, this, &TimelineWidget::onTick);

  d.start_button = makeButton(this, QStyle::SP_MediaSkipBackward, tr("First frame (Home)"));
  d.back_button = makeButton(this, QStyle::SP_MediaSeekBackward, tr("Previous frame (Left)"));
  d.play_button = makeButton(this, QStyle::SP_MediaPlay, tr("Play / pause (Space)"));
  d.forward_button = makeButton(this, QStyle::SP_MediaSeekForward, tr("Next frame (Right)"));
  d.end_button = makeButton(this, QStyle::SP_MediaSkipForward, tr("Last frame (End)"));
  d.loop_button = new QToolButton(this);
  d.loop_button->setText(tr("Loop"));
  d.loop_button->setIcon(style()->standardIcon(QStyle::SP_BrowserReload));
  d.loop_button->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  d.loop_button->setCheckable(true);
  d.loop_button->setChecked(d.looping);
  d.loop_button->setAutoRaise(true);
  d.loop_button->setFocusPolicy(Qt::NoFocus);
  d.loop_button->setToolTip(tr("Loop playback"));

  d.speed_box = new QComboBox(this);
  for (const double speed : kSpeeds) d.speed_box->addItem(QStringLiteral("%1x").arg(speed), speed);
  d.speed_box->setCurrentIndex(3);
  d.speed_box->setFocusPolicy(Qt::NoFocus);
  d.speed_box->setToolTip(tr("Playback speed"));

  d.frame_box = new QSpinBox(this);
  d.frame_box->setRange(0, 0);
  d.frame_box->setKeyboardTracking(false);
  d.frame_box->setToolTip(tr("Current frame"));
  d.frame_box->setAlignment(Qt::AlignRight);
  d.frame_box->setMinimumWidth(70);
  d.frame_total = new QLabel(this);
  d.time_label = new QLabel(this);
  d.time_label->setToolTip(tr("Time (mm:ss.fff) / duration"));
  QFont mono = d.time_label->font();
  mono.setFamily(QStringLiteral("monospace"));
  mono.setStyleHint(QFont::Monospace);
  d.time_label->setFont(mono);
  d.frame_total->setFont(mono);
  // Fixed widths sized for the longest text, so the row does not jitter or clip while playing.
  const QFontMetrics metrics(mono);
  d.frame_total->setMinimumWidth(metrics.horizontalAdvance(QStringLiteral("/ 9999999")));
  d.time_label->setMinimumWidth(metrics.horizontalAdvance(QStringLiteral("000:00.000 / 000:00.000  120.00 fps")));

  d.slider = new ScrubSlider(Qt::Horizontal, this);
  d.slider->setObjectName(QStringLiteral("ScrubSlider"));
  d.slider->setRange(0, 0);
  d.slider->setFocusPolicy(Qt::NoFocus);
  d.slider->setToolTip(tr("Scrub"));

  d.tracks = new TrackView(this);

  auto* controls = new QHBoxLayout;
  controls->setSpacing(2);
  for (QWidget* w : std::initializer_list<QWidget*>{d.start_button, d.back_button, d.play_button, d.forward_button,
                                                    d.end_button})
    controls->addWidget(w);
  controls->addSpacing(10);
  controls->addWidget(d.loop_button);
  controls->addSpacing(6);
  controls->addWidget(new QLabel(tr("Speed"), this));
  controls->addWidget(d.speed_box);
  controls->addStretch(1);
  controls->addWidget(new QLabel(tr("Frame"), this));
  controls->addWidget(d.frame_box);
  controls->addWidget(d.frame_total);
  controls->addSpacing(12);
  controls->addWidget(d.time_label);

  // The slider starts where the tracks' time area starts, so the two read as one time axis.
  auto* scrub_row = new QHBoxLayout;
  scrub_row->setContentsMargins(TrackView::kHeaderWidth - 8, 0, 0, 0);
  scrub_row->addWidget(d.slider);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(6, 4, 6, 6);
  layout->setSpacing(4);
  layout->addLayout(controls);
  layout->addLayout(scrub_row);
  layout->addWidget(d.tracks);

  connect(d.start_button, &QToolButton::clicked, this, &TimelineWidget::goToStart);
  connect(d.back_button, &QToolButton::clicked, this, &TimelineWidget::stepBackward);
  connect(d.play_button, &QToolButton::clicked, this, &TimelineWidget::togglePlay);
  connect(d.forward_button, &QToolButton::clicked, this, &TimelineWidget::stepForward);
  connect(d.end_button, &QToolButton::clicked, this, &TimelineWidget::goToEnd);
  connect(d.loop_button, &QToolButton::toggled, this, &TimelineWidget::setLooping);
  connect(d.speed_box, &QComboBox::currentIndexChanged, this,
          [this](int index) { setSpeed(impl_->speed_box->itemData(index).toDouble()); });
  connect(d.frame_box, &QSpinBox::valueChanged, this, &TimelineWidget::setFrame);
  connect(d.slider, &QSlider::valueChanged, this, &TimelineWidget::setFrame);
  connect(d.tracks, &TrackView::scrubbed, this, &TimelineWidget::setFrame);

  const auto shortcut = [this](QKeySequence key, void (TimelineWidget::*slot)()) {
    auto* s = new QShortcut(key, this);
    s->setContext(Qt::WindowShortcut);
    connect(s, &QShortcut::activated, this, slot);
  };
  shortcut(QKeySequence(Qt::Key_Space), &TimelineWidget::togglePlay);
  shortcut(QKeySequence(Qt::Key_Right), &TimelineWidget::stepForward);
  shortcut(QKeySequence(Qt::Key_Left), &TimelineWidget::stepBackward);
  shortcut(QKeySequence(Qt::Key_Home), &TimelineWidget::goToStart);
  shortcut(QKeySequence(Qt::Key_End), &TimelineWidget::goToEnd);

  setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Fixed);
  refreshDisplay();
}

TimelineWidget::~TimelineWidget() = default;

void TimelineWidget::setFrameCount(int frames) {
  impl_->frames = std::max(0, frames);
  impl_->tracks->setFrameCount(impl_->frames);
  if (impl_->frames == 0) pause();
  const int last = std::max(0, impl_->frames - 1);
  {
    const QSignalBlocker block_slider(impl_->slider);
    const QSignalBlocker block_box(impl_->frame_box);
    impl_->slider->setRange(0, last);
    impl_->frame_box->setRange(0, last);
  }
  if (impl_->frame > last) setFrame(last);
  refreshDisplay();
}

void TimelineWidget::setFrameRate(double fps) {
  if (!(fps > 0.0) || !std::isfinite(fps)) return;
  impl_->fps = fps;
  restartClock();
  refreshDisplay();
}

int TimelineWidget::frameCount() const { return impl_->frames; }
double TimelineWidget::frameRate() const { return impl_->fps; }
int TimelineWidget::frame() const { return impl_->frame; }
bool TimelineWidget::isPlaying() const { return impl_->playing; }
bool TimelineWidget::isLooping() const { return impl_->looping; }
double TimelineWidget::speed() const { return impl_->clock.speed(); }
TrackView* TimelineWidget::trackView() const { return impl_->tracks; }

QString TimelineWidget::formatTime(double seconds) {
  const auto millis = static_cast<long long>(std::llround(std::max(0.0, seconds) * 1000.0));
  return QStringLiteral("%1:%2.%3")
      .arg(millis / 60000, 2, 10, QLatin1Char('0'))
      .arg((millis / 1000) % 60, 2, 10, QLatin1Char('0'))
      .arg(millis % 1000, 3, 10, QLatin1Char('0'));
}

void TimelineWidget::setFrame(int frame) {
  const int clamped = std::clamp(frame, 0, std::max(0, impl_->frames - 1));
  if (impl_->playing) impl_->clock.start(clamped, impl_->now());  // scrubbing while playing continues from here
  if (clamped == impl_->frame) {
    refreshDisplay();
    return;
  }
  impl_->frame = clamped;
  refreshDisplay();
  emit frameChanged(clamped);
}

void TimelineWidget::play() {
  if (impl_->playing || impl_->frames <= 1) return;
  if (!impl_->looping && impl_->frame >= impl_->frames - 1) setFrame(0);  // replay from the start
  impl_->playing = true;
  restartClock();
  impl_->timer.start();
  refreshDisplay();
  emit playingChanged(true);
}

void TimelineWidget::pause() {
  if (!impl_->playing) return;
  impl_->playing = false;
  impl_->timer.stop();
  refreshDisplay();
  emit playingChanged(false);
}

void TimelineWidget::togglePlay() { impl_->playing ? pause() : play(); }

void TimelineWidget::stepForward() {
  pause();
  setFrame(wrapFrame(impl_->frame + 1LL, impl_->frames, impl_->looping));
}

void TimelineWidget::stepBackward() {
  pause();
  setFrame(wrapFrame(impl_->frame - 1LL, impl_->frames, impl_->looping));
}

void TimelineWidget::goToStart() { setFrame(0); }
void TimelineWidget::goToEnd() { setFrame(impl_->frames - 1); }

void TimelineWidget::setLooping(bool loop) {
  impl_->looping = loop;
  const QSignalBlocker block(impl_->loop_button);
  impl_->loop_button->setChecked(loop);
}

void TimelineWidget::setSpeed(double speed) {
  const double clamped = std::clamp(speed, kSpeeds.front(), kSpeeds.back());
  impl_->clock.setRate(impl_->fps, clamped);
  restartClock();
  // Show the nearest preset (the combo only lists presets).
  int nearest = 0;
  for (int i = 0; i < static_cast<int>(kSpeeds.size()); ++i)
    if (std::abs(kSpeeds[static_cast<size_t>(i)] - clamped) < std::abs(kSpeeds[static_cast<size_t>(nearest)] - clamped))
      nearest = i;
  const QSignalBlocker block(impl_->speed_box);
  impl_->speed_box->setCurrentIndex(nearest);
}

void TimelineWidget::restartClock() {
  impl_->clock.setRate(impl_->fps, impl_->clock.speed());
  impl_->clock.start(impl_->frame, impl_->now());
}

void TimelineWidget::onTick() {
  Impl& d = *impl_;
  if (!d.playing || d.frames <= 0) return;
  const long long due = d.clock.frameAt(d.now());
  if (!d.looping && due >= d.frames - 1) {
    const int last = d.frames - 1;
    if (last != d.frame) {
      d.frame = last;
      refreshDisplay();
      emit frameChanged(last);
    }
    pause();
    return;
  }
  const int next = wrapFrame(due, d.frames, d.looping);
  if (next == d.frame) return;
  d.frame = next;  // not setFrame(): that would restart the clock and drift
  refreshDisplay();
  emit frameChanged(next);
}

void TimelineWidget::refreshDisplay() {
  Impl& d = *impl_;
  {
    const QSignalBlocker block_slider(d.slider);
    const QSignalBlocker block_box(d.frame_box);
    d.slider->setValue(d.frame);
    d.frame_box->setValue(d.frame);
  }
  d.tracks->setPlayhead(d.frame);
  d.frame_total->setText(QStringLiteral("/ %1").arg(std::max(0, d.frames - 1)));
  d.time_label->setText(formatTime(d.frame / d.fps) + QStringLiteral(" / ") + formatTime(d.frames / d.fps) +
                        QStringLiteral("  %1 fps").arg(d.fps, 0, 'g', 4));
  d.play_button->setIcon(style()->standardIcon(d.playing ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
  const bool has_frames = d.frames > 0;
  for (QWidget* w : std::initializer_list<QWidget*>{d.start_button, d.back_button, d.play_button, d.forward_button,
                                                    d.end_button, d.slider, d.frame_box})
    w->setEnabled(has_frames);
}

}  // namespace motionstyle
