// NetworkPanel: layout, the networks list (load, save, remove, details) and the training form. The jobs
// (training, the optimisation method, the live preview) are in network_panel_jobs.cpp.
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
#include <QThread>
#include <QTreeWidget>
#include <QVBoxLayout>

#include <algorithm>

#include <exception>

#include "common/errors.h"
#include "common/resource_paths.h"
#include "adapt_tab.h"
#include "loss_curve_widget.h"
#include "main_window.h"
#include "training_worker.h"

namespace motionstyle {
namespace {

enum NetworkColumn { kNetName, kNetStyles, kNetEpochs, kNetCreated, kNetColumnCount };
enum StyleColumn { kStyleLabel, kStyleFile };

const char* const kLossNetworkKey = "networks/lossNetwork";
const char* const kNetworkFolderKey = "networks/lastFolder";
const QString kNetworkFilter = QStringLiteral("MotionStyle networks (*.net);;All files (*)");

// <resources>/models/autoencoder.net when installed (resource_paths.h), else empty.
QString shippedLossNetworkFile() {
  const auto resources = resourceDirectory();
  const auto file = resources ? shippedNetworkFile(*resources, kShippedAutoencoderName) : std::nullopt;
  return file ? QString::fromStdString(file->string()) : QString();
}

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

QString weightsText(const nn::LossWeights& w) {
  return QStringLiteral("content %1, style %2, foot %3, bone %4, trajectory %5")
      .arg(w.content, 0, 'g', 4).arg(w.style, 0, 'g', 4).arg(w.foot, 0, 'g', 4).arg(w.bone, 0, 'g', 4)
      .arg(w.trajectory, 0, 'g', 4);
}

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

NetworkPanel::NetworkPanel(MainWindow* window, bool persist_settings)
    : QWidget(window), window_(window), persist_settings_(persist_settings) {
  setObjectName(QStringLiteral("NetworkPanel"));
  registerWorkerMetaTypes();
  confirmer_ = [this](const QString& title, const QString& text, QMessageBox::StandardButtons buttons) {
    return QMessageBox::question(this, title, text, buttons);
  };

  tabs_ = new QTabWidget(this);
  tabs_->addTab(createNetworksTab(), tr("Networks"));
  // The training form is tall: it scrolls rather than squeezing its fields on a small screen.
  auto* train_scroll = new QScrollArea(this);
  train_scroll->setWidget(createTrainTab());
  train_scroll->setWidgetResizable(true);
  train_scroll->setFrameShape(QFrame::NoFrame);
  tabs_->addTab(train_scroll, tr("Train"));
  tabs_->addTab(createOptimiseTab(), tr("Optimise"));
  tabs_->addTab(createAdaptTab(), tr("Adapt"));

  progress_bar_ = new QProgressBar(this);
  progress_bar_->setObjectName(QStringLiteral("TrainingProgress"));
  progress_bar_->setRange(0, 1000);
  progress_bar_->setValue(0);
  progress_bar_->setTextVisible(true);
  progress_bar_->setFormat(tr("Idle"));
  status_label_ = new QLabel(tr("Load a network, or train one on the Train tab."), this);
  status_label_->setWordWrap(true);
  status_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  // Room for three lines whatever the text: a status that wraps to a second line must not grow the
  // area and push the splitter, which moved the Cancel button away from the pointer.
  status_label_->setAlignment(Qt::AlignLeft | Qt::AlignTop);
  status_label_->setMinimumHeight(3 * status_label_->fontMetrics().lineSpacing());
  loss_curve_ = new LossCurveWidget(this);

  auto* bottom = new QWidget(this);
  auto* bottom_layout = new QVBoxLayout(bottom);
  bottom_layout->setContentsMargins(0, 0, 0, 0);
  // Train, Retrain and Cancel stay in view under the (scrolling) form, next to the progress they start.
  auto* run_buttons = new QHBoxLayout;
  run_buttons->addWidget(train_button_);
  run_buttons->addWidget(retrain_button_);
  run_buttons->addWidget(cancel_button_);
  bottom_layout->addLayout(run_buttons);
  bottom_layout->addWidget(progress_bar_);
  bottom_layout->addWidget(status_label_);
  bottom_layout->addWidget(loss_curve_, 1);
  auto* splitter = new QSplitter(Qt::Vertical, this);
  splitter->addWidget(tabs_);
  splitter->addWidget(bottom);
  splitter->setStretchFactor(0, 3);
  splitter->setStretchFactor(1, 2);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  layout->addWidget(splitter);

  // The loss network: the one last used if it is still there, else the shipped one, so that a first
  // training needs nothing but clips.
  QString loss_file = persist_settings_ ? QSettings().value(kLossNetworkKey).toString() : QString();
  if (loss_file.isEmpty() || !QFileInfo::exists(loss_file)) loss_file = shippedLossNetworkFile();
  loss_network_edit_->setText(loss_file);
  connect(window_, &MainWindow::clipsChanged, this, &NetworkPanel::onClipsChanged);
  refreshTrainingSummary();
  updateButtons();
}

NetworkPanel::~NetworkPanel() {
  // MainWindow is half destroyed by now: nothing may reach it through a signal (the list's clean-up could
  // otherwise announce a "current network change").
  blockSignals(true);
  network_list_->blockSignals(true);
  shutdownJob();
}

void NetworkPanel::setConfirmer(Confirmer confirmer) { confirmer_ = std::move(confirmer); }

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
    const int index = window_->styleClip();
    if (index < 0) report(tr("No style clip"), tr("Give a clip the Style role first (right-click it in the Clips list)."));
    else addStyleClip(window_->clip(index).path);
  });
  connect(add_file, &QPushButton::clicked, this, [this] {
    const QString file = QFileDialog::getOpenFileName(this, tr("Style clip"), lastFolder(), tr("BVH motion (*.bvh *.BVH)"));
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
    const QString file = QFileDialog::getOpenFileName(this, tr("Loss network"), lastFolder(), kNetworkFilter);
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

// ---- Networks ---------------------------------------------------------------------------------------

int NetworkPanel::currentIndex() const { return network_list_->indexOfTopLevelItem(network_list_->currentItem()); }

void NetworkPanel::setCurrentIndex(int index) {
  if (index >= 0 && index < networkCount()) network_list_->setCurrentItem(network_list_->topLevelItem(index));
}

std::shared_ptr<const nn::StyleModel> NetworkPanel::network(int index) const {
  if (index < 0 || index >= networkCount()) return nullptr;
  return networks_[static_cast<std::size_t>(index)].model;
}

std::shared_ptr<const nn::StyleModel> NetworkPanel::currentNetwork() const { return network(currentIndex()); }

QString NetworkPanel::currentNetworkName() const {
  const int index = currentIndex();
  return index >= 0 ? networks_[static_cast<std::size_t>(index)].name : QString();
}

QString NetworkPanel::networkFile(int index) const {
  return index >= 0 && index < networkCount() ? networks_[static_cast<std::size_t>(index)].file : QString();
}

bool NetworkPanel::isNetworkSaved(int index) const {
  return index >= 0 && index < networkCount() && networks_[static_cast<std::size_t>(index)].saved;
}

void NetworkPanel::addNetwork(NetworkEntry entry) {
  // Names tell networks apart everywhere (this list, the Result panel's Style choice, the close
  // prompt): a taken name gets " (2)", " (3)", ...
  const auto taken = [this](const QString& name) {
    return std::any_of(networks_.begin(), networks_.end(), [&](const NetworkEntry& other) { return other.name == name; });
  };
  const QString base = entry.name;
  for (int counter = 2; taken(entry.name); ++counter) entry.name = QStringLiteral("%1 (%2)").arg(base).arg(counter);
  networks_.push_back(std::move(entry));
  refreshNetworkList();
  setCurrentIndex(networkCount() - 1);
}

bool NetworkPanel::loadNetworkFile(const QString& file) {
  const QString absolute = QFileInfo(file).absoluteFilePath();
  for (int i = 0; i < networkCount(); ++i) {
    if (networks_[static_cast<std::size_t>(i)].file == absolute) {  // already listed: select it
      setCurrentIndex(i);
      return true;
    }
  }
  const std::filesystem::path path(absolute.toStdString());
  try {
    rememberFolder(QFileInfo(absolute).absolutePath());
    NetworkEntry entry;
    entry.model = std::make_shared<const nn::StyleModel>(style::loadCompatibleStyleModel(path));
    entry.name = QFileInfo(absolute).completeBaseName();
    entry.file = absolute;
    entry.saved = true;
    addNetwork(std::move(entry));
    status_label_->setText(tr("Loaded %1").arg(absolute));
    return true;
  } catch (const InputError& error) {
    // An autoencoder file is not a style network, but it is what the Train tab needs as the loss network.
    bool is_autoencoder = false;
    try {
      is_autoencoder = nn::networkFileKind(path) == nn::NetworkKind::Autoencoder;
    } catch (const std::exception&) {
    }
    if (is_autoencoder) {
      setLossNetworkFile(absolute);
      status_label_->setText(tr("%1 is a loss network (autoencoder): set as the loss network for training.").arg(absolute));
      return true;
    }
    report(tr("Could not load the network"), QString::fromStdString(error.what()));
  } catch (const std::bad_alloc&) {
    report(tr("Could not load the network"), tr("%1: not enough memory").arg(absolute));
  } catch (const std::exception& error) {
    report(tr("Could not load the network"), tr("%1: internal error: %2").arg(absolute, QString::fromStdString(error.what())));
  }
  return false;
}

bool NetworkPanel::saveNetwork(int index, const QString& file, bool overwrite_confirmed) {
  if (index < 0 || index >= networkCount() || file.isEmpty()) return false;
  NetworkEntry& entry = networks_[static_cast<std::size_t>(index)];
  const QString absolute = QFileInfo(file).absoluteFilePath();
  if (!overwrite_confirmed && QFileInfo::exists(absolute) &&
      ask(tr("Replace the file?"), tr("%1 already exists. Replace it?").arg(absolute), QMessageBox::Yes | QMessageBox::No) !=
          QMessageBox::Yes)
    return false;
  try {
    nn::saveStyleModel(*entry.model, std::filesystem::path(absolute.toStdString()));  // atomic
  } catch (const std::exception& error) {
    report(tr("Could not save the network"), QString::fromStdString(error.what()));
    return false;
  }
  entry.file = absolute;
  entry.name = QFileInfo(absolute).completeBaseName();
  entry.saved = true;
  rememberFolder(QFileInfo(absolute).absolutePath());
  refreshNetworkList();
  showNetworkDetails();
  status_label_->setText(tr("Saved %1").arg(absolute));
  return true;
}

bool NetworkPanel::confirmDropUnsaved(int index, bool allow_cancel) {
  if (isNetworkSaved(index)) return true;
  const NetworkEntry& entry = networks_[static_cast<std::size_t>(index)];
  const QMessageBox::StandardButtons buttons =
      QMessageBox::Save | QMessageBox::Discard | (allow_cancel ? QMessageBox::Cancel : QMessageBox::NoButton);
  const QMessageBox::StandardButton answer =
      ask(tr("Unsaved network"), tr("The trained network \"%1\" has not been saved. Save it?").arg(entry.name), buttons);
  if (answer == QMessageBox::Discard) return true;
  if (answer != QMessageBox::Save) return false;
  const QString file = QFileDialog::getSaveFileName(this, tr("Save network"), QDir(lastFolder()).filePath(entry.name + ".net"),
                                                    kNetworkFilter);
  return !file.isEmpty() && saveNetwork(index, file, /*overwrite_confirmed=*/true);
}

bool NetworkPanel::removeNetwork(int index) {
  if (index < 0 || index >= networkCount() || !confirmDropUnsaved(index, true)) return false;
  networks_.erase(networks_.begin() + index);
  // The list is rebuilt with its signals blocked, so announce the new selection (or none) here.
  refreshNetworkList();
  {
    const QSignalBlocker blocker(network_list_);
    setCurrentIndex(std::min(index, networkCount() - 1));
  }
  showNetworkDetails();
  updateButtons();
  emit currentNetworkChanged(currentNetwork());
  return true;
}

void NetworkPanel::refreshNetworkList() {
  const QSignalBlocker blocker(network_list_);
  const int current = currentIndex();
  network_list_->clear();
  for (const NetworkEntry& entry : networks_) {
    const nn::NetworkMetadata& metadata = entry.model->metadata;
    auto* item = new QTreeWidgetItem(network_list_);
    item->setText(kNetName, entry.saved ? entry.name : entry.name + QStringLiteral(" *"));
    item->setToolTip(kNetName, entry.saved ? entry.file : tr("Not saved"));
    item->setText(kNetStyles, styleClipNames(metadata));
    item->setText(kNetEpochs, QString::number(metadata.training.epochs));
    item->setTextAlignment(kNetEpochs, Qt::AlignRight | Qt::AlignVCenter);
    QString created = propertyValue(metadata, "created");
    const QDateTime stamp = QDateTime::fromString(created, Qt::ISODate);
    if (stamp.isValid()) created = stamp.toString(QStringLiteral("yyyy-MM-dd hh:mm"));
    if (created.isEmpty() && !entry.file.isEmpty())
      created = QFileInfo(entry.file).lastModified().toString(QStringLiteral("yyyy-MM-dd hh:mm"));
    item->setText(kNetCreated, created);
  }
  if (current >= 0 && current < networkCount()) network_list_->setCurrentItem(network_list_->topLevelItem(current));
  updateButtons();
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

void NetworkPanel::browseLoad() {
  const QStringList files = QFileDialog::getOpenFileNames(this, tr("Load networks"), lastFolder(), kNetworkFilter);
  for (const QString& file : files) loadNetworkFile(file);
}

void NetworkPanel::browseSave() {
  const int index = currentIndex();
  if (index < 0) return;
  const NetworkEntry& entry = networks_[static_cast<std::size_t>(index)];
  const QString suggestion = entry.file.isEmpty() ? QDir(lastFolder()).filePath(entry.name + ".net") : entry.file;
  // The file dialog itself asks before replacing an existing file.
  const QString file = QFileDialog::getSaveFileName(this, tr("Save network"), suggestion, kNetworkFilter);
  if (!file.isEmpty()) saveNetwork(index, file, /*overwrite_confirmed=*/true);
}

// ---- Training form ----------------------------------------------------------------------------------

NetworkPanel::TrainingForm NetworkPanel::trainingForm() const {
  TrainingForm form;
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

void NetworkPanel::setTrainingForm(const TrainingForm& form) {
  content_weight_->setValue(form.weights.content);
  style_weight_->setValue(form.weights.style);
  foot_weight_->setValue(form.weights.foot);
  bone_weight_->setValue(form.weights.bone);
  trajectory_weight_->setValue(form.weights.trajectory);
  epochs_spin_->setValue(form.epochs);
  learning_rate_spin_->setValue(form.learning_rate);
  hidden_spin_->setValue(form.hidden_units);
}

QString NetworkPanel::lossNetworkFile() const { return loss_network_edit_->text().trimmed(); }

void NetworkPanel::setLossNetworkFile(const QString& file) {
  loss_network_edit_->setText(file);
  if (persist_settings_ && !file.isEmpty()) QSettings().setValue(kLossNetworkKey, file);
}

QStringList NetworkPanel::trainingFolders() const {
  QStringList folders;
  for (int i = 0; i < folder_list_->count(); ++i) folders << folder_list_->item(i)->text();
  return folders;
}

void NetworkPanel::addTrainingFolder(const QString& folder) {
  const QString absolute = QDir(folder).absolutePath();
  if (!QDir(absolute).exists()) {
    report(tr("Could not add the folder"), tr("%1 does not exist.").arg(absolute));
    return;
  }
  if (!trainingFolders().contains(absolute)) folder_list_->addItem(absolute);
  refreshTrainingSummary();
}

void NetworkPanel::browseTrainingFolder() {
  const QString folder = QFileDialog::getExistingDirectory(this, tr("Add a folder to the training set"), lastFolder());
  if (folder.isEmpty()) return;
  rememberFolder(folder);
  addTrainingFolder(folder);
  tabs_->setCurrentIndex(1);
}

void NetworkPanel::addStyleClip(const QString& file, const QString& label) {
  auto* item = new QTreeWidgetItem(style_list_);
  item->setText(kStyleLabel, label);
  item->setText(kStyleFile, QFileInfo(file).absoluteFilePath());
  item->setToolTip(kStyleFile, QFileInfo(file).absoluteFilePath());
  item->setFlags(item->flags() | Qt::ItemIsEditable);
  refreshTrainingSummary();
}

int NetworkPanel::styleClipCount() const { return style_list_->topLevelItemCount(); }

std::vector<style::StyleSource> NetworkPanel::styleSources() const {
  std::vector<style::StyleSource> sources;
  for (int i = 0; i < style_list_->topLevelItemCount(); ++i) {
    const QTreeWidgetItem* item = style_list_->topLevelItem(i);
    style::StyleSource source;
    const QString label = item->text(kStyleLabel).trimmed();
    if (!label.isEmpty()) source.label = label.toStdString();
    source.file = item->text(kStyleFile).toStdString();
    sources.push_back(std::move(source));
  }
  if (sources.empty() && window_->styleClip() >= 0)
    sources.push_back({std::nullopt, window_->clip(window_->styleClip()).path.toStdString()});
  return sources;
}

void NetworkPanel::refreshTrainingSummary() {
  const int clips = static_cast<int>(window_->trainingClipPaths().size());
  const int folders = folder_list_->count();
  if (clips == 0 && folders == 0)
    database_label_->setText(tr("No training set yet: right-click clips and choose \"In the Training Set\", or add a "
                                "folder of BVH files."));
  else
    database_label_->setText(tr("%n clip(s) with the training-database role", nullptr, clips) +
                             tr(", %n folder(s)", nullptr, folders));
  if (style_list_->topLevelItemCount() > 0)
    style_hint_label_->setText(tr("Each content clip is paired with the style clip of its label (from the file name, "
                                  "or the label given here); an unlabelled clip is the default."));
  else if (window_->styleClip() >= 0)
    style_hint_label_->setText(tr("None listed: the Style clip %1 is used for every content clip.")
                                   .arg(window_->clip(window_->styleClip()).name));
  else
    style_hint_label_->setText(tr("None listed and no clip has the Style role yet."));
}

void NetworkPanel::onClipsChanged() {
  refreshTrainingSummary();
  // A preview made from another content clip (or the same clip re-mapped) is stale.
  const int content = window_->contentClip();
  const std::uint64_t id = content >= 0 ? window_->clip(content).id : 0;
  if (preview_shown_ && id != preview_content_id_) {
    preview_shown_ = false;
    emit previewCleared();
  }
}

bool NetworkPanel::isBusy() const { return thread_ != nullptr || (adapt_tab_ && adapt_tab_->isBusy()); }

void NetworkPanel::updateButtons() {
  const bool busy = isBusy();
  const bool has_current = currentIndex() >= 0;
  train_button_->setEnabled(!busy);
  retrain_button_->setEnabled(!busy && has_current);
  cancel_button_->setEnabled(busy && training_worker_ != nullptr);
  optimise_button_->setEnabled(!busy);
  optimise_cancel_button_->setEnabled(busy && transfer_worker_ != nullptr);
  save_button_->setEnabled(has_current);
  remove_button_->setEnabled(has_current);
}

QString NetworkPanel::statusText() const { return status_label_->text(); }

void NetworkPanel::report(const QString& title, const QString& message) {
  status_label_->setText(title);
  emit errorOccurred(title, message);
}

QMessageBox::StandardButton NetworkPanel::ask(const QString& title, const QString& text, QMessageBox::StandardButtons buttons) {
  return confirmer_ ? confirmer_(title, text, buttons) : QMessageBox::Cancel;
}

QString NetworkPanel::lastFolder() const {
  const QString folder = persist_settings_ ? QSettings().value(kNetworkFolderKey).toString() : QString();
  return !folder.isEmpty() && QDir(folder).exists() ? folder : QDir::homePath();
}

void NetworkPanel::rememberFolder(const QString& path) {
  if (persist_settings_) QSettings().setValue(kNetworkFolderKey, path);
}

}  // namespace motionstyle
