// NetworkPanel's tabs: the widgets of the Networks, Train and Optimise tabs, their connections, and the
// selected network's details.
#include "network_panel.h"

#include <QDateTime>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSettings>
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
          .arg(entry.model->transformation.shape().hidden));
  if (!isBusy()) {
    QStringList terms;
    for (const std::string& term : metadata.loss_history.terms) terms << QString::fromStdString(term);
    loss_curve_->setHistory(terms, metadata.loss_history.epochs);
  }
}

}  // namespace motionstyle
