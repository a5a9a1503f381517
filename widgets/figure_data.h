#pragma once
// FigureData: what the viewport draws for one character, as plain data (no VTK, no core types), so the
// app can build it from any source (a loaded clip, a network's output, an IK result).
//
// Space: world positions in CENTIMETRES, Y-up, floor near y = 0 (the team's normalised convention).
// The viewport does not rescale or rotate; it only moves each figure sideways for its layout.

#include <QColor>
#include <QString>

#include <cstdint>
#include <vector>

namespace motionstyle {

// The paper's colour code: content green, style red, output blue; the raw (pre-IK) output grey.
enum class FigureRole : std::uint8_t { Content, Style, Output, RawOutput };

QColor figureColor(FigureRole role);
QString figureRoleName(FigureRole role);  // "Content", "Style", "Output", "Raw output"

struct FigureData {
  QString name;  // shown in the viewport's legend, e.g. the clip's file name
  FigureRole role = FigureRole::Content;

  // Topology: parents[j] is the parent of joint j, -1 for a root. Parents come before children.
  std::vector<int> parents;

  // World positions, cm, Y-up: frame f, joint j, axis a at positions[(f * jointCount() + j) * 3 + a].
  int frame_count = 0;
  std::vector<double> positions;

  // Optional foot contacts: contact_joints lists the joints whose contact is given (e.g. the two
  // ankles); contacts[f * contact_joints.size() + k] != 0 when contact_joints[k] touches the floor in
  // frame f. Empty vectors mean "no contact information".
  std::vector<int> contact_joints;
  std::vector<std::uint8_t> contacts;

  int jointCount() const { return static_cast<int>(parents.size()); }
  double x(int frame, int joint) const { return positions[index(frame, joint)]; }
  double y(int frame, int joint) const { return positions[index(frame, joint) + 1]; }
  double z(int frame, int joint) const { return positions[index(frame, joint) + 2]; }
  bool inContact(int frame, int contact) const {
    return contacts[static_cast<size_t>(frame) * contact_joints.size() + static_cast<size_t>(contact)] != 0;
  }

  // Throws std::invalid_argument naming the first problem: no joints or frames, a parent index not
  // before its child, a positions size other than frames * joints * 3, a non-finite coordinate, a
  // contact joint out of range or a contacts size other than frames * contact_joints.
  void validate() const;

 private:
  size_t index(int frame, int joint) const {
    return (static_cast<size_t>(frame) * parents.size() + static_cast<size_t>(joint)) * 3;
  }
};

}  // namespace motionstyle
