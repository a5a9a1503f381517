#include "aim_choice.h"

#include <QSignalBlocker>

#include <algorithm>

#include "style/locomotion_kind.h"

namespace motionstyle {

AimChoice::AimChoice(QWidget* parent) : QComboBox(parent) {
  setObjectName(QStringLiteral("AimChoice"));
  addItem(tr("Read from the clip"), QString());
  for (const std::string_view kind : style::kLocomotionKinds)
    addItem(tr("The style's %1").arg(QString::fromStdString(style::locomotionKindText(kind))),
            QString::fromUtf8(kind.data(), static_cast<qsizetype>(kind.size())));
  setToolTip(tr("Which of the style's clips the network aims at: its walk, run or turning walk.\n"
                "Read from the clip: a run where a fifth of the frames have no foot down, a turning walk where "
                "it turns steadily.\nChoose one when the reading is wrong for your clip (a shuffling run read "
                "as a walk)."));
  connect(this, &QComboBox::currentIndexChanged, this, [this] {
    by_clip_[clip_file_] = currentData().toString();
    emit kindChanged();
  });
}

void AimChoice::showChoiceFor(const QString& clip_file, const std::string& read_kind) {
  clip_file_ = clip_file;
  const QSignalBlocker quiet(this);
  setItemText(0, read_kind.empty() ? tr("Read from the clip")
                                   : tr("Read from the clip: %1").arg(QString::fromStdString(style::locomotionKindText(read_kind))));
  setCurrentIndex(std::max(0, findData(by_clip_.value(clip_file))));
}

std::string AimChoice::kind() const { return currentData().toString().toStdString(); }

QString AimChoice::statusSentence(const std::string& aimed) const {
  if (aimed.empty()) return {};
  const QString text = QString::fromStdString(style::locomotionKindText(aimed));
  return kind().empty() ? tr(" Aimed at the style's %1 (read from the clip).").arg(text)
                        : tr(" Aimed at the style's %1 (chosen under Aim at).").arg(text);
}

}  // namespace motionstyle
