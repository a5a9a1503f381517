#pragma once
// The shipped style networks as the app lists them (the Result panel's Style choice, the Adapt tab):
// each file is fully checked (nn::networkFileInfo: header, CRC, every stored value) once, and again only
// when it changes on disk, so a damaged or foreign file is shown disabled with the reason instead of
// failing when chosen.

#include <QString>
#include <vector>

class QComboBox;

namespace motionstyle {

struct ShippedStyleNetwork {
  QString name;     // the file's stem ("elderly")
  QString file;     // absolute path
  QString problem;  // why it cannot be used (the reader's message); empty: usable
};

// The resources folder's style networks (not the loss network), sorted by name; empty without one.
std::vector<ShippedStyleNetwork> shippedStyleNetworks();

// <resources>/models/loss_network.net when installed (resource_paths.h), else empty: the loss network
// every shipped style learnt against.
QString shippedLossNetworkFile();

// Appends them to `choice` with the file as item data: "Elderly", or "Broken (cannot be read)"
// disabled with the problem as tooltip.
void addShippedStyleNetworks(QComboBox* choice);

}  // namespace motionstyle
