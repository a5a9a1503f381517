// NetworkPanel: the tabs and the run buttons, the training form's values, the status and the loss
// curve. The jobs (training, the optimisation method, the live preview) are in network_panel_jobs.cpp,
// the Adapt tab's connections in network_panel_adapt.cpp.
#include "network_panel.h"

#include <QDir>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QScrollArea>
#include <QSettings>
#include <QSplitter>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QVBoxLayout>

#include "adapt_tab.h"
#include "loss_curve_widget.h"
#include "job_runner.h"
#include "shipped_networks.h"

namespace motionstyle {
namespace {

const char* const kLossNetworkKey = "networks/lossNetwork";

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

  network_list_ = new NetworkList(persist_settings_, this);
  network_list_->setConfirmer(confirmer_);
  connect(network_list_, &NetworkList::errorOccurred, this, &NetworkPanel::report);
  connect(network_list_, &NetworkList::statusMessage, this, &NetworkPanel::showOutcome);
  connect(network_list_, &NetworkList::lossNetworkFileLoaded, this, &NetworkPanel::setLossNetworkFile);
  connect(network_list_, &NetworkList::currentNetworkChanged, this, [this] {
    showLossHistory();
    updateButtons();
  });
  tabs_ = new QTabWidget(this);
  tabs_->addTab(network_list_, tr("Networks"));
  // The forms are tall: each scrolls rather than squeezing its fields, or making the window taller
  // than a laptop's screen (their height was the window's minimum: 948 px).
  const auto scrolling = [this](QWidget* form) {
    auto* scroll = new QScrollArea(this);
    scroll->setWidget(form);
    scroll->setWidgetResizable(true);
    scroll->setFrameShape(QFrame::NoFrame);
    return scroll;
  };
  train_tab_ = new TrainTab(roles_, this);
  train_tab_->setFolders([this] { return clipFolder().folder(); }, [this] { return network_list_->networksFolder(); });
  connect(train_tab_, &TrainTab::errorOccurred, this, &NetworkPanel::report);
  connect(train_tab_, &TrainTab::clipFolderChosen, this, [this](const QString& folder) { clipFolder().remember(folder); });
  connect(train_tab_, &TrainTab::lossNetworkChanged, this, [this](const QString& file) {
    if (persist_settings_ && !file.isEmpty()) QSettings().setValue(kLossNetworkKey, file);
  });
  tabs_->addTab(scrolling(train_tab_), tr("Train"));
  optimise_tab_ = new OptimiseTab(this);
  connect(optimise_tab_, &OptimiseTab::optimiseRequested, this, &NetworkPanel::startTransfer);
  connect(optimise_tab_, &OptimiseTab::cancelRequested, this, &NetworkPanel::cancelJob);
  tabs_->addTab(scrolling(optimise_tab_), tr("Optimise"));
  tabs_->addTab(scrolling(createAdaptTab()), tr("Adapt"));

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

  bottom_ = new QWidget(this);
  auto* bottom_layout = new QVBoxLayout(bottom_);
  bottom_layout->setContentsMargins(0, 0, 0, 0);
  // Train, Retrain, Cancel and Resume stay in view under the (scrolling) form, next to the progress
  // they start; under the Optimise and Adapt forms, which have their own buttons, only while a
  // training runs (updateButtons).
  run_row_ = new QWidget(this);
  auto* run_buttons = new QHBoxLayout(run_row_);
  run_buttons->setContentsMargins(0, 0, 0, 0);
  const auto button = [&](const QString& text, const char* name, const QString& tip, auto on_click) {
    auto* made = new QPushButton(text, this);
    made->setObjectName(QString::fromLatin1(name));
    made->setToolTip(tip);
    connect(made, &QPushButton::clicked, this, on_click);
    run_buttons->addWidget(made);
    return made;
  };
  train_button_ = button(tr("&Train"), "TrainButton", tr("Train a new network on the training set"),
                         [this] { startTraining(false); });
  retrain_button_ = button(tr("&Retrain"), "RetrainButton", tr("Warm start from the selected network with these weights"),
                           [this] { startTraining(true); });
  cancel_button_ = button(tr("Cancel"), "CancelButton", tr("Stop; the last completed epoch is kept"), [this] { cancelJob(); });
  resume_button_ = button(tr("Res&ume"), "ResumeButton", tr("Continue the cancelled training from its last completed epoch"),
                          [this] { resumeTraining(); });
  bottom_layout->addWidget(run_row_);
  bottom_layout->addWidget(progress_bar_);
  bottom_layout->addWidget(status_label_);
  bottom_layout->addWidget(loss_curve_, 1);
  auto* splitter = new QSplitter(Qt::Vertical, this);
  splitter->addWidget(tabs_);
  splitter->addWidget(bottom_);
  splitter->setStretchFactor(0, 3);
  splitter->setStretchFactor(1, 2);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 4, 4, 4);
  layout->addWidget(splitter);
  connect(tabs_, &QTabWidget::currentChanged, this, &NetworkPanel::updateButtons);

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
  network_list_->blockSignals(true);  // its tree's clean-up would announce a "current network change"
  delete runner_;  // cancels the job and waits for its thread before the panel's members go
  runner_ = nullptr;
}

void NetworkPanel::setConfirmer(Confirmer confirmer) {
  confirmer_ = std::move(confirmer);
  network_list_->setConfirmer(confirmer_);
}

void NetworkPanel::showLossHistory() {
  if (isBusy()) return;  // the run draws its own curve
  const std::shared_ptr<const nn::StyleModel> model = network_list_->currentNetwork();
  if (!model) {
    loss_curve_->clear();
    return;
  }
  QStringList terms;
  for (const std::string& term : model->metadata.loss_history.terms) terms << QString::fromStdString(term);
  loss_curve_->setXAxisName(tr("epochs"));
  loss_curve_->setHistory(terms, model->metadata.loss_history.epochs);
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
  const bool has_current = network_list_->currentIndex() >= 0;
  train_button_->setEnabled(!busy);
  retrain_button_->setEnabled(!busy && has_current);
  cancel_button_->setEnabled(running_ == Running::Training);
  resume_button_->setEnabled(!busy && canResumeTraining());
  const bool training_tab = tabs_->currentWidget() == network_list_ || tabs_->currentWidget()->isAncestorOf(train_tab_);
  run_row_->setVisible(training_tab || running_ == Running::Training);
  // The Adapt form has its own progress and results: the training's progress, status and loss curve
  // show under it only while a training or an optimisation runs.
  bottom_->setVisible(!tabs_->currentWidget()->isAncestorOf(adapt_tab_) || running_ != Running::None);
  optimise_tab_->setRunState(!busy, running_ == Running::Transfer);
  if (busy != busy_) {
    busy_ = busy;
    emit busyChanged(busy);
  }
}

QString NetworkPanel::statusText() const { return status_label_->text(); }

void NetworkPanel::report(const QString& title, const QString& message) {
  status_label_->setText(title);
  emit errorOccurred(title, message);
}

void NetworkPanel::showOutcome(const QString& text) {
  status_label_->setText(text);
  emit statusMessage(text);
}

QMessageBox::StandardButton NetworkPanel::ask(const QString& title, const QString& text, QMessageBox::StandardButtons buttons) {
  return confirmer_ ? confirmer_(title, text, buttons) : QMessageBox::Cancel;
}

}  // namespace motionstyle
