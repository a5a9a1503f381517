#include "bvh/bvh_writer.h"

#include <charconv>
#include <stdexcept>
#include <vector>

#include "common/atomic_file.h"

namespace motionstyle {
namespace {

// Shortest round-trip decimal in fixed notation (see bvh_writer.h for why).
void appendNumber(std::string& out, double value) {
  char buffer[512];  // the longest fixed double (5e-324, 1.8e308) needs ~330 characters
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed);
  if (result.ec != std::errc()) result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void checkWritable(const Skeleton& skeleton) {
  for (const Joint& joint : skeleton.joints) {
    const std::string label = "joint '" + joint.name + "'";
    if (!joint.end_site) {
      int rotations = 0;
      for (ChannelType channel : joint.channels) rotations += isRotation(channel) ? 1 : 0;
      const auto count = joint.channels.size();
      if ((count != 3 && count != 6) || (rotations != 0 && rotations != 3))
        throw std::invalid_argument("cannot write BVH: " + label + " has " + std::to_string(count) + " channels (" +
                                    std::to_string(rotations) + " rotations); BVH joints need 3 or 6: three rotations and/or three positions");
    }
    const std::string& name = joint.name;
    const bool padded = name.front() == ' ' || name.back() == ' ';
    bool unprintable = false;
    for (char c : name) {
      const auto byte = static_cast<unsigned char>(c);
      unprintable = unprintable || byte < 0x20 || byte == 0x7F || c == '{' || c == '}';
    }
    if (!joint.end_site && (padded || unprintable))
      throw std::invalid_argument("cannot write BVH: " + label + " has a name with edge spaces, braces or control characters");
  }
}

struct ChildLists {
  std::vector<int> first;  // index into `children` where joint j's children start
  std::vector<int> children;
};

ChildLists childLists(const Skeleton& skeleton) {
  const std::size_t n = skeleton.joints.size();
  ChildLists lists;
  lists.first.assign(n + 1, 0);
  for (std::size_t j = 1; j < n; ++j) ++lists.first[static_cast<std::size_t>(skeleton.joints[j].parent) + 1];
  for (std::size_t j = 0; j < n; ++j) lists.first[j + 1] += lists.first[j];
  lists.children.resize(n > 0 ? n - 1 : 0);
  std::vector<int> fill(lists.first.begin(), lists.first.end() - 1);
  for (std::size_t j = 1; j < n; ++j)
    lists.children[static_cast<std::size_t>(fill[static_cast<std::size_t>(skeleton.joints[j].parent)]++)] = static_cast<int>(j);
  return lists;
}

// Writes the hierarchy depth-first without recursion; returns the joints in the order written.
std::vector<int> appendHierarchy(std::string& out, const Skeleton& skeleton) {
  const ChildLists lists = childLists(skeleton);
  std::vector<int> order;
  order.reserve(skeleton.joints.size());
  struct Open {
    int joint;
    int next_child;  // position in lists.children
  };
  std::vector<Open> open;

  out += "HIERARCHY\n";
  auto start = [&](int index) {
    const Joint& joint = skeleton.joints[static_cast<std::size_t>(index)];
    const std::string indent(open.size(), '\t');
    out += indent;
    out += joint.end_site ? "End Site" : (joint.parent < 0 ? "ROOT " : "JOINT ") + joint.name;
    out += "\n" + indent + "{\n" + indent + "\tOFFSET";
    for (int axis = 0; axis < 3; ++axis) {
      out += ' ';
      appendNumber(out, joint.offset[axis]);
    }
    out += '\n';
    if (!joint.end_site) {
      out += indent + "\tCHANNELS " + std::to_string(joint.channels.size());
      for (ChannelType channel : joint.channels) (out += ' ') += channelName(channel);
      out += '\n';
    }
    order.push_back(index);
    open.push_back({index, lists.first[static_cast<std::size_t>(index)]});
  };

  start(0);
  while (!open.empty()) {
    Open& top = open.back();
    if (top.next_child < lists.first[static_cast<std::size_t>(top.joint) + 1]) {
      start(lists.children[static_cast<std::size_t>(top.next_child++)]);
    } else {
      open.pop_back();
      out += std::string(open.size(), '\t') + "}\n";
    }
  }
  return order;
}

}  // namespace

std::string formatBvh(const Motion& motion) {
  motion.validate();
  const Skeleton& skeleton = motion.skeleton;
  checkWritable(skeleton);

  std::string out;
  // ~9 characters per value is typical of mocap; a good guess saves the reallocations.
  out.reserve(4096 + static_cast<std::size_t>(motion.values.size()) * 9);
  const std::vector<int> order = appendHierarchy(out, skeleton);

  // Source column of each written column (identity for a skeleton already in depth-first order).
  const std::vector<int> offsets = skeleton.channelOffsets();
  std::vector<Eigen::Index> columns;
  columns.reserve(static_cast<std::size_t>(skeleton.channelCount()));
  for (int joint : order) {
    const auto j = static_cast<std::size_t>(joint);
    for (std::size_t c = 0; c < skeleton.joints[j].channels.size(); ++c)
      columns.push_back(static_cast<Eigen::Index>(offsets[j]) + static_cast<Eigen::Index>(c));
  }

  out += "MOTION\nFrames: " + std::to_string(motion.frameCount()) + "\nFrame Time: ";
  appendNumber(out, motion.frame_time);
  out += '\n';
  for (Eigen::Index frame = 0; frame < motion.values.rows(); ++frame) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (c > 0) out += ' ';
      appendNumber(out, motion.values(frame, columns[c]));
    }
    out += '\n';
  }
  return out;
}

void writeBvh(const Motion& motion, const std::filesystem::path& file) {
  const std::string text = formatBvh(motion);  // before touching the disk: a bad motion writes nothing
  writeFileAtomically(file, text);
}

}  // namespace motionstyle
