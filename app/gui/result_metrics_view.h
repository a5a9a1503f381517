#pragma once
// The Result panel's quality figures of one result: a table of foot skate, floor penetration, bone
// error and residual for the raw network output and the cleaned clip, and the clean-up's warnings
// below it (the first few; all of them in the tooltip), each one that names frames a link to its
// first frame (frameRequested: the timeline goes there). Shows "-" without a result.

#include <QWidget>

class QLabel;
class QTableWidget;

namespace motionstyle {
namespace style {
struct StylizeCleanupResult;
}

class ResultMetricsView : public QWidget {
  Q_OBJECT

 public:
  enum MetricRow { kSkateRow, kPenetrationRow, kBoneErrorRow, kResidualRow, kMetricRowCount };
  enum MetricColumn { kRawColumn, kCleanedColumn };

  explicit ResultMetricsView(QWidget* parent = nullptr);

  void showResult(const style::StylizeCleanupResult* result);  // nullptr: no result
  QTableWidget* table() const { return table_; }

 signals:
  // A warning's link was clicked: show this frame of the content (the clean-up names the frames of the
  // clip it gives back, CleanupOptions::warning_fps).
  void frameRequested(int frame);

 private:
  QTableWidget* table_ = nullptr;
  QLabel* warnings_label_ = nullptr;
};

}  // namespace motionstyle
