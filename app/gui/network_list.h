#pragma once
// NetworkList: the Networks tab. The style networks the user has in this session (files loaded and
// networks trained or adapted, unsaved until saved), each under a unique name the user can edit (F2
// or a double click; empty or taken names refused); Load, Save As and Remove; the selected one's
// style clips, loss weights and training settings.
//
// Nothing the user owns is lost: a network file is saved atomically by the core and an existing file
// is replaced only after a confirmation; removing an unsaved network asks; prepareToClose() asks once
// for all unsaved networks (Save All into one folder, never over a file; Discard; Cancel).
// Dialogs go through the Confirmer (tests replace it), errors out as errorOccurred().

#include <QMessageBox>
#include <QWidget>

#include <functional>
#include <memory>
#include <vector>

#include "nn/network_file.h"
#include "style/reconstruction_memory.h"

class QLabel;
class QPushButton;
class QTreeWidget;

namespace motionstyle {

class NetworkList : public QWidget {
  Q_OBJECT

 public:
  // Shows a question and returns the button chosen (default: a QMessageBox).
  using Confirmer = std::function<QMessageBox::StandardButton(const QString& title, const QString& text,
                                                              QMessageBox::StandardButtons buttons)>;
  // Picks the folder "Save all" writes into, starting at `start` (default: a folder dialog).
  using FolderChooser = std::function<QString(const QString& start)>;

  // persist_settings: the networks folder (where files were last loaded or saved) is kept in QSettings.
  explicit NetworkList(bool persist_settings, QWidget* parent = nullptr);

  void setConfirmer(Confirmer confirmer) { confirmer_ = std::move(confirmer); }
  void setFolderChooser(FolderChooser chooser) { folder_chooser_ = std::move(chooser); }

  int networkCount() const { return static_cast<int>(networks_.size()); }
  int currentIndex() const;  // -1 when none is selected
  void setCurrentIndex(int index);
  std::shared_ptr<const nn::StyleModel> network(int index) const;  // null outside the list
  std::shared_ptr<const nn::StyleModel> currentNetwork() const;
  QString networkName(int index) const;  // the list's name, empty outside the list
  QString currentNetworkName() const;
  QString networkFile(int index) const;  // empty while never saved
  bool isNetworkSaved(int index) const;

  // A network made in this session (trained, adapted), unsaved, under `name` or, when taken, "name (2)",
  // "name (3)", ...; it becomes the current one. `memory`: what its loss network must go on
  // reconstructing when adapted again (an adapted network's, style/reconstruction_memory.h), saved and
  // loaded beside its file (network.memory); may be null.
  void addNetwork(std::shared_ptr<const nn::StyleModel> model, const QString& name,
                  std::shared_ptr<const style::ReconstructionMemory> memory = nullptr);
  std::shared_ptr<const style::ReconstructionMemory> networkMemory(int index) const;  // null: none
  // Loads a style network file and selects it (an already listed file is only selected). A loss
  // network file is announced as lossNetworkFileLoaded() instead. Errors are reported; false then.
  bool loadNetworkFile(const QString& file);
  // Saves atomically, with its memory beside it (both or neither); an existing file is replaced only
  // after the Confirmer answers Yes (or when `overwrite_confirmed`, e.g. after a file dialog asked).
  // false (and a report) on failure.
  bool saveNetwork(int index, const QString& file, bool overwrite_confirmed = false);
  // Asks before dropping an unsaved network; false when the user keeps it.
  bool removeNetwork(int index);
  // A new name for the network. Refused, with a report, when empty or taken by another network;
  // networkRenamed() tells the other panels.
  bool renameNetwork(int index, const QString& name);

  // For closing the window: true when no unsaved network is left to ask about, or the user chose.
  bool prepareToClose();

  // Where network files were last loaded or saved (the user's networks folder), else the home folder.
  QString networksFolder() const;
  // The file dialogs' filter for network files.
  static QString fileFilter();

 public slots:
  void browseLoad();
  void browseSave();

 signals:
  void currentNetworkChanged(std::shared_ptr<const motionstyle::nn::StyleModel> network);
  void networkRenamed(const QString& old_name, const QString& new_name);
  void networkRemoved(const QString& name);  // after currentNetworkChanged() named the new selection
  void lossNetworkFileLoaded(const QString& file);
  void statusMessage(const QString& text);
  void errorOccurred(const QString& title, const QString& message);

 private:
  struct Entry {
    std::shared_ptr<const nn::StyleModel> model;
    QString name;
    QString file;
    bool saved = false;
    std::shared_ptr<const style::ReconstructionMemory> memory;
  };

  void addEntry(Entry entry);
  bool nameTaken(const QString& name, const Entry* except) const;  // by a network other than `except`
  // `base`, or "base (2)", "base (3)", ...: the first no network other than `except` has.
  QString uniqueName(const QString& base, const Entry* except) const;
  void refresh();
  void showDetails();
  void updateButtons();
  void report(const QString& title, const QString& message);
  QMessageBox::StandardButton ask(const QString& title, const QString& text, QMessageBox::StandardButtons buttons);
  bool confirmDropUnsaved(int index);
  void rememberFolder(const QString& path);

  bool persist_settings_;
  Confirmer confirmer_;
  FolderChooser folder_chooser_;
  std::vector<Entry> networks_;
  QTreeWidget* tree_ = nullptr;
  QLabel* details_label_ = nullptr;
  QPushButton* save_button_ = nullptr;
  QPushButton* remove_button_ = nullptr;
};

}  // namespace motionstyle
