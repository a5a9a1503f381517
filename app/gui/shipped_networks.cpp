#include "shipped_networks.h"

#include <QComboBox>
#include <QFileInfo>
#include <QStandardItemModel>
#include <exception>

#include "common/resource_paths.h"
#include "common/text_safety.h"
#include "nn/network_file.h"

namespace motionstyle {

std::vector<ShippedStyleNetwork> shippedStyleNetworks() {
  std::vector<ShippedStyleNetwork> networks;
  const std::optional<std::filesystem::path> resources = resourceDirectory();
  if (!resources) return networks;
  for (const std::filesystem::path& file : shippedNetworkFiles(*resources)) {
    if (file.stem() == kShippedAutoencoderName) continue;  // the loss network is not a style
    ShippedStyleNetwork network;
    network.name = QString::fromStdString(safeText(file.stem().string()));
    network.file = QFileInfo(QString::fromStdString(file.string())).absoluteFilePath();
    try {
      if (nn::networkFileInfo(file).kind != nn::NetworkKind::Style)
        network.problem = QObject::tr("%1: a loss network, not a style network").arg(network.file);
    } catch (const std::exception& error) {  // InputError, or bad_alloc on a huge claimed size
      network.problem = QString::fromStdString(safeText(error.what()));
    }
    networks.push_back(network);
  }
  return networks;
}

void addShippedStyleNetworks(QComboBox* choice) {
  auto* model = qobject_cast<QStandardItemModel*>(choice->model());
  for (const ShippedStyleNetwork& network : shippedStyleNetworks()) {
    const QString label = network.name.left(1).toUpper() + network.name.mid(1);
    if (network.problem.isEmpty()) {
      choice->addItem(label, network.file);
      continue;
    }
    choice->addItem(QObject::tr("%1 (cannot be read)").arg(label), network.file);
    const int index = choice->count() - 1;
    choice->setItemData(index, network.problem, Qt::ToolTipRole);
    if (model) model->item(index)->setEnabled(false);
  }
}

}  // namespace motionstyle
