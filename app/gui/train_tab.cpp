#include "train_tab.h"

#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHeaderView>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPushButton>
#include <QSpinBox>
#include <QTreeWidget>
#include <QVBoxLayout>

#include <tuple>

#include "network_list.h"
#include "nn/transformation_network.h"

namespace motionstyle {
namespace {

// The style-clip table's columns.
enum StyleColumn { kStyleLabel, kStyleFile };

QDoubleSpinBox* weightSpin(QWidget* parent, const QString& name, double value, const QString& tip) {
  auto* spin = new QDoubleSpinBox(parent);
  spin->setObjectName(name);
  spin->setRange(0.0, 1e6);
  spin->setDecimals(4);
  spin->setValue(value);
  spin->setToolTip(tip);
  return spin;
}

}  // namespace

TrainTab::TrainTab(ClipRoles roles, QWidget* parent)
    : QWidget(parent), roles_(std::move(roles)), clip_folder_(&QDir::homePath), network_folder_(&QDir::homePath) {
  const nn::LossWeights defaults;

  auto* data_box = new QGroupBox(tr("Content (training set)"), this);
  database_label_ = new QLabel(data_box);
  database_label_->setObjectName(QStringLiteral("TrainingSetSummary"));
  database_label_->setWordWrap(true);
  folder_list_ = new QListWidget(data_box);
  folder_list_->setObjectName(QStringLiteral("TrainingFolders"));
  folder_list_->setMaximumHeight(60);
  auto* add_folder = new QPushButton(tr("Add Folder..."), data_box);
  auto* remove_folder = new QPushButton(tr("Remove Folder"), data_box);
  connect(add_folder, &QPushButton::clicked, this, &TrainTab::browseTrainingFolder);
  connect(remove_folder, &QPushButton::clicked, this, [this] {
    delete folder_list_->currentItem();
    refreshSummary();
  });
  auto* data_buttons = new QHBoxLayout;
  data_buttons->addWidget(add_folder);
  data_buttons->addWidget(remove_folder);
  data_buttons->addStretch(1);
  auto* data_layout = new QVBoxLayout(data_box);
  data_layout->addWidget(database_label_);
  data_layout->addWidget(folder_list_);
  data_layout->addLayout(data_buttons);

  auto* style_box = new QGroupBox(tr("Style clips (one per kind of content)"), this);
  style_list_ = new QTreeWidget(style_box);
  style_list_->setObjectName(QStringLiteral("StyleClips"));
  style_list_->setHeaderLabels({tr("For content labelled"), tr("Style clip")});
  style_list_->setRootIsDecorated(false);
  style_list_->setMaximumHeight(80);
  // The label column as wide as its title ("For content labe" was cut off at the dock's width).
  style_list_->header()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  style_list_->setToolTip(tr("Double-click a label to edit it. An empty label pairs by file name and is the "
                             "default for labels nothing else matches. With no clip listed, the clip with the "
                             "Style role is used."));
  auto* add_current = new QPushButton(tr("Add Style Clip"), style_box);
  add_current->setToolTip(tr("Add the clip that has the Style role"));
  auto* add_file = new QPushButton(tr("Add File..."), style_box);
  auto* remove_style = new QPushButton(tr("Remove"), style_box);
  connect(add_current, &QPushButton::clicked, this, [this] {
    const LoadedClip* style = roles_.style();
    if (style == nullptr) emit errorOccurred(tr("No style clip"), tr("Give a clip the Style role first (right-click it in the Clips list)."));
    else addStyleClip(style->path);
  });
  connect(add_file, &QPushButton::clicked, this, [this] {
    const QString file = QFileDialog::getOpenFileName(this, tr("Style clip"), clip_folder_(), tr("BVH motion (*.bvh *.BVH)"));
    if (!file.isEmpty()) addStyleClip(file);
  });
  connect(remove_style, &QPushButton::clicked, this, [this] {
    delete style_list_->currentItem();
    refreshSummary();
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

  loss_network_edit_ = new QLineEdit(this);
  loss_network_edit_->setObjectName(QStringLiteral("LossNetwork"));
  loss_network_edit_->setPlaceholderText(tr("loss network .net file"));
  auto* browse_loss = new QPushButton(tr("..."), this);
  connect(browse_loss, &QPushButton::clicked, this, [this] {
    const QString file = QFileDialog::getOpenFileName(this, tr("Loss network"), network_folder_(), NetworkList::fileFilter());
    if (!file.isEmpty()) setLossNetworkFile(file);
  });
  auto* loss_row = new QHBoxLayout;
  loss_row->addWidget(loss_network_edit_, 1);
  loss_row->addWidget(browse_loss);

  content_weight_ = weightSpin(this, QStringLiteral("ContentWeight"), defaults.content, tr("Content term (eq. 4)"));
  style_weight_ = weightSpin(this, QStringLiteral("StyleWeight"), defaults.style, tr("Style term (eq. 5)"));
  foot_weight_ = weightSpin(this, QStringLiteral("FootWeight"), defaults.foot, tr("Foot contact term (eq. 7)"));
  bone_weight_ = weightSpin(this, QStringLiteral("BoneWeight"), defaults.bone, tr("Bone length term (eq. 8)"));
  trajectory_weight_ = weightSpin(this, QStringLiteral("TrajectoryWeight"), defaults.trajectory, tr("Trajectory term (eq. 9)"));
  epochs_spin_ = new QSpinBox(this);
  epochs_spin_->setObjectName(QStringLiteral("Epochs"));
  epochs_spin_->setRange(1, 100000);
  epochs_spin_->setValue(style::kQuickStyleEpochs);
  epochs_spin_->setToolTip(tr("Passes over the training set. %1 (Quick): a usable style in seconds; %2 (Full): the "
                              "shipped networks' training").arg(style::kQuickStyleEpochs).arg(style::kFullStyleEpochs));
  auto* epochs_row = new QHBoxLayout;
  epochs_row->addWidget(epochs_spin_, 1);
  for (const auto& [text, name, epochs] : {std::tuple{tr("Quick"), "QuickEpochs", style::kQuickStyleEpochs},
                                           std::tuple{tr("Full"), "FullEpochs", style::kFullStyleEpochs}}) {
    auto* preset = new QPushButton(text, this);
    preset->setObjectName(QString::fromLatin1(name));
    preset->setToolTip(tr("%1 epochs").arg(epochs));
    connect(preset, &QPushButton::clicked, epochs_spin_, [spin = epochs_spin_, count = epochs] { spin->setValue(count); });
    epochs_row->addWidget(preset);
  }
  learning_rate_spin_ = new QDoubleSpinBox(this);
  learning_rate_spin_->setObjectName(QStringLiteral("LearningRate"));
  learning_rate_spin_->setDecimals(6);
  learning_rate_spin_->setRange(1e-6, 1.0);
  learning_rate_spin_->setSingleStep(1e-4);
  learning_rate_spin_->setValue(1e-3);
  learning_rate_spin_->setToolTip(tr("Adam's learning rate at the start; it decays along a cosine to 1% of this "
                                     "by the last epoch"));
  hidden_spin_ = new QSpinBox(this);
  hidden_spin_->setObjectName(QStringLiteral("HiddenUnits"));
  hidden_spin_->setRange(1, 4096);
  hidden_spin_->setValue(nn::TransformationShape{}.hidden);
  hidden_spin_->setToolTip(tr("Hidden units of a new network (Retrain keeps the selected network's)"));

  auto* form = new QFormLayout;
  form->addRow(tr("Loss network"), loss_row);
  form->addRow(tr("Content weight"), content_weight_);
  form->addRow(tr("Style weight"), style_weight_);
  form->addRow(tr("Foot weight"), foot_weight_);
  form->addRow(tr("Bone weight"), bone_weight_);
  form->addRow(tr("Trajectory weight"), trajectory_weight_);
  form->addRow(tr("Epochs"), epochs_row);
  form->addRow(tr("Learning rate (start)"), learning_rate_spin_);
  form->addRow(tr("Hidden units"), hidden_spin_);

  auto* layout = new QVBoxLayout(this);
  layout->addWidget(data_box);
  layout->addWidget(style_box);
  layout->addLayout(form);
  layout->addStretch(1);
  refreshSummary();
}

void TrainTab::setFolders(std::function<QString()> clip_folder, std::function<QString()> network_folder) {
  clip_folder_ = std::move(clip_folder);
  network_folder_ = std::move(network_folder);
}

TrainTab::Form TrainTab::form() const {
  Form form;
  form.weights.content = content_weight_->value();
  form.weights.style = style_weight_->value();
  form.weights.foot = foot_weight_->value();
  form.weights.bone = bone_weight_->value();
  form.weights.trajectory = trajectory_weight_->value();
  form.epochs = epochs_spin_->value();
  form.learning_rate = learning_rate_spin_->value();
  form.hidden_units = hidden_spin_->value();
  return form;
}

void TrainTab::setForm(const Form& form) {
  content_weight_->setValue(form.weights.content);
  style_weight_->setValue(form.weights.style);
  foot_weight_->setValue(form.weights.foot);
  bone_weight_->setValue(form.weights.bone);
  trajectory_weight_->setValue(form.weights.trajectory);
  epochs_spin_->setValue(form.epochs);
  learning_rate_spin_->setValue(form.learning_rate);
  hidden_spin_->setValue(form.hidden_units);
}

QString TrainTab::lossNetworkFile() const { return loss_network_edit_->text().trimmed(); }

void TrainTab::setLossNetworkFile(const QString& file) {
  loss_network_edit_->setText(file);
  emit lossNetworkChanged(file);
}

QStringList TrainTab::trainingFolders() const {
  QStringList folders;
  for (int i = 0; i < folder_list_->count(); ++i) folders << folder_list_->item(i)->text();
  return folders;
}

void TrainTab::addTrainingFolder(const QString& folder) {
  const QString absolute = QDir(folder).absolutePath();
  if (!QDir(absolute).exists()) {
    emit errorOccurred(tr("Could not add the folder"), tr("%1 does not exist.").arg(absolute));
    return;
  }
  if (!trainingFolders().contains(absolute)) folder_list_->addItem(absolute);
  refreshSummary();
}

void TrainTab::browseTrainingFolder() {
  const QString folder = QFileDialog::getExistingDirectory(this, tr("Add a folder to the training set"), clip_folder_());
  if (folder.isEmpty()) return;
  emit clipFolderChosen(folder);
  addTrainingFolder(folder);
}

void TrainTab::addStyleClip(const QString& file, const QString& label) {
  auto* item = new QTreeWidgetItem(style_list_);
  item->setText(kStyleLabel, label);
  item->setText(kStyleFile, QFileInfo(file).absoluteFilePath());
  item->setToolTip(kStyleFile, QFileInfo(file).absoluteFilePath());
  item->setFlags(item->flags() | Qt::ItemIsEditable);
  refreshSummary();
}

int TrainTab::styleClipCount() const { return style_list_->topLevelItemCount(); }

std::vector<style::StyleSource> TrainTab::styleSources() const {
  std::vector<style::StyleSource> sources;
  for (int i = 0; i < style_list_->topLevelItemCount(); ++i) {
    const QTreeWidgetItem* item = style_list_->topLevelItem(i);
    style::StyleSource source;
    const QString label = item->text(kStyleLabel).trimmed();
    if (!label.isEmpty()) source.label = label.toStdString();
    source.file = item->text(kStyleFile).toStdString();
    sources.push_back(std::move(source));
  }
  if (const LoadedClip* style = roles_.style(); sources.empty() && style != nullptr)
    sources.push_back({std::nullopt, style->path.toStdString()});
  return sources;
}

void TrainTab::refreshSummary() {
  const int clips = static_cast<int>(roles_.training_paths().size());
  const int folders = folder_list_->count();
  const int open = static_cast<int>(defaultTrainingPaths(roles_).size());
  if (clips == 0 && folders == 0 && open > 0)
    database_label_->setText(tr("None chosen: the %n open clip(s) other than the Style clip are used. To choose, "
                                "right-click clips and choose \"In the Training Set\", or add a folder of BVH files.",
                                nullptr, open));
  else if (clips == 0 && folders == 0)
    database_label_->setText(tr("No training set yet: right-click clips and choose \"In the Training Set\", or add a "
                                "folder of BVH files."));
  else
    database_label_->setText(tr("%n clip(s) with the training-database role", nullptr, clips) +
                             tr(", %n folder(s)", nullptr, folders));
  if (style_list_->topLevelItemCount() > 0)
    style_hint_label_->setText(tr("Each content clip is paired with the style clip of its label (from the file name, "
                                  "or the label given here); an unlabelled clip is the default."));
  else if (const LoadedClip* style = roles_.style())
    style_hint_label_->setText(tr("None listed: the Style clip %1 is used for every content clip.").arg(style->name));
  else
    style_hint_label_->setText(tr("None listed and no clip has the Style role yet."));
}

}  // namespace motionstyle
