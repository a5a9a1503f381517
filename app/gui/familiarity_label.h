#pragma once
// FamiliarityLabel: the Result panel's "Familiarity" row: how close the content clip is to the motion
// the chosen style network's loss network learnt from (style/familiarity.h), as a coloured reading
// with the next step ("Adapt...", which emits adaptRequested()) when the clip is not familiar.
// Computed on the GUI thread when the clip or the network changes: a projection of the clip, a few
// milliseconds for a minute of motion.

#include <QLabel>

#include <optional>

#include "clip_loader.h"
#include "nn/network_file.h"
#include "style/familiarity.h"
#include "style/stylizer.h"

namespace motionstyle {

class FamiliarityLabel : public QLabel {
  Q_OBJECT

 public:
  explicit FamiliarityLabel(QWidget* parent = nullptr);

  // Measures `clip` (its content features) with `network`'s loss network, as the network prepared it
  // (no layer set up again); either may be null (then "-"). A clip that cannot be featurised reads
  // "-" too (Stylize says why).
  void measure(const LoadedClip* clip, const style::Stylizer* network);
  const std::optional<style::Familiarity>& familiarity() const { return familiarity_; }

 signals:
  void adaptRequested();

 private:
  std::optional<style::Familiarity> familiarity_;
};

}  // namespace motionstyle
