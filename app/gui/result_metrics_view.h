#pragma once
// The Result panel's quality figures of one result: a table of foot skate, floor penetration, bone
// error and residual for the raw network output and the cleaned clip, and the clean-up's warnings
// below it (the first few; all of them in the tooltip), each one that names frames a link to its
// first frame (frameRequested: the timeline goes there), as is a click on the cleaned residual (to its
// worst frame, named with its joint in the cell's tooltip). A warning of a contact that holds a foot
// under the style's lift (CleanupWarning::contact) also offers its fix after its advice: "End it", the
// contact ended there (contactEndRequested). Shows "-" without a result.

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
  // A warning's link or the cleaned residual was clicked: show this frame of the content (the frames of
  // the clip the clean-up gives back, CleanupOptions::warning_fps).
  void frameRequested(int frame);
  // A held-down warning's "End it": end the contact of `contact` (a ContactLabel) over the content's
  // frames first..last (the warning's, the clip's own frames).
  void contactEndRequested(int contact, int first_frame, int last_frame);

 private:
  QTableWidget* table_ = nullptr;
  QLabel* warnings_label_ = nullptr;
  int worst_residual_frame_ = -1;  // of the result shown, in the clip's frames; -1: none
};

}  // namespace motionstyle
