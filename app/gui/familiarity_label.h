#pragma once
// FamiliarityLabel: the Result panel's "Familiarity" row: how close the content clip is to the motion
// the chosen style network's loss network (before one is chosen: the shipped one) learnt from
// (style/familiarity.h), as a coloured reading with the next step ("Adapt...", which emits
// adaptRequested()) when the clip is not familiar.
// Computed on the GUI thread when the clip or the loss network changes: a projection of the clip, a
// few milliseconds for a minute of motion. A switch between styles trained against one loss network
// (every shipped style) reads nothing again: their readings of a clip are the same.

#include <QLabel>

#include <cstdint>
#include <memory>
#include <optional>

#include "features/representation.h"
#include "nn/network_file.h"
#include "style/familiarity.h"
#include "style/stylizer.h"

namespace motionstyle {

class FamiliarityLabel : public QLabel {
  Q_OBJECT

 public:
  explicit FamiliarityLabel(QWidget* parent = nullptr);

  // Measures the clip `clip_id` (LoadedClip::id) from its `features` (clipFeatures) with `network`'s
  // loss network, as the network prepared it (no layer set up again); before a style is chosen (null
  // `network`) with the shipped loss network, the one every shipped style learnt against (prepared
  // once, sharing its layers with the shipped styles). The reading is kept when the clip and the loss
  // network (weights and normalisation) are those of the last one. No features (no clip, or one that
  // cannot be featurised: Stylize says why) or no network of either kind reads "-".
  void measure(std::uint64_t clip_id, const MotionFeatures* features, std::shared_ptr<const style::Stylizer> network);
  const std::optional<style::Familiarity>& familiarity() const { return familiarity_; }

 signals:
  void adaptRequested();

 private:
  std::optional<style::Familiarity> familiarity_;
  std::uint64_t measured_clip_ = 0;                       // the clip familiarity_ reads, 0: none
  std::shared_ptr<const style::Stylizer> measured_with_;  // its network, null: the shipped loss network
};

}  // namespace motionstyle
