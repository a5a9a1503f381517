#include "result_metrics_view.h"

#include <QHeaderView>
#include <QLabel>
#include <QStringList>
#include <QTableWidget>
#include <QVBoxLayout>

#include <vector>

#include "features/proportions.h"
#include "ik/cleanup.h"
#include "mapping/canonical_joints.h"
#include "style/stylize_cleanup_job.h"
#include "style/stylized_cleanup.h"

namespace motionstyle {
namespace {

QString cm(double value, int decimals = 2) { return QString::number(value, 'f', decimals); }

}  // namespace

ResultMetricsView::ResultMetricsView(QWidget* parent) : QWidget(parent) {
  table_ = new QTableWidget(kMetricRowCount, 2, this);
  table_->setObjectName(QStringLiteral("MetricsTable"));
  table_->setHorizontalHeaderLabels({tr("Raw output"), tr("Cleaned")});
  table_->setVerticalHeaderLabels(
      {tr("Foot skate (cm/s)"), tr("Floor penetration (cm)"), tr("Bone error (cm)"), tr("Residual (cm)")});
  table_->verticalHeaderItem(kSkateRow)->setToolTip(
      tr("Mean horizontal speed of a foot over the contacts on the timeline's foot tracks; where heel\n"
         "and toe are both down, of the stiller one (a heel rolling up on its planted toe does not slide);\n"
         "not where the clean-up lifts a heel or toe off the floor with the style (a foot skates on it).\n"
         "The clean-up holds every such contact unless the style moved that step more than %1 cm;\n"
         "those count here (hatched on the foot tracks; the Skate row shows where).")
          .arg(kLockableSpreadCm));
  table_->verticalHeaderItem(kPenetrationRow)->setToolTip(tr("Deepest foot below the floor"));
  table_->verticalHeaderItem(kBoneErrorRow)->setToolTip(tr("Mean difference from the skeleton's bone lengths"));
  table_->verticalHeaderItem(kResidualRow)->setToolTip(
      tr("Distance of the mapped joints from the network's output: the mean, and in brackets the worst\n"
         "joint at the worst frame (where the clean-up changed the style most to plant the feet)"));
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionMode(QAbstractItemView::NoSelection);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
  table_->verticalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->setVerticalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  table_->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  table_->setSizeAdjustPolicy(QAbstractScrollArea::AdjustToContents);
  warnings_label_ = new QLabel(this);
  warnings_label_->setObjectName(QStringLiteral("CleanupWarnings"));
  warnings_label_->setWordWrap(true);
  warnings_label_->setTextFormat(Qt::RichText);
  warnings_label_->setTextInteractionFlags(Qt::LinksAccessibleByMouse | Qt::LinksAccessibleByKeyboard);
  warnings_label_->setStyleSheet(QStringLiteral("color: #d08a2a"));
  connect(warnings_label_, &QLabel::linkActivated, this, [this](const QString& link) {
    // "<frame>" or "end:<contact>:<first>:<last>" (showResult).
    const QStringList parts = link.split(QLatin1Char(':'));
    bool ok[3] = {false, false, false};
    if (parts.size() == 1) {
      const int frame = link.toInt(ok);
      if (ok[0]) emit frameRequested(frame);
    } else if (parts.size() == 4 && parts[0] == QLatin1String("end")) {
      const int contact = parts[1].toInt(&ok[0]), first = parts[2].toInt(&ok[1]), last = parts[3].toInt(&ok[2]);
      if (ok[0] && ok[1] && ok[2]) emit contactEndRequested(contact, first, last);
    }
  });
  // A click on the cleaned residual goes to its worst frame.
  connect(table_, &QTableWidget::cellClicked, this, [this](int row, int column) {
    if (row == kResidualRow && column == kCleanedColumn && worst_residual_frame_ >= 0)
      emit frameRequested(worst_residual_frame_);
  });
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(table_);
  layout->addWidget(warnings_label_);
  showResult(nullptr);
}

void ResultMetricsView::showResult(const style::StylizeCleanupResult* result) {
  // A cell is written only when its text changes: during a live drag a result arrives every few
  // tens of milliseconds, and a new item relaid the headers and repainted the whole table each time.
  const auto put = [this](int row, int column, const QString& text) {
    QTableWidgetItem* item = table_->item(row, column);
    if (item == nullptr) {
      item = new QTableWidgetItem(text);
      item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      table_->setItem(row, column, item);
    } else if (item->text() != text) {
      item->setText(text);
    }
  };
  const QString none = QStringLiteral("-");
  if (!result) {
    for (int row = 0; row < kMetricRowCount; ++row)
      for (int column : {kRawColumn, kCleanedColumn}) put(row, column, none);
    warnings_label_->clear();
    warnings_label_->setToolTip(QString());
    worst_residual_frame_ = -1;
    table_->item(kResidualRow, kCleanedColumn)->setToolTip(QString());
    return;
  }
  const ClipMetrics& raw = result->raw_metrics;
  const ClipMetrics& cleaned = result->cleaned_metrics;
  put(kSkateRow, kRawColumn, cm(raw.foot_skate_cm_s));
  put(kSkateRow, kCleanedColumn, cm(cleaned.foot_skate_cm_s));
  put(kPenetrationRow, kRawColumn, cm(raw.penetration_max_cm));
  put(kPenetrationRow, kCleanedColumn, cm(cleaned.penetration_max_cm));
  put(kBoneErrorRow, kRawColumn, cm(raw.bone_error_mean_cm));
  put(kBoneErrorRow, kCleanedColumn, cm(cleaned.bone_error_mean_cm, 4));
  // The raw output IS the target of the clean-up: its residual is zero by definition.
  put(kResidualRow, kRawColumn, raw.has_residual ? cm(raw.residual_mean_cm) : QStringLiteral("0 (target)"));
  put(kResidualRow, kCleanedColumn,
      cleaned.has_residual ? tr("%1 (max %2)").arg(cm(cleaned.residual_mean_cm), cm(cleaned.residual_max_cm, 1)) : none);
  // Where the worst is, in the frames of the clip given back (as the warnings name them,
  // CleanupOptions::warning_fps): the metrics are at the clean-up's rate.
  worst_residual_frame_ = -1;
  QString where;
  const double clip_fps = result->cleaned.fps();
  if (cleaned.has_residual && cleaned.residual_max_frame >= 0 && result->cleanup_fps > 0.0 && clip_fps > 0.0) {
    worst_residual_frame_ = frameAtRate(cleaned.residual_max_frame, clip_fps / result->cleanup_fps);
    const auto joint = static_cast<CanonicalJoint>(cleaned.residual_max_joint);
    where = tr("Worst: %1 at frame %2 (%3 s). Click to go there.")
                .arg(QString::fromUtf8(canonicalJointName(joint)))
                .arg(worst_residual_frame_)
                .arg(QString::number(worst_residual_frame_ / clip_fps, 'f', 2));
  }
  table_->item(kResidualRow, kCleanedColumn)->setToolTip(where);
  // A few lines in the panel, all of them in the tooltip: a long list would push the table away.
  // A warning that names frames links to its first one (the link keeps the warnings' colour).
  constexpr qsizetype kShownWarnings = 3;
  const std::vector<CleanupWarning>& warnings = result->report.warnings;
  QStringList shown, all;
  for (const CleanupWarning& warning : warnings) {
    const QString text = QString::fromStdString(warning.text);
    all << text;
    if (shown.size() == kShownWarnings) continue;
    QString line = warning.first_frame < 0 ? text.toHtmlEscaped()
                                           : QStringLiteral("<a href=\"%1\" style=\"color:#d08a2a\">%2</a>")
                                                 .arg(warning.first_frame)
                                                 .arg(text.toHtmlEscaped());
    if (warning.contact >= 0 && warning.first_frame >= 0)
      line += QStringLiteral(" <a href=\"end:%1:%2:%3\"><b>%4</b></a>")
                  .arg(warning.contact)
                  .arg(warning.first_frame)
                  .arg(warning.last_frame)
                  .arg(tr("End it"));
    shown << line;
  }
  if (all.size() > kShownWarnings) shown << tr("... and %1 more (hover to see them)").arg(all.size() - kShownWarnings);
  warnings_label_->setText(shown.join(QStringLiteral("<br>")));
  warnings_label_->setToolTip(all.isEmpty() ? QString() : tr("Click a warning to go to its first frame.\n\n") + all.join(QStringLiteral("\n")));
}

}  // namespace motionstyle
