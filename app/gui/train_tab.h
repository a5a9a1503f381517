#pragma once
// TrainTab: the Style networks panel's training form, and nothing else: the training set (the clips
// with the "training set" role, read through ClipRoles, plus folders), the style clips per content label
// (style_pairing.h), the loss network file, the loss weights (eq. 10, defaults from nn::LossWeights),
// epochs, learning rate and hidden units. It holds editable data only; NetworkPanel reads it when a run
// starts (and validates it then). Errors go out as errorOccurred(); the folders it should open dialogs
// in come from the owner (setFolders), the folders the user picked go back by clipFolderChosen().

#include <QString>
#include <QStringList>
#include <QWidget>

#include <functional>
#include <vector>

#include "clip_roles.h"
#include "nn/transformation_objective.h"
#include "style/style_pairing.h"
#include "style/training.h"

class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QSpinBox;
class QTreeWidget;

namespace motionstyle {

class TrainTab : public QWidget {
  Q_OBJECT

 public:
  struct Form {
    nn::LossWeights weights;  // unweighted terms are multiplied by these (eq. 10)
    int epochs = style::kQuickStyleEpochs;
    double learning_rate = 1e-3;  // Adam
    int hidden_units = 128;       // of the transformation network (new networks only)
  };

  explicit TrainTab(ClipRoles roles, QWidget* parent = nullptr);

  // Where the file dialogs open: clips and training folders, network files.
  void setFolders(std::function<QString()> clip_folder, std::function<QString()> network_folder);

  Form form() const;
  void setForm(const Form& form);
  QString lossNetworkFile() const;
  void setLossNetworkFile(const QString& file);
  QStringList trainingFolders() const;
  void addTrainingFolder(const QString& folder);
  void browseTrainingFolder();  // a folder dialog, then addTrainingFolder
  // Style clips per content label: an empty label pairs by the clip's file name / as the default.
  void addStyleClip(const QString& file, const QString& label = QString());
  int styleClipCount() const;
  // With no style clip listed, the clip with the Style role (none: empty).
  std::vector<style::StyleSource> styleSources() const;

 public slots:
  void refreshSummary();  // the clips or their roles changed

 signals:
  void errorOccurred(const QString& title, const QString& message);
  void clipFolderChosen(const QString& folder);
  void lossNetworkChanged(const QString& file);

 private:
  ClipRoles roles_;
  std::function<QString()> clip_folder_;
  std::function<QString()> network_folder_;

  QLabel* database_label_ = nullptr;
  QListWidget* folder_list_ = nullptr;
  QTreeWidget* style_list_ = nullptr;
  QLabel* style_hint_label_ = nullptr;
  QLineEdit* loss_network_edit_ = nullptr;
  QDoubleSpinBox* content_weight_ = nullptr;
  QDoubleSpinBox* style_weight_ = nullptr;
  QDoubleSpinBox* foot_weight_ = nullptr;
  QDoubleSpinBox* bone_weight_ = nullptr;
  QDoubleSpinBox* trajectory_weight_ = nullptr;
  QSpinBox* epochs_spin_ = nullptr;
  QDoubleSpinBox* learning_rate_spin_ = nullptr;
  QSpinBox* hidden_spin_ = nullptr;
};

}  // namespace motionstyle
