#pragma once
// The viewport's figures of a stylize + clean-up result (style::StylizeCleanupJob), shared by the Result panel
// and the off-screen filmstrip renderer, so that both draw exactly what the user sees:
//   - the cleaned clip on the content's own skeleton (blue), with the contacts the clean-up locked;
//   - the raw network output, 21 canonical joints (grey), with the content's contacts (what the
//     network was asked to respect, and what judges it).
// Both are in the CONTENT's display space (same floor) and at `display_fps` (the timeline's rate).

#include <QString>

#include "clip_loader.h"
#include "figure_data.h"
#include "style/stylize_cleanup_job.h"

namespace motionstyle {

// content must be mapped (it was stylized). Throws std::invalid_argument otherwise.
FigureData cleanedOutputFigure(const style::StylizeCleanupResult& result, const LoadedClip& content, const QString& name,
                               double display_fps);
FigureData rawOutputFigure(const style::StylizeCleanupResult& result, const LoadedClip& content, const QString& name,
                           double display_fps);

}  // namespace motionstyle
