#include "adapt_tab.h"
#include "shipped_networks.h"

#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSpinBox>
#include <QTemporaryDir>
#include <QTableWidget>
#include <QVBoxLayout>

#include <cmath>
#include <set>

#include "common/errors.h"
#include "common/resource_paths.h"
#include "error_text.h"
#include "item_view_layout.h"
#include "job_runner.h"
#include "style/adaptation.h"
#include "style/reconstruction_memory.h"
#include "style/training.h"

namespace motionstyle {
namespace {

constexpr int kPathRole = Qt::UserRole;       // clip list: file or folder path
constexpr int kFolderRole = Qt::UserRole + 1;  // clip list: true for a folder entry

QString duration(double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) return QStringLiteral("--:--");
  const long long s = std::llround(seconds);
  return QStringLiteral("%1:%2").arg(s / 60).arg(s % 60, 2, 10, QLatin1Char('0'));
}

std::set<QString> uncheckedTexts(const QListWidget* list) {
  std::set<QString> unchecked;
  for (int i = 0; i < list->count(); ++i)
    if (list->item(i)->checkState() != Qt::Checked) unchecked.insert(list->item(i)->data(kPathRole).toString());
  return unchecked;
}

}  // namespace

AdaptTab::AdaptTab(ClipsProvider clips, NetworksProvider networks, QWidget* parent)
    : QWidget(parent), clips_(std::move(clips)), networks_(std::move(networks)) {
  setObjectName(QStringLiteral("AdaptTab"));
  runner_ = new JobRunner(this);
  auto* intro = new QLabel(tr("Make the networks hold on your own clips (another studio, actor or rig): the loss "
                              "network learns to reconstruct them, then the styles you choose are retrained on "
                              "them. What the networks knew is kept (the loss network's memory of the data it "
                              "learnt from). Ten clips and one style take about 20 s."),
                           this);
  intro->setWordWrap(true);
  clip_list_ = new QListWidget(this);
  clip_list_->setObjectName(QStringLiteral("AdaptClips"));
  clip_list_->setToolTip(tr("Your clips: the mapped clips loaded in MotionStyle, and folders you add"));
  auto* add_folder = new QPushButton(tr("Add Folder..."), this);
  connect(add_folder, &QPushButton::clicked, this, [this] {
    const QString folder = QFileDialog::getExistingDirectory(this, tr("A folder of your clips"));
    if (folder.isEmpty()) return;
    auto* item = new QListWidgetItem(tr("%1 (folder)").arg(QDir(folder).dirName()), clip_list_);
    item->setData(kPathRole, folder);
    item->setData(kFolderRole, true);
    item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
    item->setCheckState(Qt::Checked);
  });
  style_list_ = new QListWidget(this);
  style_list_->setObjectName(QStringLiteral("AdaptStyles"));
  style_list_->setToolTip(tr("The styles to retrain on your clips (networks that store their style targets)"));
  loss_epochs_ = new QSpinBox(this);
  loss_epochs_->setRange(1, 1000);
  loss_epochs_->setValue(style::AdaptationSettings{}.epochs);
  loss_epochs_->setFocusPolicy(Qt::StrongFocus);  // the wheel changes it only with focus
  style_epochs_ = new QSpinBox(this);
  style_epochs_->setRange(1, 1000);
  style_epochs_->setValue(30);
  style_epochs_->setFocusPolicy(Qt::StrongFocus);
  adapt_button_ = new QPushButton(tr("Adapt"), this);
  adapt_button_->setObjectName(QStringLiteral("AdaptButton"));
  cancel_button_ = new QPushButton(tr("Cancel"), this);
  cancel_button_->setEnabled(false);
  connect(adapt_button_, &QPushButton::clicked, this, &AdaptTab::start);
  connect(cancel_button_, &QPushButton::clicked, this, &AdaptTab::cancel);
  progress_ = new QProgressBar(this);
  progress_->setVisible(false);
  status_ = new QLabel(this);
  status_->setWordWrap(true);
  table_ = new QTableWidget(0, 3, this);
  table_->setObjectName(QStringLiteral("AdaptFamiliarity"));
  table_->setHorizontalHeaderLabels({tr("Clip"), tr("Before (cm)"), tr("After (cm)")});
  table_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setToolTip(tr("Familiarity of each clip: the loss network's reconstruction error before and after "
                        "adapting (familiar up to %1 cm, unusual up to %2 cm)")
                         .arg(style::kFamiliarMaxCm)
                         .arg(style::kUnusualMaxCm));

  auto* clip_row = new QHBoxLayout;
  clip_row->addWidget(clip_list_, 1);
  clip_row->addWidget(add_folder, 0, Qt::AlignTop);
  auto* epochs = new QHBoxLayout;
  epochs->addWidget(new QLabel(tr("loss network"), this));
  epochs->addWidget(loss_epochs_);
  epochs->addWidget(new QLabel(tr("styles"), this));
  epochs->addWidget(style_epochs_);
  epochs->addStretch(1);
  auto* form = new QFormLayout;
  form->addRow(tr("Your clips:"), clip_row);
  form->addRow(tr("Styles to retrain:"), style_list_);
  form->addRow(tr("Epochs:"), epochs);
  auto* buttons = new QHBoxLayout;
  buttons->addWidget(adapt_button_, 1);
  buttons->addWidget(cancel_button_);
  auto* layout = new QVBoxLayout(this);
  layout->addWidget(intro);
  layout->addLayout(form);
  layout->addLayout(buttons);
  layout->addWidget(progress_);
  layout->addWidget(status_);
  layout->addWidget(table_, 1);

  // Only a user's toggle reaches this: the lists are rebuilt and focused with the signals blocked.
  connect(style_list_, &QListWidget::itemChanged, this, [this] { styles_chosen_here_ = true; });
  connect(runner_, &JobRunner::failed, this, &AdaptTab::errorOccurred);
  connect(runner_, &JobRunner::busyChanged, this, [this](bool busy) {
    adapt_button_->setEnabled(!busy);
    cancel_button_->setEnabled(busy);
    progress_->setVisible(busy);
    emit busyChanged(busy);
  });
  connect(runner_, &JobRunner::finished, this, [this](bool completed) {
    if (completed) return;
    status_->setText(tr("Adaptation stopped: nothing was changed."));
    emit statusMessage(status_->text());
  });
  refresh();
}

AdaptTab::~AdaptTab() {
  delete runner_;  // cancels the job and waits for its thread before its scratch folder goes
  runner_ = nullptr;
}

bool AdaptTab::isBusy() const { return runner_->isBusy(); }
QString AdaptTab::statusText() const { return status_->text(); }
void AdaptTab::cancel() {
  if (!runner_->isBusy()) return;
  runner_->cancel();
  status_->setText(tr("Cancelling..."));
}

void AdaptTab::setEpochs(int loss_epochs, int style_epochs) {
  loss_epochs_->setValue(loss_epochs);
  style_epochs_->setValue(style_epochs);
}

void AdaptTab::refresh() {
  const std::set<QString> unchecked_clips = uncheckedTexts(clip_list_);
  std::set<QString> checked_styles;
  for (int i = 0; i < style_list_->count(); ++i)
    if (style_list_->item(i)->checkState() == Qt::Checked) checked_styles.insert(style_list_->item(i)->data(kPathRole).toString());
  const bool first_listing = style_list_->count() == 0;
  std::vector<QListWidgetItem*> folders;
  for (int i = clip_list_->count() - 1; i >= 0; --i)
    if (clip_list_->item(i)->data(kFolderRole).toBool()) folders.push_back(clip_list_->takeItem(i));
  clip_list_->clear();
  for (const LoadedClip* clip : clips_()) {
    if (!clip->isMapped()) continue;
    auto* item = new QListWidgetItem(clip->name, clip_list_);
    item->setData(kPathRole, clip->path);
    item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
    item->setCheckState(unchecked_clips.count(clip->path) ? Qt::Unchecked : Qt::Checked);
  }
  for (auto it = folders.rbegin(); it != folders.rend(); ++it) clip_list_->addItem(*it);

  const QSignalBlocker listing(style_list_);
  style_list_->clear();
  const auto addStyle = [&](const QString& name, const QString& key, const QString& problem = {}) {
    auto* item = new QListWidgetItem(name, style_list_);
    item->setData(kPathRole, key);
    item->setFlags(item->flags() | Qt::ItemIsUserCheckable);
    const bool checked = problem.isEmpty() && (first_listing ? style_list_->count() == 1 : checked_styles.count(key) > 0);
    item->setCheckState(checked ? Qt::Checked : Qt::Unchecked);  // first listing: the first style
    if (problem.isEmpty()) return;
    item->setText(tr("%1 (cannot be read)").arg(name));
    item->setToolTip(problem);
    item->setFlags(item->flags() & ~Qt::ItemIsEnabled);
  };
  for (const ShippedStyleNetwork& network : shippedStyleNetworks()) addStyle(network.name, network.file, network.problem);
  for (const NamedNetwork& network : networks_())
    if (network.model && !network.model->style_targets.empty()) addStyle(network.name, QStringLiteral("panel:") + network.name);
  layOutItemsNow(*clip_list_);
  layOutItemsNow(*style_list_);
}

void AdaptTab::focus(const QString& clip_path, const QString& style) {
  if (!clip_path.isEmpty())
    for (int i = 0; i < clip_list_->count(); ++i) {
      QListWidgetItem* item = clip_list_->item(i);
      item->setCheckState(item->data(kPathRole).toString() == clip_path ? Qt::Checked : Qt::Unchecked);
    }
  const QSignalBlocker focusing(style_list_);
  const auto matches = [&](int i) { return style_list_->item(i)->text().compare(style, Qt::CaseInsensitive) == 0; };
  bool listed = false;
  for (int i = 0; i < style_list_->count() && !style.isEmpty(); ++i) listed = listed || matches(i);
  if (!listed) return;
  for (int i = 0; i < style_list_->count(); ++i) {
    style_list_->item(i)->setCheckState(matches(i) ? Qt::Checked : Qt::Unchecked);
    if (matches(i)) style_list_->scrollToItem(style_list_->item(i));
  }
}

void AdaptTab::followStyle(const QString& style) {
  if (!styles_chosen_here_) focus(QString(), style);
}

void AdaptTab::setStyleChecked(const QString& name, bool checked) {
  for (int i = 0; i < style_list_->count(); ++i)
    if (style_list_->item(i)->text() == name) style_list_->item(i)->setCheckState(checked ? Qt::Checked : Qt::Unchecked);
}

bool AdaptTab::start() {
  const QString title = tr("Could not adapt the networks");
  if (runner_->isBusy()) return false;
  // Inputs are copied on the GUI thread: the user may change the app's clips while the job runs.
  struct Source {
    QString name;
    Motion motion;
    JointMapping mapping;
  };
  auto sources = std::make_shared<std::vector<Source>>();
  auto folders = std::make_shared<std::vector<std::filesystem::path>>();
  std::set<QString> wanted;
  for (int i = 0; i < clip_list_->count(); ++i) {
    const QListWidgetItem* item = clip_list_->item(i);
    if (item->checkState() != Qt::Checked) continue;
    if (item->data(kFolderRole).toBool()) folders->emplace_back(item->data(kPathRole).toString().toStdString());
    else wanted.insert(item->data(kPathRole).toString());
  }
  for (const LoadedClip* clip : clips_())
    if (clip->isMapped() && wanted.count(clip->path)) sources->push_back({clip->path, clip->motion, *clip->mapping});
  if (sources->empty() && folders->empty()) {
    emit errorOccurred(title, tr("Check at least one of your clips (load BVH files first, or add a folder)."));
    return false;
  }
  style::AdaptNetworksJob job;
  std::vector<NamedNetwork> panel = networks_();
  // What the loss network must not forget: the first style's own memory (an adapted network), else one
  // beside its file or the shipped one that fits (found on the worker).
  std::shared_ptr<const style::ReconstructionMemory> first_memory;
  std::filesystem::path first_file;
  try {
    for (int i = 0; i < style_list_->count(); ++i) {
      const QListWidgetItem* item = style_list_->item(i);
      if (item->checkState() != Qt::Checked) continue;
      const QString key = item->data(kPathRole).toString();
      const bool first = job.styles.empty();
      if (key.startsWith(QStringLiteral("panel:"))) {
        for (const NamedNetwork& network : panel)
          if (network.name == item->text()) {
            job.styles.push_back({network.name.toStdString(), *network.model});
            if (first) first_memory = network.memory;
          }
      } else {
        job.styles.push_back({item->text().toStdString(), style::loadCompatibleStyleModel(key.toStdString())});
        if (first) first_file = key.toStdString();
      }
    }
    // The loss network to adapt: the first style's own (every chosen style must share its encoder),
    // else the shipped one.
    if (!job.styles.empty()) {
      const nn::StyleModel& first = job.styles.front().model;
      job.loss.loss_network = nn::embeddedLossNetwork(first);
      job.loss.loss_network_name = job.styles.front().name + "'s loss network";
      for (const style::StyleToRetrain& style : job.styles)
        if (style.model.loss_network.encoder.weight.value != first.loss_network.encoder.weight.value)
          throw InputError(style.name, 0, "was trained against another loss network than " + job.styles.front().name +
                                              ": adapt them one at a time");
    } else {
      const auto resources = resourceDirectory();
      const auto file = resources ? shippedNetworkFile(*resources, kShippedLossNetworkName) : std::nullopt;
      if (!file) throw InputError("", 0, "no loss network: choose a style to retrain, or install the shipped networks");
      job.loss.loss_network = style::loadCompatibleLossNetwork(*file);
      job.loss.loss_network_name = kShippedLossNetworkName;
    }
  } catch (...) {
    emit errorOccurred(title, errorText(std::current_exception()));
    return false;
  }
  if (!scratch_) {  // the session's checkpoints, removed with the tab
    scratch_ = std::make_unique<QTemporaryDir>(QDir(QDir::tempPath()).filePath(QStringLiteral("motionstyle-adapt-XXXXXX")));
    if (!scratch_->isValid()) {
      scratch_.reset();
      emit errorOccurred(title, tr("Could not create a folder for the checkpoints in %1.").arg(QDir::tempPath()));
      return false;
    }
  }
  const std::filesystem::path scratch(scratch_->path().toStdString());
  job.loss.settings.epochs = loss_epochs_->value();
  job.loss.settings.output = scratch / "adapted-loss-network.net";
  job.style_epochs = style_epochs_->value();
  job.scratch = scratch;
  // The session's scratch folder: Cancel never waits for the disk.
  job.loss.settings.checkpoint_durability = FileDurability::Unsynced;
  table_->setRowCount(0);
  progress_->setRange(0, 0);
  status_->setText(tr("Reading your clips..."));
  return runner_->start(title, [this, job = std::move(job), sources, folders, first_memory,
                                first_file](const JobRunner::Context& context) mutable
                                   -> JobRunner::Completion {
    const style::TrainingCallbacks callbacks = context.trainingCallbacks(
        [this](const style::TrainingProgress& p) { onProgress(p); }, [this](const QString& line) { status_->setText(line); });
    for (const Source& source : *sources)
      job.loss.clips.push_back(style::makeMotionClip(source.motion, source.mapping, source.name.toStdString()));
    if (!folders->empty()) {
      style::DatasetOptions options;
      options.bad_files = style::BadFilePolicy::Skip;
      for (style::MotionClip& clip : style::loadMotionClips(*folders, options, nullptr, callbacks.cancel))
        job.loss.clips.push_back(std::move(clip));
    }
    // What the loss network knew stays (reconstruction_memory.h).
    if (first_memory) job.loss.memory = *first_memory;
    else job.loss.memory = style::findMatchingMemory(job.loss.loss_network, first_file);
    auto result = std::make_shared<style::AdaptNetworksJob::Result>(job.run(callbacks));
    if (result->status != style::TrainingStatus::Completed) return nullptr;
    return [this, result] { showResult(*result); };
  });
}

void AdaptTab::onProgress(const style::TrainingProgress& p) {
  if (p.phase == style::TrainingProgress::Phase::Loading) {
    progress_->setRange(0, 0);
    status_->setText(QString::fromStdString(p.message));
    return;
  }
  progress_->setRange(0, p.epochs * std::max(1, p.steps_per_epoch));
  progress_->setValue((p.epoch - 1) * std::max(1, p.steps_per_epoch) + p.step);
  progress_->setFormat(tr("epoch %1/%2, ETA %3").arg(p.epoch).arg(p.epochs).arg(duration(p.eta_seconds)));
  status_->setText(QString::fromStdString(p.message));
}

void AdaptTab::showResult(const style::AdaptNetworksJob::Result& result) {
  table_->setRowCount(static_cast<int>(result.loss.clips.size()) + 1);
  const auto put = [this](int row, int column, const QString& text) {
    auto* item = new QTableWidgetItem(text);
    if (column > 0) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    table_->setItem(row, column, item);
  };
  const auto figure = [](double cm) {
    return QStringLiteral("%1 %2").arg(cm, 0, 'f', 2).arg(QString::fromLatin1(style::familiarityName(style::familiarityLevel(cm))));
  };
  int row = 0;
  for (const style::ClipFamiliarity& clip : result.loss.clips) {
    put(row, 0, QFileInfo(QString::fromStdString(clip.file.string())).fileName());
    put(row, 1, figure(clip.before_cm));
    put(row, 2, figure(clip.after_cm));
    ++row;
  }
  put(row, 0, tr("All clips"));
  put(row, 1, figure(result.loss.mean_before_cm));
  put(row, 2, figure(result.loss.mean_after_cm));
  const QString kept = result.loss.memory.empty()
                          ? tr("No memory of the data it learnt from fits this loss network: some of it may be forgotten.")
                          : tr("What it knew is kept (its memory of %1).").arg(QString::fromStdString(result.loss.memory));
  status_->setText(tr("Adapted in %1: familiarity %2 -> %3 cm. %4 The adapted networks are in the Networks list "
                      "(unsaved).")
                       .arg(duration(result.seconds))
                       .arg(result.loss.mean_before_cm, 0, 'f', 2)
                       .arg(result.loss.mean_after_cm, 0, 'f', 2)
                       .arg(kept));
  emit statusMessage(status_->text());
  emit adapted(std::make_shared<const nn::LossNetworkModel>(result.loss.model), result.styles,
               result.loss.memory_after ? std::make_shared<const style::ReconstructionMemory>(*result.loss.memory_after)
                                        : nullptr);
}

}  // namespace motionstyle
