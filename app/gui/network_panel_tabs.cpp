// NetworkPanel's tabs: the widgets of the Networks, Train and Optimise tabs, their connections, and the
// selected network's details.
#include "network_panel.h"

#include <QDateTime>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSettings>
#include <QSpinBox>
#include <QSplitter>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QStyledItemDelegate>
#include <QTreeWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <exception>

#include "common/errors.h"
#include "common/resource_paths.h"
#include "adapt_tab.h"
#include "loss_curve_widget.h"
#include "network_panel_internal.h"
#include "style/optimization_transfer.h"

namespace motionstyle {
namespace network_panel_detail {

QString propertyValue(const nn::NetworkMetadata& metadata, const std::string& key) {
  for (const auto& [name, value] : metadata.properties)
    if (name == key) return QString::fromStdString(value);
  return {};
}

QString styleClipNames(const nn::NetworkMetadata& metadata) {
  QStringList names;
  for (const nn::StyleClipRef& clip : metadata.style_clips) names << QString::fromStdString(clip.name);
  return names.isEmpty() ? QStringLiteral("-") : names.join(QStringLiteral(", "));
}

}  // namespace network_panel_detail

namespace {

// Edits one column only (the name), without the " *" that marks an unsaved network.
class EditableColumnDelegate : public QStyledItemDelegate {
 public:
  EditableColumnDelegate(int column, QObject* parent) : QStyledItemDelegate(parent), column_(column) {}
  QWidget* createEditor(QWidget* parent, const QStyleOptionViewItem& option, const QModelIndex& index) const override {
    return index.column() == column_ ? QStyledItemDelegate::createEditor(parent, option, index) : nullptr;
  }
  void setEditorData(QWidget* editor, const QModelIndex& index) const override {
    QStyledItemDelegate::setEditorData(editor, index);
    auto* line = qobject_cast<QLineEdit*>(editor);
    if (line && line->text().endsWith(QStringLiteral(" *"))) line->setText(line->text().chopped(2));
  }

 private:
  int column_;
};

using namespace network_panel_detail;

QDoubleSpinBox* weightSpin(QWidget* parent, const QString& name, double value, const QString& tip) {
  auto* spin = new QDoubleSpinBox(parent);
  spin->setObjectName(name);
  spin->setRange(0.0, 1e6);
  spin->setDecimals(4);
  spin->setValue(value);
  spin->setToolTip(tip);
  return spin;
}

QString weightsText(const nn::LossWeights& w) {
  return QStringLiteral("content %1, style %2, foot %3, bone %4, trajectory %5")
      .arg(w.content, 0, 'g', 4).arg(w.style, 0, 'g', 4).arg(w.foot, 0, 'g', 4).arg(w.bone, 0, 'g', 4)
      .arg(w.trajectory, 0, 'g', 4);
}


}  // namespace

QWidget* NetworkPanel::createNetworksTab() {
  auto* tab = new QWidget(this);
  auto* load = new QPushButton(tr("&Load..."), tab);
  load->setToolTip(tr("Load a style network file (.net); an autoencoder file becomes the loss network"));
  save_button_ = new QPushButton(tr("&Save As..."), tab);
  remove_button_ = new QPushButton(tr("Remove"), tab);
  connect(load, &QPushButton::clicked, this, &NetworkPanel::browseLoad);
  connect(save_button_, &QPushButton::clicked, this, &NetworkPanel::browseSave);
  connect(remove_button_, &QPushButton::clicked, this, [this] { removeNetwork(currentIndex()); });
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(load);
  buttons->addWidget(save_button_);
  buttons->addWidget(remove_button_);
  buttons->addStretch(1);

  network_list_ = new QTreeWidget(tab);
  network_list_->setObjectName(QStringLiteral("NetworkList"));
  network_list_->setColumnCount(kNetColumnCount);
  network_list_->setHeaderLabels({tr("Network"), tr("Style clips"), tr("Epochs"), tr("Created")});
  network_list_->setRootIsDecorated(false);
  network_list_->setSelectionMode(QAbstractItemView::SingleSelection);
  network_list_->header()->setSectionResizeMode(kNetName, QHeaderView::Stretch);
  connect(network_list_, &QTreeWidget::currentItemChanged, this, [this] {
    showNetworkDetails();
    updateButtons();
    emit currentNetworkChanged(currentNetwork());
  });
  // Only the name column is edited (F2 or a double click); " *" marks an unsaved network, not its name.
  network_list_->setEditTriggers(QAbstractItemView::DoubleClicked | QAbstractItemView::EditKeyPressed);
  connect(network_list_, &QTreeWidget::itemChanged, this, [this](QTreeWidgetItem* item, int column) {
    if (column != kNetName) return;
    QString name = item->text(kNetName);
    if (name.endsWith(QStringLiteral(" *"))) name.chop(2);
    renameNetwork(network_list_->indexOfTopLevelItem(item), name);
  });
  network_list_->setItemDelegate(new EditableColumnDelegate(kNetName, network_list_));
  details_label_ = new QLabel(tab);
  details_label_->setWordWrap(true);
  details_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  details_label_->setAlignment(Qt::AlignTop | Qt::AlignLeft);

  auto* layout = new QVBoxLayout(tab);
  layout->addLayout(buttons);
  layout->addWidget(network_list_, 1);
  layout->addWidget(details_label_);
  return tab;
}

QWidget* NetworkPanel::createTrainTab() {
  auto* tab = new QWidget(this);
  const nn::LossWeights defaults;

  auto* data_box = new QGroupBox(tr("Content (training set)"), tab);
  database_label_ = new QLabel(data_box);
  database_label_->setWordWrap(true);
  folder_list_ = new QListWidget(data_box);
  folder_list_->setObjectName(QStringLiteral("TrainingFolders"));
  folder_list_->setMaximumHeight(60);
  auto* add_folder = new QPushButton(tr("Add Folder..."), data_box);
  auto* remove_folder = new QPushButton(tr("Remove Folder"), data_box);
  connect(add_folder, &QPushButton::clicked, this, &NetworkPanel::browseTrainingFolder);
  connect(remove_folder, &QPushButton::clicked, this, [this] {
    delete folder_list_->currentItem();
    refreshTrainingSummary();
  });
  auto* data_buttons = new QHBoxLayout;
  data_buttons->addWidget(add_folder);
  data_buttons->addWidget(remove_folder);
  data_buttons->addStretch(1);
  auto* data_layout = new QVBoxLayout(data_box);
  data_layout->addWidget(database_label_);
  data_layout->addWidget(folder_list_);
  data_layout->addLayout(data_buttons);

  auto* style_box = new QGroupBox(tr("Style clips (one per kind of content)"), tab);
  style_list_ = new QTreeWidget(style_box);
  style_list_->setObjectName(QStringLiteral("StyleClips"));
  style_list_->setHeaderLabels({tr("For content labelled"), tr("Style clip")});
  style_list_->setRootIsDecorated(false);
  style_list_->setMaximumHeight(80);
  style_list_->setToolTip(tr("Double-click a label to edit it. An empty label pairs by file name and is the "
                             "default for labels nothing else matches. With no clip listed, the clip with the "
                             "Style role is used."));
  auto* add_current = new QPushButton(tr("Add Style Clip"), style_box);
  add_current->setToolTip(tr("Add the clip that has the Style role"));
  auto* add_file = new QPushButton(tr("Add File..."), style_box);
  auto* remove_style = new QPushButton(tr("Remove"), style_box);
  connect(add_current, &QPushButton::clicked, this, [this] {
    const LoadedClip* style = roles_.style();
    if (style == nullptr) report(tr("No style clip"), tr("Give a clip the Style role first (right-click it in the Clips list)."));
    else addStyleClip(style->path);
  });
  connect(add_file, &QPushButton::clicked, this, [this] {
    const QString file = QFileDialog::getOpenFileName(this, tr("Style clip"), lastClipFolder(), tr("BVH motion (*.bvh *.BVH)"));
    if (!file.isEmpty()) addStyleClip(file);
  });
  connect(remove_style, &QPushButton::clicked, this, [this] {
    delete style_list_->currentItem();
    refreshTrainingSummary();
  });
  auto* style_buttons = new QHBoxLayout;
  style_buttons->addWidget(add_current);
  style_buttons->addWidget(add_file);
  style_buttons->addWidget(remove_style);
  style_buttons->addStretch(1);
  style_hint_label_ = new QLabel(style_box);
  style_hint_label_->setWordWrap(true);
  auto* style_layout = new QVBoxLayout(style_box);
  style_layout->addWidget(style_list_);
  style_layout->addWidget(style_hint_label_);
  style_layout->addLayout(style_buttons);

  loss_network_edit_ = new QLineEdit(tab);
  loss_network_edit_->setObjectName(QStringLiteral("LossNetwork"));
  loss_network_edit_->setPlaceholderText(tr("autoencoder .net file"));
  auto* browse_loss = new QPushButton(tr("..."), tab);
  connect(browse_loss, &QPushButton::clicked, this, [this] {
    const QString file = QFileDialog::getOpenFileName(this, tr("Loss network"), lastFolder(), networkFileFilter());
    if (!file.isEmpty()) setLossNetworkFile(file);
  });
  auto* loss_row = new QHBoxLayout;
  loss_row->addWidget(loss_network_edit_, 1);
  loss_row->addWidget(browse_loss);

  content_weight_ = weightSpin(tab, QStringLiteral("ContentWeight"), defaults.content, tr("Content term (eq. 4)"));
  style_weight_ = weightSpin(tab, QStringLiteral("StyleWeight"), defaults.style, tr("Style term (eq. 5)"));
  foot_weight_ = weightSpin(tab, QStringLiteral("FootWeight"), defaults.foot, tr("Foot contact term (eq. 7)"));
  bone_weight_ = weightSpin(tab, QStringLiteral("BoneWeight"), defaults.bone, tr("Bone length term (eq. 8)"));
  trajectory_weight_ = weightSpin(tab, QStringLiteral("TrajectoryWeight"), defaults.trajectory, tr("Trajectory term (eq. 9)"));
  epochs_spin_ = new QSpinBox(tab);
  epochs_spin_->setObjectName(QStringLiteral("Epochs"));
  epochs_spin_->setRange(1, 100000);
  epochs_spin_->setValue(100);
  learning_rate_spin_ = new QDoubleSpinBox(tab);
  learning_rate_spin_->setObjectName(QStringLiteral("LearningRate"));
  learning_rate_spin_->setDecimals(6);
  learning_rate_spin_->setRange(1e-6, 1.0);
  learning_rate_spin_->setSingleStep(1e-4);
  learning_rate_spin_->setValue(1e-3);
  learning_rate_spin_->setToolTip(tr("Adam's learning rate at the start; it decays along a cosine to 1% of this "
                                     "by the last epoch"));
  hidden_spin_ = new QSpinBox(tab);
  hidden_spin_->setObjectName(QStringLiteral("HiddenUnits"));
  hidden_spin_->setRange(1, 4096);
  hidden_spin_->setValue(nn::TransformerShape{}.hidden);
  hidden_spin_->setToolTip(tr("Hidden units of a new network (Retrain keeps the selected network's)"));

  auto* form = new QFormLayout;
  form->addRow(tr("Loss network"), loss_row);
  form->addRow(tr("Content weight"), content_weight_);
  form->addRow(tr("Style weight"), style_weight_);
  form->addRow(tr("Foot weight"), foot_weight_);
  form->addRow(tr("Bone weight"), bone_weight_);
  form->addRow(tr("Trajectory weight"), trajectory_weight_);
  form->addRow(tr("Epochs"), epochs_spin_);
  form->addRow(tr("Learning rate (start)"), learning_rate_spin_);
  form->addRow(tr("Hidden units"), hidden_spin_);

  train_button_ = new QPushButton(tr("&Train"), tab);
  train_button_->setObjectName(QStringLiteral("TrainButton"));
  train_button_->setToolTip(tr("Train a new network on the training set"));
  retrain_button_ = new QPushButton(tr("&Retrain"), tab);
  retrain_button_->setObjectName(QStringLiteral("RetrainButton"));
  retrain_button_->setToolTip(tr("Warm start from the selected network with these weights"));
  cancel_button_ = new QPushButton(tr("Cancel"), tab);
  cancel_button_->setObjectName(QStringLiteral("CancelButton"));
  cancel_button_->setToolTip(tr("Stop; the last completed epoch is kept"));
  connect(train_button_, &QPushButton::clicked, this, [this] { startTraining(false); });
  connect(retrain_button_, &QPushButton::clicked, this, [this] { startTraining(true); });
  connect(cancel_button_, &QPushButton::clicked, this, &NetworkPanel::cancelJob);
  resume_button_ = new QPushButton(tr("Res&ume"), tab);
  resume_button_->setObjectName(QStringLiteral("ResumeButton"));
  resume_button_->setToolTip(tr("Continue the cancelled training from its last completed epoch"));
  connect(resume_button_, &QPushButton::clicked, this, [this] { resumeTraining(); });
  auto* layout = new QVBoxLayout(tab);
  layout->addWidget(data_box);
  layout->addWidget(style_box);
  layout->addLayout(form);
  layout->addStretch(1);
  return tab;
}

QWidget* NetworkPanel::createOptimiseTab() {
  auto* tab = new QWidget(this);
  auto* text = new QLabel(tr("The optimisation method (Holden et al. 2016): no trained network; the content clip's "
                             "hidden units are optimised towards the style clip's Gram matrix with the loss "
                             "network above, then the foot, bone and trajectory constraints. Slower than a "
                             "trained network, for one style clip."),
                          tab);
  text->setWordWrap(true);
  iterations_spin_ = new QSpinBox(tab);
  iterations_spin_->setObjectName(QStringLiteral("Iterations"));
  iterations_spin_->setRange(1, 100000);
  iterations_spin_->setValue(style::OptimizationOptions{}.iterations);
  transfer_style_weight_ = new QDoubleSpinBox(tab);
  transfer_style_weight_->setObjectName(QStringLiteral("OptimiseStyleWeight"));
  transfer_style_weight_->setRange(0.0, 1e4);
  transfer_style_weight_->setDecimals(2);
  transfer_style_weight_->setValue(style::OptimizationOptions{}.style_weight);
  transfer_style_weight_->setToolTip(tr("How hard the style clip's Gram matrix pulls against the content "
                                        "(content weight 1; both are renormalised to sum 1)"));
  optimise_button_ = new QPushButton(tr("&Optimise"), tab);
  optimise_button_->setObjectName(QStringLiteral("OptimiseButton"));
  optimise_cancel_button_ = new QPushButton(tr("Cancel"), tab);
  connect(optimise_button_, &QPushButton::clicked, this, [this] { startTransfer(iterations_spin_->value()); });
  connect(optimise_cancel_button_, &QPushButton::clicked, this, &NetworkPanel::cancelJob);
  auto* form = new QFormLayout;
  form->addRow(tr("Iterations"), iterations_spin_);
  form->addRow(tr("Style weight"), transfer_style_weight_);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(optimise_button_);
  buttons->addWidget(optimise_cancel_button_);
  buttons->addStretch(1);
  auto* layout = new QVBoxLayout(tab);
  layout->addWidget(text);
  layout->addLayout(form);
  layout->addLayout(buttons);
  layout->addStretch(1);
  return tab;
}

void NetworkPanel::showNetworkDetails() {
  const int index = currentIndex();
  if (index < 0) {
    details_label_->clear();
    if (!isBusy()) loss_curve_->clear();
    return;
  }
  const NetworkEntry& entry = networks_[static_cast<std::size_t>(index)];
  const nn::NetworkMetadata& metadata = entry.model->metadata;
  const nn::TrainingConfig& training = metadata.training;
  QStringList pairing;
  for (const auto& [key, value] : metadata.properties)
    if (key.rfind("style_for_", 0) == 0)
      pairing << QStringLiteral("%1 -> %2").arg(QString::fromStdString(key.substr(10)), QString::fromStdString(value));
  details_label_->setText(
      tr("<b>%1</b>%2<br>Style clips: %3%4<br>Loss weights: %5<br>%6 epochs, learning rate %7, batch %8 x %9 frames, "
         "%10 hidden units")
          .arg(entry.name.toHtmlEscaped(), entry.saved ? QString() : tr(" <i>(not saved)</i>"),
               styleClipNames(metadata).toHtmlEscaped(),
               pairing.isEmpty() ? QString() : QStringLiteral(" (%1)").arg(pairing.join(QStringLiteral(", ")).toHtmlEscaped()),
               weightsText(training.weights))
          .arg(training.epochs)
          .arg(training.learning_rate, 0, 'g', 4)
          .arg(training.batch_windows)
          .arg(training.window_frames)
          .arg(entry.model->transformer.shape().hidden));
  if (!isBusy()) {
    QStringList terms;
    for (const std::string& term : metadata.loss_history.terms) terms << QString::fromStdString(term);
    loss_curve_->setHistory(terms, metadata.loss_history.epochs);
  }
}

}  // namespace motionstyle
