// The Result panel's result as the viewport and the timeline show it: its figures (the cleaned clip,
// and the raw network output when asked) and its quality tracks at the content's rate.
#include "familiarity_label.h"
#include "result_figures.h"
#include "result_panel.h"

namespace motionstyle {

QStringList ResultPanel::resultFigureNames(bool include_raw) const {
  if (!result_ || !content_) return {};
  const QString name = resultIsStale() ? tr("%1 (%2, out of date)").arg(content_->name, result_network_name_)
                                       : tr("%1 (%2)").arg(content_->name, result_network_name_);
  return include_raw ? QStringList{name, tr("%1 raw").arg(name)} : QStringList{name};
}

std::vector<FigureData> ResultPanel::resultFigures(bool include_raw) const {
  std::vector<FigureData> figures;
  const QStringList names = resultFigureNames(include_raw);
  if (names.isEmpty()) return figures;
  figures.push_back(cleanedOutputFigure(*result_, *content_, names.front(), content_->fps()));
  if (include_raw) figures.push_back(rawOutputFigure(*result_, *content_, names.back(), content_->fps()));
  return figures;
}

QualityTracks ResultPanel::qualityTracks() const {
  QualityTracks tracks;
  if (!content_) return tracks;
  if (const auto& familiarity = familiarity_label_->familiarity())
    tracks.familiarity_cm = trackAtRate(familiarity->per_frame_cm, kDefaultFeatureFps, content_->fps());
  if (!result_) return tracks;
  tracks.skate_cm_s = trackAtRate(result_->cleaned_metrics.skate_track_cm_s, result_->cleanup_fps, content_->fps());
  tracks.held_contacts = locksAtRate(result_->contacts, result_->cleanup_fps, content_->fps(), content_->frameCount());
  tracks.lifted_contacts =
      locksAtRate(result_->report.lifted_contacts, result_->cleanup_fps, content_->fps(), content_->frameCount());
  tracks.raw_bone_error_cm =
      trackAtRate(result_->raw_metrics.bone_error_track_cm, result_->stylized.fps, content_->fps());
  return tracks;
}

}  // namespace motionstyle
