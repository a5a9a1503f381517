#pragma once
// ResultPanel: the "Result" dock. The user's loop is: pick a style (the shipped networks are listed
// by name; File > Open Network or the Networks panel add others), set the strength, Stylize, look,
// Export.
//   - Stylize runs style::StylizeCleanupJob (the network on the content clip and the Ceres IK clean-up
//     onto the content's own skeleton) on a JobRunner: the UI never waits; Cancel drops the job.
//   - The metrics table shows foot skate, floor penetration, bone error and residual of the raw
//     network output (before) and of the cleaned clip (after), in cm and cm/s.
//   - Keep the content's path (on by default): the output covers the same ground and turns in the same
//     time as the content (style/path_mode.h); off lets the style change the pace.
//   - Aim at: the style's clip of the content's kind of locomotion (walk, run, turning walk), read from
//     the clip unless the user picks one (AimChoice); the status names the one aimed at.
//   - Familiarity: how close the content is to what the networks know (style/familiarity.h), with the
//     next step when it is not (adapt the networks: the Style networks panel's Adapt tab).
//   - Export writes the cleaned clip as BVH on the content's skeleton, atomically (bvh_writer.h), and
//     never overwrites silently (the save dialog asks; exportResult() refuses unless told to).
// The panel owns no clip: MainWindow hands it a copy of the content clip, the user's contact overrides
// and the network, and rebuilds its figures and tracks on resultChanged().

#include <QElapsedTimer>
#include <QString>
#include <QWidget>

#include <Eigen/Core>

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "clip_loader.h"
#include "contact_tracks.h"
#include "figure_data.h"
#include "job_runner.h"
#include "recent_results.h"
#include "result_metrics_view.h"
#include "nn/network_file.h"
#include "style/stylize_cleanup_job.h"
#include "stylizer_cache.h"
#include "style/familiarity.h"

class QCheckBox;
class QComboBox;
class QLabel;
class QPushButton;
class QSlider;
class QTableWidget;
class QTimer;

namespace motionstyle {

class AimChoice;
class BusyIndicator;
class FamiliarityLabel;

class ResultPanel : public QWidget {
  Q_OBJECT

 public:
  using ErrorReporter = std::function<void(const QString& title, const QString& message)>;
  // The metrics table's rows and columns (ResultMetricsView).
  static constexpr int kSkateRow = ResultMetricsView::kSkateRow;
  static constexpr int kPenetrationRow = ResultMetricsView::kPenetrationRow;
  static constexpr int kBoneErrorRow = ResultMetricsView::kBoneErrorRow;
  static constexpr int kResidualRow = ResultMetricsView::kResidualRow;
  static constexpr int kRawColumn = ResultMetricsView::kRawColumn;
  static constexpr int kCleanedColumn = ResultMetricsView::kCleanedColumn;

  explicit ResultPanel(QWidget* parent = nullptr);
  ~ResultPanel() override;  // the runner cancels the job and waits for its thread

  void setErrorReporter(ErrorReporter reporter) { reporter_ = std::move(reporter); }

  // The network used by Stylize (nullptr: none). `name` is shown and names exports ("elderly").
  void setStyleNetwork(std::shared_ptr<const nn::StyleModel> model, const QString& name = {});
  // The network called `old_name` (one without a file: from the Networks panel) is now `new_name`:
  // the Style choice, the status and the result's figures say the new name.
  void renameNetwork(const QString& old_name, const QString& new_name);
  // The network called `name` without a file was removed from the Networks panel: its entry leaves the
  // Style choice (a network with a file stays listed by its file).
  void forgetNetwork(const QString& name);
  // Loads a style network file (checked against this build's representation). false + report on error.
  bool loadNetworkFile(const QString& file);
  // The same without the GUI waiting for the file: the chooser lists it (by its name) and picks it,
  // and it is read and prepared as a picked entry is (chooseNetwork); a file that fails to read leaves
  // the chooser as it was, its entry removed, and is reported. Open..., File > Open Network and drops.
  void openNetworkFile(const QString& file);
  bool hasNetwork() const { return stylizer_ != nullptr; }
  // Stylize runs the chosen network (not a clip stylized elsewhere): the Style clip plays no part.
  bool resultComesFromNetwork() const { return hasNetwork() && !given_stylized_; }
  QString networkName() const { return network_name_; }
  // The style chooser: the shipped style networks (resources/models, by name), then networks opened
  // from files. Choosing one loads it.
  QComboBox* networkChoice() const { return network_choice_; }
  // How long the inputs must rest after a result (or, before the first, after an input changes) before
  // the chosen style and the styles nearest it in the chooser are computed ahead, one after the other
  // (result_panel_look_ahead.cpp; a clip just opened starts them at once); without a clip, before the
  // shipped networks are read and prepared; negative: never.
  // Default kLookAheadDelayMs.
  static constexpr int kLookAheadDelayMs = 400;
  // How many: kLookAheadFrames / the clip's frames, between kLookAheadMinStyles and kLookAheadMaxStyles:
  // all eight other shipped styles of a clip up to 2,000 frames (about 2 s of both cores at 120 fps,
  // 4 s at 30 fps; the app then holds 0.7-0.9 GB), fewer up to 8,000 frames, two beyond.
  static constexpr int kLookAheadFrames = 16000;
  static constexpr int kLookAheadMinStyles = 2;
  static constexpr int kLookAheadMaxStyles = 8;
  int lookAheadStyles() const;
  void setLookAheadDelay(int milliseconds);
  // held: another job has the cores (the Style networks panel trains, optimises or adapts): what is
  // computed ahead stops, and nothing more is until it is released. Edits and Stylize still run.
  void holdLookAhead(bool held);
  // The rest before the look-ahead is there for the steps of a drag, or of a key held down: it is
  // waited for only when a result comes with the hand on a control (`hand_on_control`, MainWindow:
  // LiveResolution::handOnControl; by default a mouse button held), and cut short when the hand lets go
  // (LiveResolution::handReleased).
  void setHandOnControl(std::function<bool()> hand_on_control);
  void handReleased();
  // The results remembered for switching back or ahead (recent_results.h).
  const RecentResults& recentResults() const { return recent_; }

  // The clip to stylize (a copy is kept), nullptr for none. The result is dropped when the clip's id
  // changes (another clip, or the same clip re-mapped); the same id again is a no-op.
  void setContentClip(const LoadedClip* clip);
  // The user's contact overrides at the content's rate (frames x 4, -1/0/1): used by the next clean-up.
  void setContactOverrides(const Eigen::MatrixXi& overrides);
  // An already stylized clip of the current content (the optimisation method's output): cleaned up
  // now, and again by the next Stylize instead of running a network.
  void setStylizedClip(style::StylizedClip clip, const QString& label);

  double strength() const;  // in [0, 1]: 0 = the content, 1 = fully styled
  void setStrength(double strength);
  // Whose root path and timing the output follows (style/path_mode.h): the content's by default.
  style::PathMode pathMode() const;
  void setPathMode(style::PathMode mode);
  // Which of the style's clips the refinement aims at (AimChoice, style/locomotion_kind.h): "" read
  // from the content clip (the default), else one of style::kLocomotionKinds.
  std::string aimKind() const;
  // How familiar the content is to the chosen network (style/familiarity.h); nullopt without a mapped
  // content clip and a network.
  const std::optional<style::Familiarity>& familiarity() const;
  bool isBusy() const { return busy_; }
  const style::StylizeCleanupResult* result() const { return result_.get(); }
  // The shown result was made from other inputs than the panel's (the style, strength, path or
  // contacts changed since): it is named out of date in the status, the figures' names and Export,
  // and is being replaced when the new inputs can be stylized.
  bool resultIsStale() const { return result_ != nullptr && !stale_reason_.isEmpty(); }
  QTableWidget* metricsTable() const { return metrics_->table(); }

  // The result's figures at the content's rate, in the content's display space: the cleaned output
  // (blue) with its contacts, then, when `include_raw`, the raw network output (grey). Empty without a
  // result.
  std::vector<FigureData> resultFigures(bool include_raw) const;
  // Their names, in the same order ("out of date" while resultIsStale()).
  QStringList resultFigureNames(bool include_raw) const;
  // The timeline's per-frame quality of the result at the content's rate; empty without a result.
  QualityTracks qualityTracks() const;

 public slots:
  void stylize();  // reports when there is no content or network; ignored while busy
  void cancel();
  // Writes the cleaned clip to `file` (BVH, content's skeleton and rate). An existing file is replaced
  // only when `overwrite`; otherwise, as on any failure, false and a report.
  bool exportResult(const QString& file, bool overwrite);
  void browseExport();
  void browseNetwork();

 signals:
  void resultChanged();           // a new result, or none any more
  // The shown result went out of date: only its figures' names change (resultFigureNames), so they
  // are renamed, not rebuilt; rebuilding them took GUI time from the job that will replace them.
  void resultRenamed();
  void sourceChanged();           // resultComesFromNetwork() may have changed (a network or stylized clip given)
  void familiarityChanged();      // the content or the network changed: familiarity() is new
  // The user asked to adapt the networks to clips like the content (the familiarity row's link).
  void adaptRequested();
  void networkChosen(const QString& name);  // another style network to stylize with (networkName())
  void busyChanged(bool busy);
  void jobEnded(bool succeeded);  // after finished, failed or cancelled
  void statusMessage(const QString& message);
  void frameRequested(int frame);  // a clean-up warning's link: show this frame of the content
  // A held-down warning's fix (ResultMetricsView::contactEndRequested): the content's frames.
  void contactEndRequested(int contact, int first_frame, int last_frame);

 private:
  void startJob(style::StylizeCleanupJob job);
  void onFinished(std::shared_ptr<const style::StylizeCleanupResult> result);
  void setBusy(bool busy, const QString& status);
  void clearResult();
  void refreshMetrics();
  void refreshControls();
  void refreshFamiliarity();
  // An input of the result changed (`what`, e.g. "the style changed"): a shown result becomes stale
  // and is replaced by a new run when one is possible; while a job runs, one run for the latest inputs
  // follows it (see pending_). Called for every step of a slider drag or a contact stroke.
  // changed_ms: when it changed (clock_), if before now (a style picked before its file was read).
  void inputsChanged(const QString& what, qint64 changed_ms = -1);
  void runStylize();  // stylize() without its "already busy" check: startJob drops a running job
  // The inputs a network's result depends on, as they are now (recent_results.h).
  ResultInputs currentInputs() const;
  // Shows the result remembered for the current inputs, if any (a style shown before with the same
  // clip, strength, path, aim and contacts, or computed ahead): no job. Returns whether it did.
  // stylize_pressed: it answers Stylize (the status says the clip was stylized), not a change.
  // waited_ms: how long the panel waited for the look-ahead's job of it (adoptLookAhead), for the log.
  bool showRememberedResult(bool stylize_pressed = false, qint64 waited_ms = -1);
  // The look-ahead (result_panel_look_ahead.cpp): scheduled after a result and, before the first
  // one, when a mapped clip opens or an input changes; stopped by any change and any job.
  // at_once: without the rest (nothing is being dragged); unless it is off or held.
  void scheduleLookAhead(bool at_once = false);
  void stopLookAhead();
  void lookAhead();
  // Without a mapped clip: reads and prepares the next shipped network not prepared yet, so that the
  // first clip's look-ahead and a style picked on it skip the read (the first: 150-200 ms).
  void readAhead();
  void onReadAhead(std::shared_ptr<const style::Stylizer> stylizer, const QString& file, qint64 milliseconds);
  void startLookAhead(ResultInputs inputs, const QString& file, const QString& name);
  void onLookedAhead(RecentResults::Entry entry, const QString& file, qint64 milliseconds);
  // The look-ahead job under way computes `inputs` (a prepared network's): a job for them would redo it.
  bool lookAheadComputes(const ResultInputs& inputs) const;
  // For runStylize: when the look-ahead computes the current inputs, the panel waits for it (busy, as for
  // a job of its own) instead of dropping it and starting the same job; its result is shown as one
  // computed ahead. Returns whether it did.
  bool adoptLookAhead();
  // A change or Cancel while waiting for it: the panel no longer waits (the look-ahead is dropped).
  void dropAdoptedLookAhead();
  // Shows result_: the figures first, then the rows, `status` and the buttons. Returns when (clock_)
  // the figures were on the screen: what the live latencies in the log are measured to.
  // next_job_running: a job for newer inputs already runs; the panel stays busy with its status.
  qint64 showResult(const QString& status, bool next_job_running = false);
  // The app log's line for result_ on the screen (app_log.h; test_gui_live and user_drag_test.sh
  // read it): the latency from the change, the job's and the figures' share, and `how` it was made.
  void logResultOnScreen(const QString& change, qint64 latency_ms, qint64 job_ms, qint64 figures_ms, double strength,
                         int chunks_solved, const QString& how) const;
  bool canStylize() const;  // a mapped content and a network or stylized clip
  void report(const QString& title, const QString& message);
  void listShippedNetworks();
  // setStyleNetwork / loadNetworkFile: `file` is the network's file ("" when it has none).
  void useNetwork(std::shared_ptr<const nn::StyleModel> model, const QString& name, const QString& file);
  void useStylizer(std::shared_ptr<const style::Stylizer> stylizer, const QString& name, const QString& file,
                   qint64 chosen_ms = -1);
  // The chooser's entry `index` picked by the user. A network prepared before is used at once; one not
  // yet read is read and prepared on reader_ (the GUI never waits for a file: 20-180 ms), the shown
  // result marked out of date and no job run meanwhile, and it is used when ready unless another entry
  // was picked since (result_panel_networks.cpp). The log's latency counts from the pick.
  void chooseNetwork(int index);
  void onNetworkRead(std::shared_ptr<const style::Stylizer> stylizer, const QString& file);
  // A network file read, checked against this build and prepared (on a worker). Throws as
  // style::loadCompatibleStyleModel.
  static std::shared_ptr<const style::Stylizer> readNetworkFile(const QString& file);
  void onNetworkReadFailed(const QString& title, const QString& message);
  // Selects (adding it if needed) the chooser entry for `file` ("" for a network without a file, e.g.
  // one from the Networks panel or a stylized clip), showing `label`.
  void showNetworkInChoice(const QString& label, const QString& file);

  ErrorReporter reporter_;
  std::shared_ptr<const style::Stylizer> stylizer_;
  QString network_name_;
  QString network_file_;  // stylizer_'s file, "" when it has none
  // The networks without a file in the chooser (from the Networks panel), by their entry's label: picking
  // the entry again uses the network again.
  std::map<QString, std::shared_ptr<const style::Stylizer>> unfiled_networks_;
  std::shared_ptr<const LoadedClip> content_;
  std::shared_ptr<const MotionFeatures> content_features_;  // clipFeatures(content_): familiarity, kind read
  Eigen::MatrixXi overrides_;
  std::optional<style::StylizedClip> given_stylized_;
  std::shared_ptr<const style::StylizeCleanupResult> result_;
  QString result_network_name_;  // the network the shown result was made with
  QString job_network_name_;     // the network of the running job
  QString stale_reason_;         // why the shown result is out of date; empty: it is current
  QString last_export_folder_;

  JobRunner* runner_ = nullptr;
  bool busy_ = false;        // a job is on its way
  // Live edits: a change while a job runs lets that job finish (its result is shown, marked out of
  // date) and then runs ONE job for the latest inputs; the values in between are dropped, never queued.
  // Except a job started under half the last job's time ago: it answers values the hand has left, and
  // finishing it would hold the latest inputs back by more than half a job and a paint, so it is
  // dropped and one for the latest inputs starts at once; never two in a row, so results keep coming
  // however fast the hand moves (the half against a third: docs/decisions.md).
  bool pending_ = false;
  qint64 job_start_ms_ = -1;       // when the running job was started (clock_)
  qint64 last_job_ms_ = 0;         // how long the last finished job took
  bool dropped_previous_ = false;  // the running job replaced a dropped one
  StylizerCache stylizers_;  // networks prepared from files: switching back to one skips reading it
  RecentResults recent_;     // results per network for their inputs: switching back to one shows it
  JobRunner* look_ahead_ = nullptr;     // computes the nearby styles while the user looks
  QTimer* look_ahead_timer_ = nullptr;  // the inputs' rest before it starts
  int look_ahead_delay_ms_ = kLookAheadDelayMs;
  bool look_ahead_held_ = false;
  std::function<bool()> hand_on_control_;  // setHandOnControl
  ResultInputs look_ahead_inputs_;  // what the look-ahead job under way computes
  bool look_ahead_adopted_ = false;  // the panel waits for that job's result (adoptLookAhead)
  bool adopted_for_stylize_ = false;  // ... asked for by Stylize (no result shown yet)
  bool look_ahead_reads_ = false;   // its job only reads a network (readAhead): a change lets it finish
  QStringList unreadable_files_;    // listed network files the look-ahead could not read: passed over
  JobRunner* reader_ = nullptr;  // reads the file of a network picked in the chooser
  QString reading_file_;         // the file it reads for the chooser's current entry, "" when none
  QString listed_for_reading_;   // a file openNetworkFile added to the chooser, until it reads
  bool stylize_when_read_ = false;   // Stylize was pressed during the read
  qint64 chosen_ms_ = -1;        // when the entry being read was picked (clock_)
  std::shared_ptr<style::StylizeCleanupMemory> memory_;  // the last job on the content: an edit redoes what changed
  QElapsedTimer clock_;                    // for the log's latencies (app_log.h)
  qint64 last_change_ms_ = -1;             // when the inputs last changed, and what changed
  QString last_change_;
  qint64 job_change_ms_ = -1;              // the change the running job answers
  QString job_change_;
  double job_strength_ = 1.0;
  bool abandoning_ = false;  // dropping a job on purpose: its finished(false) is not a cancellation

  QComboBox* network_choice_ = nullptr;
  QLabel* content_label_ = nullptr;
  QSlider* strength_slider_ = nullptr;
  QLabel* strength_label_ = nullptr;
  QCheckBox* keep_path_ = nullptr;
  AimChoice* aim_choice_ = nullptr;
  FamiliarityLabel* familiarity_label_ = nullptr;
  QPushButton* stylize_button_ = nullptr;
  QPushButton* cancel_button_ = nullptr;
  BusyIndicator* progress_ = nullptr;
  QLabel* status_label_ = nullptr;
  ResultMetricsView* metrics_ = nullptr;
  QPushButton* export_button_ = nullptr;
};

}  // namespace motionstyle
