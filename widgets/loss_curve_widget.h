#pragma once
// LossCurveWidget: live training loss curves, one per term, painted with QPainter (no VTK, no core
// types). The y axis is logarithmic because the terms span decades (a style term of 1e-4 next to a
// content term of 1); the x axis is in epochs (fractional while an epoch runs: epoch - 1 + step/steps),
// or in the optimisation method's iterations (setXAxisName).
//
// Non-positive and non-finite values cannot be drawn on a log axis: they are counted (skippedPoints)
// but not stored, so a diverging run does not break the plot.

#include <QColor>
#include <QString>
#include <QStringList>
#include <QWidget>

#include <vector>

namespace motionstyle {

class LossCurveWidget : public QWidget {
  Q_OBJECT

 public:
  explicit LossCurveWidget(QWidget* parent = nullptr);

  // Removes every series and point.
  void clear();
  // Appends (x epochs, y loss) to the series `term`, creating it (with its colour) on first use.
  void addPoint(const QString& term, double x, double y);
  // Replaces everything with a per-epoch history: values[e][i] is terms[i] after epoch e + 1
  // (nn::LossHistory's layout). Rows shorter than `terms` are tolerated (missing values skipped).
  void setHistory(const QStringList& terms, const std::vector<std::vector<double>>& values);

  // What x counts, named under the axis: "epochs" (the default, training) or "iterations" (the
  // optimisation method). clear() keeps it.
  void setXAxisName(const QString& name);
  const QString& xAxisName() const { return x_axis_name_; }

  QStringList terms() const;
  int pointCount(const QString& term) const;  // 0 for an unknown term
  int skippedPoints() const { return skipped_; }

  // Fixed colours for the known term names (content, style, foot, bone, trajectory, total, mse,
  // sparsity), a stable hash-based colour for others.
  static QColor termColor(const QString& term);

  QSize sizeHint() const override { return {360, 200}; }
  // Small enough for a laptop screen: the Style networks panel, and so the window, is never taller
  // than its forms need (they scroll) plus this.
  QSize minimumSizeHint() const override { return {200, 64}; }

 protected:
  void paintEvent(QPaintEvent* event) override;

 private:
  struct Series {
    QString term;
    QColor color;
    std::vector<QPointF> points;  // x in epochs, y the raw (positive) value
  };
  Series& series(const QString& term);

  std::vector<Series> series_;
  int skipped_ = 0;
  QString x_axis_name_;
};

}  // namespace motionstyle
