#pragma once
// The Result panel's quality figures of one result: a table of foot skate, floor penetration, bone
// error and residual for the raw network output and the cleaned clip, and the clean-up's warnings
// below it (the first few; all of them in the tooltip). Shows "-" without a result.

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

 private:
  QTableWidget* table_ = nullptr;
  QLabel* warnings_label_ = nullptr;
};

}  // namespace motionstyle
