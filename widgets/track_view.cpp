#include "track_view.h"

#include <QHelpEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QPainterPath>
#include <QToolTip>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace motionstyle {
namespace {

constexpr int kRowGap = 2;
const QColor kBackground(43, 46, 51);
const QColor kRowBackground(54, 58, 64);
const QColor kHeaderText(200, 204, 210);
const QColor kPlayhead(255, 196, 64);

}  // namespace

TrackView::TrackView(QWidget* parent) : QWidget(parent) {
  setMouseTracking(false);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
}

void TrackView::setFrameCount(int frames) {
  frames_ = std::max(0, frames);
  for (BoolTrack& track : bool_tracks_) {
    track.values.resize(static_cast<size_t>(frames_), false);
    if (!track.unheld.empty()) track.unheld.resize(static_cast<size_t>(frames_), false);
    if (!track.lifted.empty()) track.lifted.resize(static_cast<size_t>(frames_), false);
  }
  for (FloatTrack& track : float_tracks_) track.values.resize(static_cast<size_t>(frames_), track.minimum);
  playhead_ = std::clamp(playhead_, 0, std::max(0, frames_ - 1));
  update();
}

int TrackView::addBoolTrack(const QString& name, const QColor& color, std::vector<bool> values) {
  values.resize(static_cast<size_t>(frames_), false);
  bool_tracks_.push_back({name, color, std::move(values), {}, {}, {}, {}});
  updateGeometry();
  update();
  return static_cast<int>(bool_tracks_.size()) - 1;
}

void TrackView::setBoolValues(int track, std::vector<bool> values) {
  values.resize(static_cast<size_t>(frames_), false);
  bool_tracks_.at(static_cast<size_t>(track)).values = std::move(values);
  update();
}

const std::vector<bool>& TrackView::boolValues(int track) const {
  return bool_tracks_.at(static_cast<size_t>(track)).values;
}

void TrackView::setUnheldFrames(int track, std::vector<bool> unheld, const QString& tool_tip) {
  BoolTrack& target = bool_tracks_.at(static_cast<size_t>(track));
  if (!unheld.empty()) unheld.resize(static_cast<size_t>(frames_), false);
  target.unheld = std::move(unheld);
  target.unheld_tool_tip = tool_tip;
  update();
}

const std::vector<bool>& TrackView::unheldFrames(int track) const {
  return bool_tracks_.at(static_cast<size_t>(track)).unheld;
}

void TrackView::setLiftedFrames(int track, std::vector<bool> lifted, const QString& tool_tip) {
  BoolTrack& target = bool_tracks_.at(static_cast<size_t>(track));
  if (!lifted.empty()) lifted.resize(static_cast<size_t>(frames_), false);
  target.lifted = std::move(lifted);
  target.lifted_tool_tip = tool_tip;
  update();
}

const std::vector<bool>& TrackView::liftedFrames(int track) const {
  return bool_tracks_.at(static_cast<size_t>(track)).lifted;
}

bool TrackView::isLifted(int track, int frame) const {
  const BoolTrack& t = bool_tracks_[static_cast<size_t>(track)];
  const auto f = static_cast<size_t>(frame);
  return frame >= 0 && f < t.lifted.size() && t.lifted[f] && t.values[f] && !isUnheld(track, frame);
}

bool TrackView::isUnheld(int track, int frame) const {
  const BoolTrack& t = bool_tracks_[static_cast<size_t>(track)];
  const auto f = static_cast<size_t>(frame);
  return frame >= 0 && f < t.unheld.size() && t.unheld[f] && t.values[f];
}

bool TrackView::event(QEvent* event) {
  if (event->type() == QEvent::ToolTip) {
    const auto* help = static_cast<QHelpEvent*>(event);
    const int frame = frameAt(help->pos().x());
    for (int t = 0; t < boolTrackCount(); ++t) {
      if (!boolTrackRect(t).contains(help->pos())) continue;
      const BoolTrack& track = bool_tracks_[static_cast<size_t>(t)];
      if (isUnheld(t, frame) || isLifted(t, frame)) {
        QToolTip::showText(help->globalPos(), isUnheld(t, frame) ? track.unheld_tool_tip : track.lifted_tool_tip, this);
        return true;
      }
    }
    QToolTip::hideText();
    event->ignore();
    return true;
  }
  return QWidget::event(event);
}

int TrackView::addFloatTrack(const QString& name, const QColor& color) {
  float_tracks_.push_back({name, color, std::vector<float>(static_cast<size_t>(frames_), 0.0f), 0.0f, 1.0f});
  updateGeometry();
  update();
  return static_cast<int>(float_tracks_.size()) - 1;
}

void TrackView::setFloatValues(int track, std::vector<float> values, float minimum, float maximum) {
  FloatTrack& row = float_tracks_.at(static_cast<size_t>(track));
  values.resize(static_cast<size_t>(frames_), minimum);
  row.values = std::move(values);
  row.minimum = minimum;
  row.maximum = maximum > minimum ? maximum : minimum + 1.0f;
  update();
}

const std::vector<float>& TrackView::floatValues(int track) const {
  return float_tracks_.at(static_cast<size_t>(track)).values;
}

void TrackView::clearTracks() {
  bool_tracks_.clear();
  float_tracks_.clear();
  updateGeometry();
  update();
}

void TrackView::setPlayhead(int frame) {
  const int clamped = std::clamp(frame, 0, std::max(0, frames_ - 1));
  if (clamped == playhead_) return;
  playhead_ = clamped;
  update();
}

QRect TrackView::timeArea() const { return QRect(kHeaderWidth, 0, std::max(1, width() - kHeaderWidth - 6), height()); }

QRect TrackView::rulerRect() const {
  const QRect area = timeArea();
  return QRect(area.left(), 0, area.width(), kRulerHeight);
}

QRect TrackView::boolTrackRect(int track) const {
  const QRect area = timeArea();
  return QRect(area.left(), kRulerHeight + kRowGap + track * (kBoolRowHeight + kRowGap), area.width(), kBoolRowHeight);
}

QRect TrackView::floatTrackRect(int track) const {
  const QRect area = timeArea();
  return QRect(area.left(),
               kRulerHeight + kRowGap + boolTrackCount() * (kBoolRowHeight + kRowGap) + track * (kFloatRowHeight + kRowGap),
               area.width(), kFloatRowHeight);
}

QSize TrackView::sizeHint() const {
  int height = kRulerHeight + kRowGap + boolTrackCount() * (kBoolRowHeight + kRowGap);
  height += floatTrackCount() * (kFloatRowHeight + kRowGap);
  return {600, height + 2};
}

QSize TrackView::minimumSizeHint() const { return {kHeaderWidth + 100, sizeHint().height()}; }

int TrackView::frameAt(double x) const {
  if (frames_ <= 0) return -1;
  const QRect area = timeArea();
  const double cell = static_cast<double>(area.width()) / frames_;
  return std::clamp(static_cast<int>(std::floor((x - area.left()) / cell)), 0, frames_ - 1);
}

double TrackView::xForFrame(int frame) const {
  const QRect area = timeArea();
  if (frames_ <= 0) return area.left();
  return area.left() + (frame + 0.5) * static_cast<double>(area.width()) / frames_;
}

void TrackView::paintRuler(QPainter& painter) const {
  const QRect ruler = rulerRect();
  painter.fillRect(ruler, kRowBackground.darker(115));
  if (frames_ <= 0) return;
  // Label every 1, 2 or 5 x 10^k frames, whichever keeps labels at least ~70 px apart.
  const double cell = static_cast<double>(ruler.width()) / frames_;
  int step = 1;
  for (int decade = 1; step * cell < 70.0 && decade < 1'000'000; decade *= 10) {
    for (const int multiple : {1, 2, 5, 10}) {
      step = multiple * decade;
      if (step * cell >= 70.0) break;
    }
  }
  painter.setPen(QColor(150, 155, 162));
  const int minor = std::max(1, step / 5);
  for (int frame = 0; frame < frames_; frame += minor) {
    const int x = static_cast<int>(std::lround(xForFrame(frame)));
    const bool major = frame % step == 0;
    painter.drawLine(x, ruler.bottom(), x, ruler.bottom() - (major ? 8 : 4));
    if (major) painter.drawText(QRect(x + 3, ruler.top(), 60, ruler.height() - 6), Qt::AlignLeft | Qt::AlignVCenter,
                                QString::number(frame));
  }
}

void TrackView::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), kBackground);
  QFont font = painter.font();
  font.setPointSizeF(8.5);
  painter.setFont(font);
  paintRuler(painter);

  const double cell = frames_ > 0 ? static_cast<double>(timeArea().width()) / frames_ : 0.0;
  for (int t = 0; t < boolTrackCount(); ++t) {
    const QRect row = boolTrackRect(t);
    const BoolTrack& track = bool_tracks_[static_cast<size_t>(t)];
    painter.fillRect(row, kRowBackground);
    painter.setPen(kHeaderText);
    painter.drawText(QRect(6, row.top(), kHeaderWidth - 10, row.height()), Qt::AlignVCenter | Qt::AlignLeft, track.name);
    // Draw runs, not frames: a 10 000-frame clip is a handful of rectangles.
    for (int f = 0; f < frames_;) {
      if (!track.values[static_cast<size_t>(f)]) { ++f; continue; }
      int end = f;
      while (end < frames_ && track.values[static_cast<size_t>(end)]) ++end;
      const QRectF run(row.left() + f * cell, row.top() + 3, std::max(1.0, (end - f) * cell), row.height() - 6);
      painter.fillRect(run, track.color);
      f = end;
    }
    // Unheld runs: the track's colour dimmed under a hatch, so an "on" the user did not get reads apart.
    for (int f = 0; f < frames_ && !track.unheld.empty();) {
      if (!isUnheld(t, f)) { ++f; continue; }
      int end = f;
      while (end < frames_ && isUnheld(t, end)) ++end;
      const QRectF run(row.left() + f * cell, row.top() + 3, std::max(1.0, (end - f) * cell), row.height() - 6);
      painter.fillRect(run, kRowBackground);
      painter.fillRect(run, QBrush(track.color, Qt::BDiagPattern));
      painter.setPen(QPen(track.color, 1));
      painter.drawRect(run.adjusted(0, 0, -1, -1));
      f = end;
    }
    // Lifted runs: the bar raised off the row's floor (its lower half cleared), a foot in the air.
    for (int f = 0; f < frames_ && !track.lifted.empty();) {
      if (!isLifted(t, f)) { ++f; continue; }
      int end = f;
      while (end < frames_ && isLifted(t, end)) ++end;
      const double middle = row.top() + 0.5 * row.height();
      painter.fillRect(QRectF(row.left() + f * cell, middle, std::max(1.0, (end - f) * cell), row.bottom() - 2 - middle),
                       kRowBackground);
      f = end;
    }
  }

  for (int t = 0; t < floatTrackCount() && frames_ > 0; ++t) {
    const FloatTrack& track = float_tracks_[static_cast<size_t>(t)];
    const QRect row = floatTrackRect(t);
    painter.fillRect(row, kRowBackground);
    painter.setPen(kHeaderText);
    painter.drawText(QRect(6, row.top(), kHeaderWidth - 10, row.height()), Qt::AlignVCenter | Qt::AlignLeft, track.name);
    QPainterPath curve;
    curve.moveTo(row.left(), row.bottom());
    // A step per frame, or, with more frames than pixels, per pixel column the highest of its frames (a
    // one-frame spike stays visible; a 36,000-frame clip is 1,300 steps, not 36,000).
    const int columns = std::min(frames_, std::max(1, timeArea().width()));
    const double step = static_cast<double>(timeArea().width()) / columns;
    for (int c = 0, f = 0; c < columns; ++c) {
      const int end = std::max(f + 1, static_cast<int>(static_cast<long long>(c + 1) * frames_ / columns));
      float highest = track.values[static_cast<size_t>(f)];
      for (; f < end; ++f) highest = std::max(highest, track.values[static_cast<size_t>(f)]);
      const double v = std::clamp((highest - track.minimum) / (track.maximum - track.minimum), 0.0f, 1.0f);
      const double y = row.bottom() - v * (row.height() - 4);
      curve.lineTo(row.left() + c * step, y);
      curve.lineTo(row.left() + (c + 1) * step, y);
    }
    curve.lineTo(row.right(), row.bottom());
    curve.closeSubpath();
    painter.setRenderHint(QPainter::Antialiasing);
    QColor fill = track.color;
    fill.setAlpha(120);
    painter.fillPath(curve, fill);
    painter.setPen(track.color.lighter(115));
    painter.drawPath(curve);
    painter.setRenderHint(QPainter::Antialiasing, false);
  }

  if (frames_ > 0) {
    const int x = static_cast<int>(std::lround(xForFrame(playhead_)));
    painter.setPen(QPen(kPlayhead, 2));
    painter.drawLine(x, 0, x, height());
  }
}

void TrackView::mousePressEvent(QMouseEvent* event) {
  if (frames_ <= 0 || event->button() != Qt::LeftButton) return;
  const QPoint pos = event->position().toPoint();
  const int frame = frameAt(pos.x());
  if (rulerRect().contains(pos)) {
    scrubbing_ = true;
    emit scrubbed(frame);
    return;
  }
  if (!editable_) return;
  for (int t = 0; t < boolTrackCount(); ++t) {
    if (!boolTrackRect(t).contains(pos)) continue;
    // A press toggles the frame, but on an unheld "on" it paints on: the user asks for it to be held.
    const bool value = isUnheld(t, frame) || !bool_tracks_[static_cast<size_t>(t)].values[static_cast<size_t>(frame)];
    stroke_ = {t, value, frame, frame, frame};
    paintStroke(frame);
    return;
  }
}

void TrackView::mouseMoveEvent(QMouseEvent* event) {
  const int frame = frameAt(event->position().x());
  if (scrubbing_) {
    emit scrubbed(frame);
  } else if (stroke_.track >= 0) {
    const int first = stroke_.first, last = stroke_.last;
    paintStroke(frame);
    if (stroke_.first != first || stroke_.last != last) emit trackEdited(stroke_.track, stroke_.first, stroke_.last, stroke_.value);
  }
}

void TrackView::paintStroke(int frame) {
  // Fill from the previous mouse frame to this one so a fast drag leaves no gaps.
  auto& values = bool_tracks_[static_cast<size_t>(stroke_.track)].values;
  for (int f = std::min(stroke_.previous, frame); f <= std::max(stroke_.previous, frame); ++f)
    values[static_cast<size_t>(f)] = stroke_.value;
  stroke_.first = std::min(stroke_.first, frame);
  stroke_.last = std::max(stroke_.last, frame);
  stroke_.previous = frame;
  update();
}

void TrackView::mouseReleaseEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  scrubbing_ = false;
  if (stroke_.track >= 0) {
    const Stroke done = stroke_;
    stroke_ = {};
    emit trackEdited(done.track, done.first, done.last, done.value);
  }
}

}  // namespace motionstyle
