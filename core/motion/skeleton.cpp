#include "motion/skeleton.h"

#include <stdexcept>
#include <unordered_set>

namespace motionstyle {

std::string_view channelName(ChannelType c) {
  switch (c) {
    case ChannelType::Xposition: return "Xposition";
    case ChannelType::Yposition: return "Yposition";
    case ChannelType::Zposition: return "Zposition";
    case ChannelType::Xrotation: return "Xrotation";
    case ChannelType::Yrotation: return "Yrotation";
    case ChannelType::Zrotation: return "Zrotation";
  }
  return "?";
}

int Skeleton::channelCount() const {
  int count = 0;
  for (const Joint& joint : joints) count += static_cast<int>(joint.channels.size());
  return count;
}

std::vector<int> Skeleton::channelOffsets() const {
  std::vector<int> offsets(joints.size());
  int next = 0;
  for (size_t j = 0; j < joints.size(); ++j) {
    offsets[j] = next;
    next += static_cast<int>(joints[j].channels.size());
  }
  return offsets;
}

int Skeleton::find(std::string_view name) const {
  for (size_t j = 0; j < joints.size(); ++j)
    if (joints[j].name == name) return static_cast<int>(j);
  return -1;
}

std::vector<int> Skeleton::children(int joint) const {
  std::vector<int> result;
  for (size_t j = 0; j < joints.size(); ++j)
    if (joints[j].parent == joint) result.push_back(static_cast<int>(j));
  return result;
}

void Skeleton::validate() const {
  if (joints.empty()) throw std::invalid_argument("skeleton has no joints");
  if (joints[0].parent != -1) throw std::invalid_argument("joint 0 must be the root (parent -1)");
  std::unordered_set<std::string> names;
  for (size_t j = 0; j < joints.size(); ++j) {
    const Joint& joint = joints[j];
    const std::string label = "joint '" + joint.name + "'";
    if (j > 0 && (joint.parent < 0 || joint.parent >= static_cast<int>(j)))
      throw std::invalid_argument(label + " has a parent that does not precede it");
    if (j > 0 && joints[static_cast<size_t>(joint.parent)].end_site)
      throw std::invalid_argument(label + " is the child of an End Site");
    if (joint.name.empty()) throw std::invalid_argument("joint " + std::to_string(j) + " has no name");
    if (!names.insert(joint.name).second) throw std::invalid_argument("duplicate joint name '" + joint.name + "'");
    if (!joint.offset.allFinite()) throw std::invalid_argument(label + " has a non-finite offset");
    if (joint.end_site && !joint.channels.empty()) throw std::invalid_argument(label + " is an End Site with channels");
    bool seen[6] = {false, false, false, false, false, false};
    for (ChannelType c : joint.channels) {
      const auto index = static_cast<size_t>(c);
      if (index >= 6) throw std::invalid_argument(label + " has an unknown channel");
      if (seen[index]) throw std::invalid_argument(label + " repeats channel " + std::string(channelName(c)));
      seen[index] = true;
    }
  }
}

}  // namespace motionstyle
