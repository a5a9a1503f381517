// The Result panel's export: the cleaned clip written as BVH on the content's skeleton, atomically
// (bvh_writer.h); never over the content clip, never over a file the user did not agree to replace.
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>

#include <exception>

#include "bvh/bvh_writer.h"
#include "common/output_paths.h"
#include "error_text.h"
#include "result_panel.h"

namespace motionstyle {

bool ResultPanel::exportResult(const QString& file, bool overwrite) {
  const QString title = tr("Could not export the clip");
  if (!result_) {
    report(title, tr("There is no result to export yet: Stylize first."));
    return false;
  }
  if (resultIsStale()) {
    report(title, tr("The result shown is out of date (%1 since it was made with %2): wait for the update or "
                     "Stylize again, then export.")
                      .arg(stale_reason_, result_network_name_));
    return false;
  }
  if (QFileInfo::exists(file) && !overwrite) {
    report(title, tr("%1 already exists; it was not overwritten.").arg(file));
    return false;
  }
  try {  // the content clip itself is never overwritten, even when the user confirmed the file dialog
    if (content_) checkOutputPaths({{content_->path.toStdString(), "the content clip"}}, {{file.toStdString(), "the export"}});
    writeBvh(result_->cleaned, file.toStdString());
  } catch (...) {
    report(title, errorText(std::current_exception(), file));
    return false;
  }
  last_export_folder_ = QFileInfo(file).absolutePath();
  emit statusMessage(tr("Exported %1").arg(file));
  return true;
}

void ResultPanel::browseExport() {
  if (!result_ || !content_) return;
  if (resultIsStale()) {  // says why, without a file dialog first
    exportResult(QString(), false);
    return;
  }
  const QString folder = last_export_folder_.isEmpty() ? QFileInfo(content_->path).absolutePath() : last_export_folder_;
  const QString suggestion = QFileInfo(content_->path).completeBaseName() + QLatin1Char('_') +
                             (result_network_name_.isEmpty() ? QStringLiteral("styled") : result_network_name_) +
                             QStringLiteral(".bvh");
  // QFileDialog asks before replacing an existing file, so the choice to overwrite is the user's.
  const QString file = QFileDialog::getSaveFileName(this, tr("Export the cleaned clip"), QDir(folder).filePath(suggestion),
                                                    tr("BVH motion (*.bvh)"));
  if (!file.isEmpty()) exportResult(file, /*overwrite=*/true);
}

}  // namespace motionstyle
