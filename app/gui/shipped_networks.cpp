#include "shipped_networks.h"

#include <QComboBox>
#include <QDateTime>
#include <QFileInfo>
#include <QStandardItemModel>
#include <exception>
#include <map>

#include "common/resource_paths.h"
#include "common/text_safety.h"
#include "nn/network_file.h"

namespace motionstyle {
namespace {

// Why `file` cannot be used as a style network (empty: it can). The full check reads every stored
// value, so its answer is kept per file and reused while the file's size and modification time stay
// the same: the Adapt tab relists on every refresh. GUI thread only.
QString styleNetworkProblem(const std::filesystem::path& file, const QString& shown_path) {
  struct Checked {
    qint64 size = -1;
    QDateTime modified;
    QString problem;
  };
  static std::map<QString, Checked> checked;
  const QFileInfo info(shown_path);
  Checked& entry = checked[shown_path];
  if (entry.size == info.size() && entry.modified == info.lastModified() && info.exists()) return entry.problem;
  QString problem;
  try {
    if (nn::networkFileInfo(file).kind != nn::NetworkKind::Style)
      problem = QObject::tr("%1: a loss network, not a style network").arg(shown_path);
  } catch (const std::exception& error) {  // InputError, or bad_alloc on a huge claimed size
    problem = QString::fromStdString(safeText(error.what()));
  }
  entry = {info.size(), info.lastModified(), problem};
  return problem;
}

}  // namespace

QString shippedLossNetworkFile() {
  const auto resources = resourceDirectory();
  const auto file = resources ? shippedNetworkFile(*resources, kShippedLossNetworkName) : std::nullopt;
  return file ? QString::fromStdString(file->string()) : QString();
}

std::vector<ShippedStyleNetwork> shippedStyleNetworks() {
  std::vector<ShippedStyleNetwork> networks;
  const std::optional<std::filesystem::path> resources = resourceDirectory();
  if (!resources) return networks;
  for (const std::filesystem::path& file : shippedNetworkFiles(*resources)) {
    if (file.stem() == kShippedLossNetworkName) continue;  // the loss network is not a style
    ShippedStyleNetwork network;
    network.name = QString::fromStdString(safeText(file.stem().string()));
    network.file = QFileInfo(QString::fromStdString(file.string())).absoluteFilePath();
    network.problem = styleNetworkProblem(file, network.file);
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
