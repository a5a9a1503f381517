#include "network_list.h"

#include <QDateTime>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QStyledItemDelegate>
#include <QTreeWidget>
#include <QVBoxLayout>

#include <algorithm>
#include <exception>
#include <filesystem>

#include "common/atomic_file.h"
#include "error_text.h"
#include "item_view_layout.h"
#include "remembered_folder.h"
#include "style/training.h"

namespace motionstyle {
namespace {

enum Column { kName, kStyles, kEpochs, kCreated, kColumnCount };

const QString kUnsavedMark = QStringLiteral(" *");

// The value of metadata property `key` ("created", ...), empty when absent.
QString propertyValue(const nn::NetworkMetadata& metadata, const std::string& key) {
  for (const auto& [name, value] : metadata.properties)
    if (name == key) return QString::fromStdString(value);
  return {};
}

// The network's style clips' names, comma-separated ("-" when none).
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

// Edits one column only (the name), without the " *" that marks an unsaved network.
class NameColumnDelegate : public QStyledItemDelegate {
 public:
  using QStyledItemDelegate::QStyledItemDelegate;
  QWidget* createEditor(QWidget* parent, const QStyleOptionViewItem& option, const QModelIndex& index) const override {
    return index.column() == kName ? QStyledItemDelegate::createEditor(parent, option, index) : nullptr;
  }
  void setEditorData(QWidget* editor, const QModelIndex& index) const override {
    QStyledItemDelegate::setEditorData(editor, index);
    auto* line = qobject_cast<QLineEdit*>(editor);
    if (line && line->text().endsWith(kUnsavedMark)) line->setText(line->text().chopped(kUnsavedMark.size()));
  }
};

}  // namespace

QString NetworkList::fileFilter() { return QStringLiteral("MotionStyle networks (*.net);;All files (*)"); }

NetworkList::NetworkList(bool persist_settings, QWidget* parent) : QWidget(parent), persist_settings_(persist_settings) {
  confirmer_ = [this](const QString& title, const QString& text, QMessageBox::StandardButtons buttons) {
    return QMessageBox::question(this, title, text, buttons);
  };
  auto* load = new QPushButton(tr("&Load..."), this);
  load->setToolTip(tr("Load a style network file (.net); a loss network file becomes the loss network"));
  save_button_ = new QPushButton(tr("&Save As..."), this);
  remove_button_ = new QPushButton(tr("Remove"), this);
  connect(load, &QPushButton::clicked, this, &NetworkList::browseLoad);
  connect(save_button_, &QPushButton::clicked, this, &NetworkList::browseSave);
  connect(remove_button_, &QPushButton::clicked, this, [this] { removeNetwork(currentIndex()); });
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(load);
  buttons->addWidget(save_button_);
  buttons->addWidget(remove_button_);
  buttons->addStretch(1);

  tree_ = new QTreeWidget(this);
  tree_->setObjectName(QStringLiteral("NetworkList"));
  tree_->setColumnCount(kColumnCount);
  tree_->setHeaderLabels({tr("Network"), tr("Style clips"), tr("Epochs"), tr("Created")});
  tree_->setRootIsDecorated(false);
  tree_->setSelectionMode(QAbstractItemView::SingleSelection);
  tree_->header()->setSectionResizeMode(kName, QHeaderView::Stretch);
  connect(tree_, &QTreeWidget::currentItemChanged, this, [this] {
    showDetails();
    updateButtons();
    emit currentNetworkChanged(currentNetwork());
  });
  // Only the name column is edited; " *" marks an unsaved network, it is not part of the name.
  tree_->setEditTriggers(QAbstractItemView::DoubleClicked | QAbstractItemView::EditKeyPressed);
  tree_->setItemDelegate(new NameColumnDelegate(tree_));
  connect(tree_, &QTreeWidget::itemChanged, this, [this](QTreeWidgetItem* item, int column) {
    if (column != kName) return;
    QString name = item->text(kName);
    if (name.endsWith(kUnsavedMark)) name.chop(kUnsavedMark.size());
    renameNetwork(tree_->indexOfTopLevelItem(item), name);
  });
  details_label_ = new QLabel(this);
  details_label_->setWordWrap(true);
  details_label_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  details_label_->setAlignment(Qt::AlignTop | Qt::AlignLeft);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(buttons);
  layout->addWidget(tree_, 1);
  layout->addWidget(details_label_);
  updateButtons();
}

int NetworkList::currentIndex() const { return tree_->indexOfTopLevelItem(tree_->currentItem()); }

void NetworkList::setCurrentIndex(int index) {
  if (index >= 0 && index < networkCount()) tree_->setCurrentItem(tree_->topLevelItem(index));
}

std::shared_ptr<const nn::StyleModel> NetworkList::network(int index) const {
  return index >= 0 && index < networkCount() ? networks_[static_cast<std::size_t>(index)].model : nullptr;
}

std::shared_ptr<const nn::StyleModel> NetworkList::currentNetwork() const { return network(currentIndex()); }

QString NetworkList::networkName(int index) const {
  return index >= 0 && index < networkCount() ? networks_[static_cast<std::size_t>(index)].name : QString();
}

QString NetworkList::currentNetworkName() const { return networkName(currentIndex()); }

QString NetworkList::networkFile(int index) const {
  return index >= 0 && index < networkCount() ? networks_[static_cast<std::size_t>(index)].file : QString();
}

bool NetworkList::isNetworkSaved(int index) const {
  return index >= 0 && index < networkCount() && networks_[static_cast<std::size_t>(index)].saved;
}

bool NetworkList::nameTaken(const QString& name, const Entry* except) const {
  return std::any_of(networks_.begin(), networks_.end(),
                     [&](const Entry& other) { return &other != except && other.name == name; });
}

QString NetworkList::uniqueName(const QString& base, const Entry* except) const {
  QString name = base;
  for (int counter = 2; nameTaken(name, except); ++counter) name = QStringLiteral("%1 (%2)").arg(base).arg(counter);
  return name;
}

void NetworkList::addNetwork(std::shared_ptr<const nn::StyleModel> model, const QString& name,
                             std::shared_ptr<const style::ReconstructionMemory> memory) {
  addEntry({std::move(model), name, QString(), false, std::move(memory)});
}

std::shared_ptr<const style::ReconstructionMemory> NetworkList::networkMemory(int index) const {
  return index >= 0 && index < networkCount() ? networks_[static_cast<std::size_t>(index)].memory : nullptr;
}

void NetworkList::addEntry(Entry entry) {
  // Names tell networks apart everywhere (this list, the Result panel's Style choice, the close prompt).
  entry.name = uniqueName(entry.name, nullptr);
  networks_.push_back(std::move(entry));
  refresh();
  setCurrentIndex(networkCount() - 1);
}

bool NetworkList::loadNetworkFile(const QString& file) {
  const QString absolute = QFileInfo(file).absoluteFilePath();
  for (int i = 0; i < networkCount(); ++i)
    if (networks_[static_cast<std::size_t>(i)].file == absolute) {  // already listed: select it
      setCurrentIndex(i);
      return true;
    }
  const std::filesystem::path path(absolute.toStdString());
  try {
    rememberFolder(QFileInfo(absolute).absolutePath());
    auto model = std::make_shared<const nn::StyleModel>(style::loadCompatibleStyleModel(path));
    // Its memory, when one beside it fits its loss network (an adapted network saved here).
    std::shared_ptr<const style::ReconstructionMemory> memory;
    if (const std::filesystem::path beside = style::memoryFileBeside(path); std::filesystem::is_regular_file(beside)) {
      try {
        auto found = std::make_shared<const style::ReconstructionMemory>(style::loadReconstructionMemory(beside));
        if (found->fits(nn::embeddedLossNetwork(*model))) memory = std::move(found);  // else another network's
      } catch (const std::exception&) {  // damaged: the network loads without it
      }
    }
    addEntry({std::move(model), QFileInfo(absolute).completeBaseName(), absolute, true, std::move(memory)});
    emit statusMessage(tr("Loaded %1").arg(absolute));
    return true;
  } catch (...) {
    // A loss network file is not a style network, but it is what training needs as the loss network.
    const std::exception_ptr failure = std::current_exception();
    bool is_loss_network = false;
    try {
      is_loss_network = nn::networkFileKind(path) == nn::NetworkKind::LossNetwork;
    } catch (const std::exception&) {  // not a network file at all: the first failure says so
    }
    if (is_loss_network) {
      emit lossNetworkFileLoaded(absolute);
      emit statusMessage(tr("%1 is a loss network: set as the loss network for training.").arg(absolute));
      return true;
    }
    report(tr("Could not load the network"), errorText(failure, absolute));
  }
  return false;
}

bool NetworkList::saveNetwork(int index, const QString& file, bool overwrite_confirmed) {
  if (index < 0 || index >= networkCount() || file.isEmpty()) return false;
  Entry& entry = networks_[static_cast<std::size_t>(index)];
  const QString absolute = QFileInfo(file).absoluteFilePath();
  if (!overwrite_confirmed && QFileInfo::exists(absolute) &&
      ask(tr("Replace the file?"), tr("%1 already exists. Replace it?").arg(absolute), QMessageBox::Yes | QMessageBox::No) !=
          QMessageBox::Yes)
    return false;
  try {
    const std::filesystem::path path(absolute.toStdString());
    AtomicFileBatch batch;  // the network and its memory: both or neither
    batch.stage(path, nn::serialiseStyleModel(*entry.model));
    if (entry.memory) batch.stage(style::memoryFileBeside(path), style::serialiseReconstructionMemoryCompactly(*entry.memory));
    batch.commit();
  } catch (...) {
    report(tr("Could not save the network"), errorText(std::current_exception(), absolute));
    return false;
  }
  // The list shows the file's name from now on (unique: "name (2)" when another network has it).
  const QString old_name = entry.name;
  entry.name = uniqueName(QFileInfo(absolute).completeBaseName(), &entry);
  entry.file = absolute;
  entry.saved = true;
  rememberFolder(QFileInfo(absolute).absolutePath());
  refresh();
  showDetails();
  if (entry.name != old_name) emit networkRenamed(old_name, entry.name);
  emit statusMessage(tr("Saved %1").arg(absolute));
  return true;
}

bool NetworkList::confirmDropUnsaved(int index) {
  if (isNetworkSaved(index)) return true;
  const QString name = networkName(index);
  const QMessageBox::StandardButton answer =
      ask(tr("Unsaved network"), tr("The trained network \"%1\" has not been saved. Save it?").arg(name),
          QMessageBox::Save | QMessageBox::Discard | QMessageBox::Cancel);
  if (answer == QMessageBox::Discard) return true;
  if (answer != QMessageBox::Save) return false;
  const QString file = QFileDialog::getSaveFileName(this, tr("Save network"), QDir(networksFolder()).filePath(name + ".net"),
                                                    fileFilter());
  return !file.isEmpty() && saveNetwork(index, file, /*overwrite_confirmed=*/true);
}

bool NetworkList::removeNetwork(int index) {
  if (index < 0 || index >= networkCount() || !confirmDropUnsaved(index)) return false;
  const QString name = networkName(index);
  networks_.erase(networks_.begin() + index);
  // The list is rebuilt with its signals blocked, so announce the new selection (or none) here.
  refresh();
  {
    const QSignalBlocker blocker(tree_);
    setCurrentIndex(std::min(index, networkCount() - 1));
  }
  showDetails();
  updateButtons();
  emit currentNetworkChanged(currentNetwork());
  emit networkRemoved(name);
  return true;
}

bool NetworkList::renameNetwork(int index, const QString& name) {
  if (index < 0 || index >= networkCount()) return false;
  Entry& entry = networks_[static_cast<std::size_t>(index)];
  const QString wanted = name.simplified();
  if (wanted == entry.name) return true;
  if (wanted.isEmpty() || nameTaken(wanted, &entry)) {
    refresh();  // the cell shows the kept name again
    report(tr("Name not changed"), wanted.isEmpty() ? tr("A network needs a name.")
                                                    : tr("Another network is already called \"%1\".").arg(wanted));
    return false;
  }
  const QString old_name = entry.name;
  entry.name = wanted;
  refresh();
  showDetails();
  emit networkRenamed(old_name, wanted);
  return true;
}

bool NetworkList::prepareToClose() {
  // One question for all unsaved networks: save them all into one folder, or discard them all.
  std::vector<int> unsaved;
  QStringList names;
  for (int i = 0; i < networkCount(); ++i)
    if (!isNetworkSaved(i)) {
      unsaved.push_back(i);
      names << networkName(i);
    }
  if (unsaved.empty()) return true;
  const QMessageBox::StandardButton answer =
      ask(tr("Unsaved networks"),
          tr("%n trained network(s) not saved: %1.\n\nSave all of them into one folder, or discard all?", nullptr,
             static_cast<int>(unsaved.size())).arg(names.join(QStringLiteral(", "))),
          QMessageBox::SaveAll | QMessageBox::Discard | QMessageBox::Cancel);
  if (answer == QMessageBox::Discard) return true;
  if (answer != QMessageBox::SaveAll) return false;
  const QString folder = folder_chooser_ ? folder_chooser_(networksFolder())
                                         : QFileDialog::getExistingDirectory(this, tr("Save the networks in"), networksFolder());
  if (folder.isEmpty()) return false;
  for (int i : unsaved) {  // never over an existing file: "name (2).net" when "name.net" is taken
    const QString name = networkName(i);
    QString file = QDir(folder).filePath(name + QStringLiteral(".net"));
    const auto taken = [](const QString& path) {  // the network's file, or its memory's beside it
      return QFileInfo::exists(path) ||
             std::filesystem::exists(style::memoryFileBeside(std::filesystem::path(path.toStdString())));
    };
    for (int counter = 2; taken(file); ++counter)
      file = QDir(folder).filePath(QStringLiteral("%1 (%2).net").arg(name).arg(counter));
    if (!saveNetwork(i, file, /*overwrite_confirmed=*/false)) return false;
  }
  return true;
}

void NetworkList::refresh() {
  const QSignalBlocker blocker(tree_);
  const int current = currentIndex();
  tree_->clear();
  for (const Entry& entry : networks_) {
    const nn::NetworkMetadata& metadata = entry.model->metadata;
    auto* item = new QTreeWidgetItem(tree_);
    item->setText(kName, entry.saved ? entry.name : entry.name + kUnsavedMark);
    item->setFlags(item->flags() | Qt::ItemIsEditable);
    item->setToolTip(kName, entry.saved ? entry.file : tr("Not saved"));
    item->setText(kStyles, styleClipNames(metadata));
    item->setText(kEpochs, QString::number(metadata.training.epochs));
    item->setTextAlignment(kEpochs, Qt::AlignRight | Qt::AlignVCenter);
    QString created = propertyValue(metadata, "created");
    const QDateTime stamp = QDateTime::fromString(created, Qt::ISODate);
    if (stamp.isValid()) created = stamp.toString(QStringLiteral("yyyy-MM-dd hh:mm"));
    if (created.isEmpty() && !entry.file.isEmpty())
      created = QFileInfo(entry.file).lastModified().toString(QStringLiteral("yyyy-MM-dd hh:mm"));
    item->setText(kCreated, created);
  }
  if (current >= 0 && current < networkCount()) tree_->setCurrentItem(tree_->topLevelItem(current));
  layOutItemsNow(*tree_);
  updateButtons();
}

void NetworkList::showDetails() {
  const int index = currentIndex();
  if (index < 0) {
    details_label_->clear();
    return;
  }
  const Entry& entry = networks_[static_cast<std::size_t>(index)];
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
          .arg(entry.model->transformation.shape().hidden) +
      (entry.memory ? tr("<br>Keeps when adapted again (saved beside it): %1")
                          .arg(QString::fromStdString(entry.memory->description).toHtmlEscaped())
                    : QString()));
}

void NetworkList::updateButtons() {
  const bool has_current = currentIndex() >= 0;
  save_button_->setEnabled(has_current);
  remove_button_->setEnabled(has_current);
}

void NetworkList::browseLoad() {
  const QStringList files = QFileDialog::getOpenFileNames(this, tr("Load networks"), networksFolder(), fileFilter());
  for (const QString& file : files) loadNetworkFile(file);
}

void NetworkList::browseSave() {
  const int index = currentIndex();
  if (index < 0) return;
  const Entry& entry = networks_[static_cast<std::size_t>(index)];
  const QString suggestion = entry.file.isEmpty() ? QDir(networksFolder()).filePath(entry.name + ".net") : entry.file;
  // The file dialog itself asks before replacing an existing file.
  const QString file = QFileDialog::getSaveFileName(this, tr("Save network"), suggestion, fileFilter());
  if (!file.isEmpty()) saveNetwork(index, file, /*overwrite_confirmed=*/true);
}

void NetworkList::report(const QString& title, const QString& message) { emit errorOccurred(title, message); }

QMessageBox::StandardButton NetworkList::ask(const QString& title, const QString& text, QMessageBox::StandardButtons buttons) {
  return confirmer_ ? confirmer_(title, text, buttons) : QMessageBox::Cancel;
}

QString NetworkList::networksFolder() const { return RememberedFolder(kNetworkFolderKey, persist_settings_).folder(); }

void NetworkList::rememberFolder(const QString& path) { RememberedFolder(kNetworkFolderKey, persist_settings_).remember(path); }

}  // namespace motionstyle
