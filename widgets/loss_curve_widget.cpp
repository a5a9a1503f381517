#include "loss_curve_widget.h"

#include <QFontMetrics>
#include <QPainter>
#include <QPainterPath>

#include <algorithm>
#include <cmath>
#include <limits>

namespace motionstyle {
namespace {

constexpr int kLeftMargin = 48;
constexpr int kRightMargin = 10;
constexpr int kTopMargin = 10;
constexpr int kBottomMargin = 24;

QString decadeLabel(int exponent) {
  if (exponent == 0) return QStringLiteral("1");
  return QStringLiteral("1e%1").arg(exponent);
}

}  // namespace

LossCurveWidget::LossCurveWidget(QWidget* parent) : QWidget(parent) {
  setObjectName(QStringLiteral("LossCurve"));
  setAttribute(Qt::WA_OpaquePaintEvent);
  setXAxisName(tr("epochs"));
}

void LossCurveWidget::setXAxisName(const QString& name) {
  x_axis_name_ = name;
  setToolTip(tr("Loss per term (unweighted), log scale, against %1").arg(name));
  update();
}

void LossCurveWidget::clear() {
  series_.clear();
  skipped_ = 0;
  update();
}

QColor LossCurveWidget::termColor(const QString& term) {
  if (term == QLatin1String("content")) return {76, 189, 92};
  if (term == QLatin1String("style")) return {219, 74, 69};
  if (term == QLatin1String("foot")) return {240, 170, 60};
  if (term == QLatin1String("bone")) return {170, 120, 230};
  if (term == QLatin1String("trajectory")) return {90, 200, 220};
  if (term == QLatin1String("total")) return {230, 230, 230};
  if (term == QLatin1String("mse")) return {66, 128, 235};
  if (term == QLatin1String("sparsity")) return {200, 200, 90};
  return QColor::fromHsv(static_cast<int>(qHash(term) % 360U), 160, 230);
}

LossCurveWidget::Series& LossCurveWidget::series(const QString& term) {
  for (Series& s : series_)
    if (s.term == term) return s;
  series_.push_back({term, termColor(term), {}});
  return series_.back();
}

void LossCurveWidget::addPoint(const QString& term, double x, double y) {
  Series& s = series(term);
  if (!(y > 0.0) || !std::isfinite(y) || !std::isfinite(x)) {
    ++skipped_;
    return;
  }
  s.points.emplace_back(x, y);
  update();
}

void LossCurveWidget::setHistory(const QStringList& terms, const std::vector<std::vector<double>>& values) {
  clear();
  for (const QString& term : terms) series(term);
  for (std::size_t epoch = 0; epoch < values.size(); ++epoch)
    for (qsizetype i = 0; i < terms.size() && static_cast<std::size_t>(i) < values[epoch].size(); ++i)
      addPoint(terms[i], static_cast<double>(epoch + 1), values[epoch][static_cast<std::size_t>(i)]);
  update();
}

QStringList LossCurveWidget::terms() const {
  QStringList names;
  for (const Series& s : series_) names << s.term;
  return names;
}

int LossCurveWidget::pointCount(const QString& term) const {
  for (const Series& s : series_)
    if (s.term == term) return static_cast<int>(s.points.size());
  return 0;
}

void LossCurveWidget::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.setRenderHint(QPainter::Antialiasing);
  painter.fillRect(rect(), QColor(38, 40, 44));
  const QFontMetrics metrics(font());
  const auto legendText = [](const Series& s) {
    return s.points.empty() ? s.term : QStringLiteral("%1  %2").arg(s.term).arg(s.points.back().y(), 0, 'g', 3);
  };
  int legend_width = 0;
  for (const Series& s : series_) legend_width = std::max(legend_width, metrics.horizontalAdvance(legendText(s)));
  // The legend goes beside the plot when the widget is wide enough, else over its top-right corner.
  const int legend_box_width = legend_width + 26;
  const bool legend_beside = width() - kLeftMargin - kRightMargin - legend_box_width >= 200;
  const int right_margin = kRightMargin + (legend_beside ? legend_box_width : 0);
  const QRectF plot(kLeftMargin, kTopMargin, std::max(10, width() - kLeftMargin - right_margin),
                    std::max(10, height() - kTopMargin - kBottomMargin));
  painter.setPen(QColor(90, 92, 98));
  painter.drawRect(plot);

  double x_min = std::numeric_limits<double>::infinity();
  double x_max = -x_min;
  double y_min = x_min;
  double y_max = -x_min;
  for (const Series& s : series_) {
    for (const QPointF& p : s.points) {
      x_min = std::min(x_min, p.x());
      x_max = std::max(x_max, p.x());
      y_min = std::min(y_min, p.y());
      y_max = std::max(y_max, p.y());
    }
  }
  painter.setPen(QColor(170, 172, 178));
  if (!std::isfinite(x_min)) {
    painter.drawText(plot, Qt::AlignCenter, tr("No loss values yet"));
    return;
  }
  // Whole decades on y; x from 0 (or the first point) to the last point.
  const int low_decade = static_cast<int>(std::floor(std::log10(y_min)));
  const int high_decade = std::max(low_decade + 1, static_cast<int>(std::ceil(std::log10(y_max))));
  x_min = std::min(0.0, x_min);
  if (x_max <= x_min) x_max = x_min + 1.0;
  const auto toScreen = [&](QPointF p) {
    const double u = (p.x() - x_min) / (x_max - x_min);
    const double v = (std::log10(p.y()) - low_decade) / (high_decade - low_decade);
    return QPointF(plot.left() + u * plot.width(), plot.bottom() - v * plot.height());
  };

  // Decade grid lines and labels.
  const int decade_step = std::max(1, (high_decade - low_decade) / 6);
  for (int decade = low_decade; decade <= high_decade; decade += decade_step) {
    const double y = toScreen(QPointF(x_min, std::pow(10.0, decade))).y();
    painter.setPen(QColor(60, 62, 68));
    painter.drawLine(QPointF(plot.left(), y), QPointF(plot.right(), y));
    painter.setPen(QColor(170, 172, 178));
    painter.drawText(QRectF(0, y - metrics.height() / 2.0, kLeftMargin - 4, metrics.height()),
                     Qt::AlignRight | Qt::AlignVCenter, decadeLabel(decade));
  }
  painter.drawText(QRectF(plot.left(), plot.bottom() + 2, plot.width(), kBottomMargin - 2), Qt::AlignLeft | Qt::AlignTop,
                   QString::number(x_min, 'g', 3));
  painter.drawText(QRectF(plot.left(), plot.bottom() + 2, plot.width(), kBottomMargin - 2), Qt::AlignHCenter | Qt::AlignTop,
                   x_axis_name_);
  painter.drawText(QRectF(plot.left(), plot.bottom() + 2, plot.width(), kBottomMargin - 2), Qt::AlignRight | Qt::AlignTop,
                   QString::number(x_max, 'g', 4));

  painter.save();
  painter.setClipRect(plot.adjusted(-1, -1, 1, 1));
  for (const Series& s : series_) {
    if (s.points.empty()) continue;
    painter.setPen(QPen(s.color, 1.6));
    if (s.points.size() == 1) {
      painter.setBrush(s.color);
      painter.drawEllipse(toScreen(s.points.front()), 2.5, 2.5);
      continue;
    }
    QPainterPath path(toScreen(s.points.front()));
    for (std::size_t i = 1; i < s.points.size(); ++i) path.lineTo(toScreen(s.points[i]));
    painter.setBrush(Qt::NoBrush);
    painter.drawPath(path);
  }
  painter.restore();

  // Legend: swatch, term and its latest value.
  const int row = metrics.height();
  const double legend_left = legend_beside ? plot.right() + 4 : plot.right() - legend_box_width;
  const QRectF legend(legend_left, plot.top() + (legend_beside ? 0 : 4), legend_width + 22,
                      row * static_cast<int>(series_.size()) + 6);
  painter.setPen(Qt::NoPen);
  painter.setBrush(QColor(30, 32, 36, 210));
  painter.drawRoundedRect(legend, 3, 3);
  for (std::size_t i = 0; i < series_.size(); ++i) {
    const Series& s = series_[i];
    const double y = legend.top() + 3 + row * static_cast<double>(i);
    painter.fillRect(QRectF(legend.left() + 5, y + row / 2.0 - 2, 10, 4), s.color);
    painter.setPen(QColor(220, 222, 228));
    painter.drawText(QRectF(legend.left() + 19, y, legend_width + 2, row), Qt::AlignLeft | Qt::AlignVCenter, legendText(s));
  }
}

}  // namespace motionstyle
