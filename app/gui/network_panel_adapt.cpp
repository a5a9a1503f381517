// NetworkPanel's Adapt tab wiring (adapt_tab.h): what the tab may adapt (the app's clips, the listed
// networks) and what becomes of its results (the adapted loss network for the Train tab, the retrained
// styles in the list, unsaved).
#include <QDateTime>
#include <QTabWidget>

#include <exception>

#include "adapt_tab.h"
#include "network_panel.h"

namespace motionstyle {

AdaptTab* NetworkPanel::createAdaptTab() {
  const auto networks = [this] {
    std::vector<AdaptTab::NamedNetwork> all;
    for (int i = 0; i < network_list_->networkCount(); ++i)
      all.push_back({network_list_->networkName(i), network_list_->network(i), network_list_->networkMemory(i)});
    return all;
  };
  adapt_tab_ = new AdaptTab(roles_.clips, networks, this);
  connect(adapt_tab_, &AdaptTab::errorOccurred, this, &NetworkPanel::report);
  connect(adapt_tab_, &AdaptTab::statusMessage, this, &NetworkPanel::statusMessage);
  connect(adapt_tab_, &AdaptTab::busyChanged, this, [this](bool) { updateButtons(); });
  connect(adapt_tab_, &AdaptTab::adapted, this,
          [this](std::shared_ptr<const nn::LossNetworkModel> loss, std::vector<style::StyleToRetrain> styles,
                 std::shared_ptr<const style::ReconstructionMemory> memory) {
            // The adapted loss network is saved in the scratch folder and becomes the Train tab's, so
            // that new styles train against it; the retrained styles join the list, unsaved.
            const std::filesystem::path file = scratchFile(QStringLiteral("adapted-loss-network.net"));
            try {
              if (!file.empty()) {
                nn::saveLossNetwork(*loss, file);
                setLossNetworkFile(QString::fromStdString(file.string()));
              }
            } catch (const std::exception& error) {
              report(tr("Could not keep the adapted loss network"), QString::fromStdString(error.what()));
            }
            for (style::StyleToRetrain& style : styles) {
              // The last one becomes current: the Result panel uses it.
              network_list_->addNetwork(std::make_shared<const nn::StyleModel>(std::move(style.model)),
                                        tr("%1 adapted %2").arg(QString::fromStdString(style.name),
                                                                QDateTime::currentDateTime().toString(QStringLiteral("MM-dd hh:mm"))),
                                        memory);
            }
          });
  return adapt_tab_;
}

void NetworkPanel::showAdaptTab(const QString& clip_path, const QString& style) {
  adapt_tab_->refresh();
  adapt_tab_->focus(clip_path, style);
  for (int index = 0; index < tabs_->count(); ++index)  // its page is the scroll area around it
    if (tabs_->widget(index)->isAncestorOf(adapt_tab_)) tabs_->setCurrentIndex(index);
  for (QWidget* ancestor = parentWidget(); ancestor != nullptr; ancestor = ancestor->parentWidget())
    if (ancestor->inherits("QDockWidget")) {
      ancestor->show();
      ancestor->raise();
      break;
    }
}

}  // namespace motionstyle
