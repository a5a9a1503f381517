// NetworkPanel: layout, the networks list (load, save, remove, details) and the training form's
// values. The tabs' widgets are built in network_panel_tabs.cpp; the jobs (training, the optimisation
// method, the live preview) are in network_panel_jobs.cpp.
#include "network_panel.h"

#include <QDateTime>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
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
#include <QTreeWidget>
#include <QVBoxLayout>

#include <algorithm>

#include <exception>

#include "common/errors.h"
#include "common/resource_paths.h"
#include "adapt_tab.h"
#include "loss_curve_widget.h"
#include "network_panel_internal.h"
#include "error_text.h"
#include "job_runner.h"

namespace motionstyle {
namespace {

using namespace network_panel_detail;

const char* const kLossNetworkKey = "networks/lossNetwork";
const char* const kNetworkFolderKey = "networks/lastFolder";
const char* const kClipFolderKey = "networks/lastClipFolder";

// <resources>/models/autoencoder.net when installed (resource_paths.h), else empty.
QString shippedLossNetworkFile() {
  const auto resources = resourceDirectory();
  const auto file = resources ? shippedNetworkFile(*resources, kShippedAutoencoderName) : std::nullopt;
  return file ? QString::fromStdString(file->string()) : QString();
}

}  // namespace

NetworkPanel::NetworkPanel(ClipRoles roles, QWidget* parent, bool persist_settings)
    : QWidget(parent), roles_(std::move(roles)), persist_settings_(persist_settings) {
  setObjectName(QStringLiteral("NetworkPanel"));
  runner_ = new JobRunner(this);
  connect(runner_, &JobRunner::failed, this, &NetworkPanel::report);
  connect(runner_, &JobRunner::finished, this, &NetworkPanel::onJobDone);
  confirmer_ = [this](const QString& title, const QString& text, QMessageBox::StandardButtons buttons) {
    return QMessageBox::question(this, title, text, buttons);
  };

  tabs_ = new QTabWidget(this);
  tabs_->addTab(createNetworksTab(), tr("Networks"));
  // The training form is tall: it scrolls rather than squeezing its fields on a small screen.
  train_tab_ = new TrainTab(roles_, this);
  train_tab_->setFolders([this] { return lastClipFolder(); }, [this] { return lastFolder(); });
  connect(train_tab_, &TrainTab::errorOccurred, this, &NetworkPanel::report);
  connect(train_tab_, &TrainTab::clipFolderChosen, this, &NetworkPanel::rememberClipFolder);
  connect(train_tab_, &TrainTab::lossNetworkChanged, this, [this](const QString& file) {
    if (persist_settings_ && !file.isEmpty()) QSettings().setValue(kLossNetworkKey, file);
  });
  auto* train_scroll = new QScrollArea(this);
  train_scroll->setWidget(train_tab_);
  train_scroll->setWidgetResizable(true);
  train_scroll->setFrameShape(QFrame::NoFrame);
  tabs_->addTab(train_scroll, tr("Train"));
  optimise_tab_ = new OptimiseTab(this);
  connect(optimise_tab_, &OptimiseTab::optimiseRequested, this, &NetworkPanel::startTransfer);
  connect(optimise_tab_, &OptimiseTab::cancelRequested, this, &NetworkPanel::cancelJob);
  tabs_->addTab(optimise_tab_, tr("Optimise"));
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
  // Train, Retrain, Cancel and Resume stay in view under the (scrolling) form, next to the progress
  // they start.
  train_button_ = new QPushButton(tr("&Train"), this);
  train_button_->setObjectName(QStringLiteral("TrainButton"));
  train_button_->setToolTip(tr("Train a new network on the training set"));
  retrain_button_ = new QPushButton(tr("&Retrain"), this);
  retrain_button_->setObjectName(QStringLiteral("RetrainButton"));
  retrain_button_->setToolTip(tr("Warm start from the selected network with these weights"));
  cancel_button_ = new QPushButton(tr("Cancel"), this);
  cancel_button_->setObjectName(QStringLiteral("CancelButton"));
  cancel_button_->setToolTip(tr("Stop; the last completed epoch is kept"));
  resume_button_ = new QPushButton(tr("Res&ume"), this);
  resume_button_->setObjectName(QStringLiteral("ResumeButton"));
  resume_button_->setToolTip(tr("Continue the cancelled training from its last completed epoch"));
  connect(train_button_, &QPushButton::clicked, this, [this] { startTraining(false); });
  connect(retrain_button_, &QPushButton::clicked, this, [this] { startTraining(true); });
  connect(cancel_button_, &QPushButton::clicked, this, &NetworkPanel::cancelJob);
  connect(resume_button_, &QPushButton::clicked, this, [this] { resumeTraining(); });
  auto* run_buttons = new QHBoxLayout;
  run_buttons->addWidget(train_button_);
  run_buttons->addWidget(retrain_button_);
  run_buttons->addWidget(cancel_button_);
  run_buttons->addWidget(resume_button_);
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
  train_tab_->setLossNetworkFile(loss_file);
  updateButtons();
}

NetworkPanel::~NetworkPanel() {
  // MainWindow is half destroyed by now: nothing may reach it through a signal (the list's clean-up could
  // otherwise announce a "current network change").
  blockSignals(true);
  network_list_->blockSignals(true);
  delete runner_;  // cancels the job and waits for its thread before the panel's members go
  runner_ = nullptr;
}

void NetworkPanel::setConfirmer(Confirmer confirmer) { confirmer_ = std::move(confirmer); }

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
  } catch (...) {
    // An autoencoder file is not a style network, but it is what the Train tab needs as the loss network.
    const std::exception_ptr failure = std::current_exception();
    bool is_autoencoder = false;
    try {
      is_autoencoder = nn::networkFileKind(path) == nn::NetworkKind::Autoencoder;
    } catch (const std::exception&) {  // not a network file at all: the first failure says so
    }
    if (is_autoencoder) {
      setLossNetworkFile(absolute);
      status_label_->setText(tr("%1 is a loss network (autoencoder): set as the loss network for training.").arg(absolute));
      return true;
    }
    report(tr("Could not load the network"), errorText(failure, absolute));
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
  } catch (...) {
    report(tr("Could not save the network"), errorText(std::current_exception(), absolute));
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
                                                    networkFileFilter());
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

bool NetworkPanel::renameNetwork(int index, const QString& name) {
  if (index < 0 || index >= networkCount()) return false;
  NetworkEntry& entry = networks_[static_cast<std::size_t>(index)];
  const QString wanted = name.simplified();
  if (wanted == entry.name) return true;
  const auto taken = std::any_of(networks_.begin(), networks_.end(),
                                 [&](const NetworkEntry& other) { return &other != &entry && other.name == wanted; });
  if (wanted.isEmpty() || taken) {
    refreshNetworkList();  // the cell shows the kept name again
    report(tr("Name not changed"), wanted.isEmpty() ? tr("A network needs a name.")
                                                    : tr("Another network is already called \"%1\".").arg(wanted));
    return false;
  }
  const QString old_name = entry.name;
  entry.name = wanted;
  refreshNetworkList();
  emit networkRenamed(old_name, wanted);
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
    item->setFlags(item->flags() | Qt::ItemIsEditable);
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

void NetworkPanel::browseLoad() {
  const QStringList files = QFileDialog::getOpenFileNames(this, tr("Load networks"), lastFolder(), networkFileFilter());
  for (const QString& file : files) loadNetworkFile(file);
}

void NetworkPanel::browseSave() {
  const int index = currentIndex();
  if (index < 0) return;
  const NetworkEntry& entry = networks_[static_cast<std::size_t>(index)];
  const QString suggestion = entry.file.isEmpty() ? QDir(lastFolder()).filePath(entry.name + ".net") : entry.file;
  // The file dialog itself asks before replacing an existing file.
  const QString file = QFileDialog::getSaveFileName(this, tr("Save network"), suggestion, networkFileFilter());
  if (!file.isEmpty()) saveNetwork(index, file, /*overwrite_confirmed=*/true);
}

// ---- Training form ----------------------------------------------------------------------------------

NetworkPanel::TrainingForm NetworkPanel::trainingForm() const { return train_tab_->form(); }
void NetworkPanel::setTrainingForm(const TrainingForm& form) { train_tab_->setForm(form); }
QString NetworkPanel::lossNetworkFile() const { return train_tab_->lossNetworkFile(); }
void NetworkPanel::setLossNetworkFile(const QString& file) { train_tab_->setLossNetworkFile(file); }
QStringList NetworkPanel::trainingFolders() const { return train_tab_->trainingFolders(); }
void NetworkPanel::addTrainingFolder(const QString& folder) { train_tab_->addTrainingFolder(folder); }
void NetworkPanel::addStyleClip(const QString& file, const QString& label) { train_tab_->addStyleClip(file, label); }
int NetworkPanel::styleClipCount() const { return train_tab_->styleClipCount(); }
std::vector<style::StyleSource> NetworkPanel::styleSources() const { return train_tab_->styleSources(); }

void NetworkPanel::browseTrainingFolder() {
  tabs_->setCurrentIndex(1);
  train_tab_->browseTrainingFolder();
}

void NetworkPanel::onClipsChanged() {
  if (adapt_tab_) adapt_tab_->refresh();
  train_tab_->refreshSummary();
  // A preview made from another content clip (or the same clip re-mapped) is stale.
  const LoadedClip* content = roles_.content();
  const std::uint64_t id = content != nullptr ? content->id : 0;
  if (preview_shown_ && id != preview_content_id_) {
    preview_shown_ = false;
    emit previewCleared();
  }
}

bool NetworkPanel::isBusy() const { return running_ != Running::None || (adapt_tab_ && adapt_tab_->isBusy()); }

void NetworkPanel::updateButtons() {
  const bool busy = isBusy();
  const bool has_current = currentIndex() >= 0;
  train_button_->setEnabled(!busy);
  retrain_button_->setEnabled(!busy && has_current);
  cancel_button_->setEnabled(running_ == Running::Training);
  resume_button_->setEnabled(!busy && canResumeTraining());
  optimise_tab_->setRunState(!busy, running_ == Running::Transfer);
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

QString NetworkPanel::lastClipFolder() const {
  const QString folder = persist_settings_ ? QSettings().value(kClipFolderKey).toString() : QString();
  return !folder.isEmpty() && QDir(folder).exists() ? folder : QDir::homePath();
}

void NetworkPanel::rememberClipFolder(const QString& path) {
  if (persist_settings_) QSettings().setValue(kClipFolderKey, path);
}

}  // namespace motionstyle
