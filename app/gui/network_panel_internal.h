#pragma once
// Private to NetworkPanel's files (network_panel*.cpp): the list columns, the file filter and the
// metadata texts they share.

#include <QString>
#include <string>

#include "nn/network_file.h"

namespace motionstyle::network_panel_detail {

enum NetworkColumn { kNetName, kNetStyles, kNetEpochs, kNetCreated, kNetColumnCount };
enum StyleColumn { kStyleLabel, kStyleFile };

// The value of metadata property `key` ("created", ...), empty when absent.
QString propertyValue(const nn::NetworkMetadata& metadata, const std::string& key);
// The network's style clips' names, comma-separated ("-" when none).
QString styleClipNames(const nn::NetworkMetadata& metadata);

inline QString networkFileFilter() { return QStringLiteral("MotionStyle networks (*.net);;All files (*)"); }

}  // namespace motionstyle::network_panel_detail
