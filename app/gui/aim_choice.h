#pragma once
// AimChoice: the Result panel's "Aim at" control, which style clip the refinement aims at
// (style/locomotion_kind.h): the style's walk, run, or walk turning left or right. By default the kind
// is read from the content clip (a fifth of its frames without a foot down is a run, a steady turn is a
// turning walk); the user picks one when the reading is wrong for their clip (a shuffling run read as a
// walk) or to try the style's other gait. The same choice as `motionstyle-cli stylize --kind`.

#include <QComboBox>
#include <QMap>
#include <QString>

#include <string>

namespace motionstyle {

class AimChoice : public QComboBox {
  Q_OBJECT

 public:
  explicit AimChoice(QWidget* parent = nullptr);

  // "" (read from the clip, the first entry) or one of style::kLocomotionKinds.
  std::string kind() const;
  // Shows the choice made for the clip `clip_file` (the last one picked while it was the content),
  // "read from the clip" for one without: a kind belongs to a clip, so another clip does not inherit
  // it. `read_kind` is what style::locomotionKind reads from the clip, shown in the first entry before
  // any result ("Read from the clip: walk"; "" for no clip or none read). No kindChanged: the caller
  // redoes its result for the new clip anyway.
  void showChoiceFor(const QString& clip_file, const std::string& read_kind);

  // The status's sentence for a result aimed at `aimed` (the StylizedClip's kind), saying whether it
  // was read from the clip or chosen here: " Aimed at the style's walk (read from the clip)."; "" for
  // a result no refinement aimed (aimed "").
  QString statusSentence(const std::string& aimed) const;

 signals:
  void kindChanged();  // the user picked another entry

 private:
  QString clip_file_;                 // the content clip the choice is for
  QMap<QString, QString> by_clip_;    // clip file -> the kind picked for it ("" none)
};

}  // namespace motionstyle
