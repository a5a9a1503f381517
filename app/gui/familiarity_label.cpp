#include "familiarity_label.h"

#include <exception>
#include <optional>

#include "features/representation.h"
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

// The shipped loss network (every shipped style learnt against it), read once; null without one.
const nn::LossNetworkModel* shippedLossNetwork() {
  static const std::optional<nn::LossNetworkModel> model = []() -> std::optional<nn::LossNetworkModel> {
    try {
      const QString file = shippedLossNetworkFile();
      if (!file.isEmpty()) return nn::loadLossNetwork(file.toStdString());
    } catch (const std::exception&) {  // a damaged file: the row reads "-" until a style is chosen
    }
    return std::nullopt;
  }();
  return model ? &*model : nullptr;
}

}  // namespace

void FamiliarityLabel::measure(const LoadedClip* clip, const style::Stylizer* network) {
  familiarity_.reset();
  int rest_pose_frames = 0;
  const nn::LossNetworkModel* shipped = network == nullptr ? shippedLossNetwork() : nullptr;
  if (clip != nullptr && clip->mapping && (network != nullptr || shipped != nullptr)) {
    try {
      const MotionFeatures features = extractFeatures(clip->motion, *clip->mapping);
      rest_pose_frames = features.anchor.rest_pose_frames;
      familiarity_ = network != nullptr ? style::measureFamiliarity(*network, features.values)
                                        : style::measureFamiliarity(*shipped, features.values);
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
  if (rest_pose_frames > 0) text += tr("<br>Frame 0 is the rig's rest pose, not motion: it is kept as it is.");
  setText(text);
}

}  // namespace motionstyle
