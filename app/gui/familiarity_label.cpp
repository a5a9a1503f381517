#include "familiarity_label.h"

#include <exception>
#include <optional>

#include "shipped_networks.h"

namespace motionstyle {

FamiliarityLabel::FamiliarityLabel(QWidget* parent) : QLabel(parent) {
  setObjectName(QStringLiteral("FamiliarityLabel"));
  setWordWrap(true);
  setTextFormat(Qt::RichText);
  setToolTip(tr("How close the content is to the motion the networks learnt from: the loss network's "
                "reconstruction error (familiar up to %1 cm, unusual up to %2 cm)")
                 .arg(style::kFamiliarMaxCm)
                 .arg(style::kUnusualMaxCm));
  connect(this, &QLabel::linkActivated, this, [this](const QString&) { emit adaptRequested(); });
  setText(QStringLiteral("-"));
}

namespace {

// The shipped loss network (every shipped style learnt against it), read and prepared once; null
// without one. Its projection shares its kernel spectra with the shipped styles' (sharedProjection).
struct ShippedReader {
  nn::LossNetworkModel model;
  std::shared_ptr<const nn::FastStylizer> prepared;  // kept: the shared spectra outlive any style
  nn::FastStylizer projection;                       // a copy to run (GUI thread only)
};

ShippedReader* shippedReader() {
  static const std::unique_ptr<ShippedReader> reader = []() -> std::unique_ptr<ShippedReader> {
    try {
      const QString file = shippedLossNetworkFile();
      if (file.isEmpty()) return nullptr;
      nn::LossNetworkModel model = nn::loadLossNetwork(file.toStdString());
      auto prepared = style::sharedProjection(model.network);
      nn::FastStylizer projection = *prepared;
      return std::make_unique<ShippedReader>(ShippedReader{std::move(model), std::move(prepared), std::move(projection)});
    } catch (const std::exception&) {  // a damaged file: the row reads "-" until a style is chosen
    }
    return nullptr;
  }();
  return reader.get();
}

// Whether `a` and `b` (null: the shipped loss network) read a clip alike: the same loss network
// (one shared prepared projection: sharedProjection compared the weights once) and normalisation.
bool readAlike(const style::Stylizer* a, const style::Stylizer* b) {
  if (a == b) return true;
  const ShippedReader* shipped = shippedReader();
  if ((a == nullptr || b == nullptr) && shipped == nullptr) return false;
  const nn::FastStylizer* projection_a = a ? a->sharedLossProjection().get() : shipped->prepared.get();
  const nn::FastStylizer* projection_b = b ? b->sharedLossProjection().get() : shipped->prepared.get();
  const FeatureStatistics& statistics_a = a ? a->model().normalisation : shipped->model.normalisation;
  const FeatureStatistics& statistics_b = b ? b->model().normalisation : shipped->model.normalisation;
  return projection_a == projection_b && statistics_a.mean == statistics_b.mean && statistics_a.std == statistics_b.std;
}

}  // namespace

void FamiliarityLabel::measure(std::uint64_t clip_id, const MotionFeatures* features,
                               std::shared_ptr<const style::Stylizer> network) {
  ShippedReader* shipped = network == nullptr ? shippedReader() : nullptr;
  const bool readable = features != nullptr && (network != nullptr || shipped != nullptr);
  if (readable && familiarity_ && clip_id == measured_clip_ && readAlike(network.get(), measured_with_.get())) {
    measured_with_ = std::move(network);  // the same reading: the text stays
    return;
  }
  familiarity_.reset();
  measured_clip_ = 0;
  measured_with_.reset();
  if (readable) {
    try {
      familiarity_ = network != nullptr
                         ? style::measureFamiliarity(*network, features->values)
                         : style::familiarityFromReconstruction(
                               features->values, style::projectFeatures(shipped->projection, shipped->model.normalisation,
                                                                        features->values));
      measured_clip_ = clip_id;
      measured_with_ = std::move(network);
    } catch (const std::exception&) {
      familiarity_.reset();
    }
  }
  if (!familiarity_) {
    setText(QStringLiteral("-"));
    return;
  }
  static const char* kColours[] = {"#4caf50", "#d08a2a", "#d04a3a"};  // familiar, unusual, far
  QString text = QStringLiteral("<span style=\"color:%1\">&#9679;</span> %2")
                     .arg(QLatin1String(kColours[static_cast<int>(familiarity_->level)]),
                          QString::fromStdString(style::familiaritySummary(*familiarity_)).toHtmlEscaped());
  if (familiarity_->level != style::FamiliarityLevel::Familiar) text += tr(" <a href=\"adapt\">Adapt...</a>");
  // features/rest_pose_frames.h: a CMU file's T-pose frame 0.
  if (features->anchor.rest_pose_frames > 0) text += tr("<br>Frame 0 is the rig's rest pose, not motion: it is kept as it is.");
  setText(text);
}

}  // namespace motionstyle
