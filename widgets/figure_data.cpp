#include "figure_data.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace motionstyle {

QColor figureColor(FigureRole role) {
  switch (role) {
    case FigureRole::Content: return QColor::fromRgbF(0.30f, 0.74f, 0.36f);
    case FigureRole::Style: return QColor::fromRgbF(0.86f, 0.29f, 0.27f);
    case FigureRole::Output: return QColor::fromRgbF(0.26f, 0.50f, 0.92f);
    case FigureRole::RawOutput: return QColor::fromRgbF(0.62f, 0.63f, 0.66f);
  }
  return Qt::white;
}

QString figureRoleName(FigureRole role) {
  switch (role) {
    case FigureRole::Content: return QStringLiteral("Content");
    case FigureRole::Style: return QStringLiteral("Style");
    case FigureRole::Output: return QStringLiteral("Output");
    case FigureRole::RawOutput: return QStringLiteral("Raw output");
  }
  return {};
}

void FigureData::validate() const {
  const std::string who = "figure '" + name.toStdString() + "': ";
  if (parents.empty()) throw std::invalid_argument(who + "has no joints");
  if (frame_count <= 0) throw std::invalid_argument(who + "has no frames");
  for (size_t j = 0; j < parents.size(); ++j) {
    if (parents[j] < -1 || parents[j] >= static_cast<int>(j))
      throw std::invalid_argument(who + "joint " + std::to_string(j) + " has parent " +
                                  std::to_string(parents[j]) + ", expected -1 or an earlier joint");
  }
  const size_t expected = static_cast<size_t>(frame_count) * parents.size() * 3;
  if (positions.size() != expected)
    throw std::invalid_argument(who + "has " + std::to_string(positions.size()) + " coordinates, expected " +
                                std::to_string(expected) + " (frames x joints x 3)");
  for (size_t i = 0; i < positions.size(); ++i) {
    if (!std::isfinite(positions[i]))
      throw std::invalid_argument(who + "coordinate " + std::to_string(i) + " is not finite");
  }
  for (const int joint : contact_joints) {
    if (joint < 0 || joint >= jointCount())
      throw std::invalid_argument(who + "contact joint " + std::to_string(joint) + " is out of range");
  }
  const size_t expected_contacts = contact_joints.empty() ? 0 : static_cast<size_t>(frame_count) * contact_joints.size();
  if (contacts.size() != expected_contacts)
    throw std::invalid_argument(who + "has " + std::to_string(contacts.size()) + " contact flags, expected " +
                                std::to_string(expected_contacts) + " (frames x contact joints)");
}

}  // namespace motionstyle
