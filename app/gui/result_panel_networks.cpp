// The Result panel's style networks: the chooser, files read (or taken prepared from the cache),
// networks from the Networks panel (result_panel.h).
#include <QComboBox>
#include <QFileDialog>
#include <QFileInfo>

#include <exception>
#include <utility>

#include "error_text.h"
#include "result_panel.h"
#include "shipped_networks.h"
#include "style/training.h"

namespace motionstyle {

void ResultPanel::setStyleNetwork(std::shared_ptr<const nn::StyleModel> model, const QString& name) {
  useNetwork(std::move(model), name, QString());
}

void ResultPanel::useNetwork(std::shared_ptr<const nn::StyleModel> model, const QString& name, const QString& file) {
  std::shared_ptr<const style::Stylizer> stylizer;
  if (model) {
    try {
      stylizer = std::make_shared<const style::Stylizer>(*model, (file.isEmpty() ? name : file).toStdString());
    } catch (...) {
      report(tr("Could not use the style network"), errorText(std::current_exception(), file));
    }
  }
  useStylizer(std::move(stylizer), name, file);
}

void ResultPanel::useStylizer(std::shared_ptr<const style::Stylizer> stylizer, const QString& name, const QString& file,
                              qint64 chosen_ms) {
  const auto previous = stylizer_;
  const bool came_from_network = resultComesFromNetwork();
  stylizer_ = std::move(stylizer);
  network_name_ = stylizer_ ? (name.isEmpty() ? tr("style network") : name) : QString();
  network_file_ = stylizer_ ? file : QString();
  if (stylizer_ && file.isEmpty()) unfiled_networks_[network_name_] = stylizer_;
  given_stylized_.reset();
  if (hasNetwork()) showNetworkInChoice(network_name_, file);  // a listed file keeps its entry's label
  refreshControls();
  refreshFamiliarity();
  // One network for another draws the same figures (rebuilding them cost a style switch 18-28 ms).
  if (resultComesFromNetwork() != came_from_network) emit sourceChanged();
  if (stylizer_ != previous) {
    if (hasNetwork()) emit networkChosen(network_name_);
    inputsChanged(tr("the style changed"), chosen_ms);
  }
}

void ResultPanel::renameNetwork(const QString& old_name, const QString& new_name) {
  for (int i = 0; i < network_choice_->count(); ++i)
    if (network_choice_->itemText(i) == old_name && network_choice_->itemData(i).toString().isEmpty())
      network_choice_->setItemText(i, new_name);
  for (QString* name : {&network_name_, &job_network_name_, &result_network_name_})
    if (*name == old_name) *name = new_name;
  if (auto unfiled = unfiled_networks_.extract(old_name)) {
    unfiled.key() = new_name;
    unfiled_networks_.insert(std::move(unfiled));
  }
  recent_.renameNetwork(old_name, new_name);
  if (result_) emit resultChanged();  // the output figures are named after the network
}

void ResultPanel::forgetNetwork(const QString& name) {
  unfiled_networks_.erase(name);
  const int index = network_choice_->findText(name);
  if (index < 0 || !network_choice_->itemData(index).toString().isEmpty()) return;
  network_choice_->removeItem(index);
  // The chooser shows the network in use (removing the current entry moved it to a neighbour).
  if (hasNetwork()) showNetworkInChoice(network_name_, network_file_);
  else network_choice_->setCurrentIndex(-1);
}

void ResultPanel::listShippedNetworks() { addShippedStyleNetworks(network_choice_); }

void ResultPanel::showNetworkInChoice(const QString& label, const QString& file) {
  int index = file.isEmpty() ? -1 : network_choice_->findData(file);
  if (index < 0) {
    index = network_choice_->findText(label);
    if (index < 0 || network_choice_->itemData(index).toString() != file) {
      network_choice_->addItem(label, file);
      index = network_choice_->count() - 1;
    }
  }
  network_choice_->setCurrentIndex(index);
}

bool ResultPanel::loadNetworkFile(const QString& file) {
  // A listed network goes by its label in the list (the shipped "Elderly"), as the look-ahead names it.
  const QString path = QFileInfo(file).absoluteFilePath();
  const int listed = network_choice_->findData(path);
  const QString name = listed >= 0 ? network_choice_->itemText(listed) : QFileInfo(file).completeBaseName();
  if (auto prepared = stylizers_.find(file)) {
    useStylizer(std::move(prepared), name, path);
    return true;
  }
  try {
    auto model = std::make_shared<const nn::StyleModel>(style::loadCompatibleStyleModel(file.toStdString()));
    useNetwork(std::move(model), name, path);
    if (hasNetwork()) stylizers_.store(file, stylizer_);
    return hasNetwork();
  } catch (...) {
    report(tr("Could not open the style network"), errorText(std::current_exception(), file));
  }
  return false;
}

void ResultPanel::openNetworkFile(const QString& file) {
  const QString path = QFileInfo(file).absoluteFilePath();
  int index = network_choice_->findData(path);
  if (index < 0) {
    network_choice_->addItem(QFileInfo(path).completeBaseName(), path);
    index = network_choice_->count() - 1;
    listed_for_reading_ = path;
  }
  network_choice_->setCurrentIndex(index);
  chooseNetwork(index);
}

void ResultPanel::chooseNetwork(int index) {
  const QString file = network_choice_->itemData(index).toString();
  const QString label = network_choice_->itemText(index);
  std::shared_ptr<const style::Stylizer> prepared;
  if (file.isEmpty()) {  // a network without a file, used here before
    const auto unfiled = unfiled_networks_.find(label);
    if (unfiled != unfiled_networks_.end()) prepared = unfiled->second;
  } else {
    prepared = stylizers_.find(file);
  }
  if (prepared || file.isEmpty()) {
    const bool was_reading = !reading_file_.isEmpty();
    reading_file_.clear();  // a read in flight only fills the cache now
    if (prepared) useStylizer(std::move(prepared), label, file);
    else if (hasNetwork()) showNetworkInChoice(network_name_, network_file_);
    // Back to the network in use (no switch, no job): the result, marked out of date by the read, is
    // brought back to the inputs (shown again, or computed).
    if (was_reading && resultIsStale() && !busy_) inputsChanged(stale_reason_);
    return;
  }
  const bool reading_already = reading_file_ == file;
  reading_file_ = file;
  if (reading_already) return;
  chosen_ms_ = clock_.elapsed();
  stopLookAhead();
  if (busy_) cancel();  // a job for the style being left: its result would be shown as the chosen one's
  if (result_) {
    stale_reason_ = tr("the style changed");
    status_label_->setText(tr("Out of date: %1. Reading %2...").arg(stale_reason_, label));
    refreshControls();
    emit resultRenamed();
  } else {
    status_label_->setText(tr("Reading %1...").arg(label));
  }
  reader_->restart(tr("Could not open the style network"), [this, file](const JobRunner::Context&) -> JobRunner::Completion {
    auto stylizer = readNetworkFile(file);
    return [this, stylizer, file] { onNetworkRead(stylizer, file); };
  });
}

std::shared_ptr<const style::Stylizer> ResultPanel::readNetworkFile(const QString& file) {
  return std::make_shared<const style::Stylizer>(style::loadCompatibleStyleModel(file.toStdString()), file.toStdString());
}

void ResultPanel::onNetworkRead(std::shared_ptr<const style::Stylizer> stylizer, const QString& file) {
  if (!stylizers_.find(file)) stylizers_.store(file, stylizer);
  if (listed_for_reading_ == file) listed_for_reading_.clear();  // it reads: it stays listed
  if (reading_file_ != file) return;  // another entry was picked since
  reading_file_.clear();
  const int listed = network_choice_->findData(file);
  const QString name = listed >= 0 ? network_choice_->itemText(listed) : QFileInfo(file).completeBaseName();
  if (!result_ && !busy_) status_label_->clear();  // "Reading ...": done
  useStylizer(std::move(stylizer), name, file, chosen_ms_);  // the change counts from the pick
  if (std::exchange(stylize_when_read_, false) && !busy_) stylize();
}

void ResultPanel::onNetworkReadFailed(const QString& title, const QString& message) {
  // A file listed only to be read leaves the chooser: it holds no network.
  if (!listed_for_reading_.isEmpty() && listed_for_reading_ == reading_file_) {
    const int listed = network_choice_->findData(listed_for_reading_);
    if (listed >= 0) network_choice_->removeItem(listed);
  }
  listed_for_reading_.clear();
  reading_file_.clear();
  stylize_when_read_ = false;
  // The chooser and the result go back to the network in use (the result shown again, or computed for
  // what changed during the read).
  if (hasNetwork()) showNetworkInChoice(network_name_, network_file_);
  else network_choice_->setCurrentIndex(-1);
  if (resultIsStale() && !busy_) inputsChanged(stale_reason_);
  else scheduleLookAhead();
  report(title, message);
}

void ResultPanel::browseNetwork() {
  const QString file = QFileDialog::getOpenFileName(this, tr("Open a style network"), QString(),
                                                    tr("Style networks (*.net);;All files (*)"));
  if (!file.isEmpty()) openNetworkFile(file);
}

}  // namespace motionstyle
