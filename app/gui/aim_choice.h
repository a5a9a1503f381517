#pragma once
// AimChoice: the Result panel's "Aim at" control, which style clip the refinement aims at
// (style/locomotion_kind.h): the style's walk, run, or walk turning left or right. By default the kind
// is read from the content clip (a fifth of its frames without a foot down is a run, a steady turn is a
// turning walk); the user picks one when the reading is wrong for their clip (a shuffling run read as a
// walk) or to try the style's other gait. The same choice as `motionstyle-cli stylize --kind`.

#include <QComboBox>
#include <QString>

#include <string>

namespace motionstyle {

class AimChoice : public QComboBox {
  Q_OBJECT

 public:
  explicit AimChoice(QWidget* parent = nullptr);

  // "" (read from the clip, the first entry) or one of style::kLocomotionKinds.
  std::string kind() const;
  // Selects `kind` ("" or one of kLocomotionKinds); any other selects "read from the clip".
  void setKind(const std::string& kind);

  // The status's sentence for a result aimed at `aimed` (the StylizedClip's kind), saying whether it
  // was read from the clip or chosen here: " Aimed at the style's walk (read from the clip)."; "" for
  // a result no refinement aimed (aimed "").
  QString statusSentence(const std::string& aimed) const;

 signals:
  void kindChanged();  // the user or setKind picked another entry
};

}  // namespace motionstyle
