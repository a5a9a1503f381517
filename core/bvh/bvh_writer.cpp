#include "bvh/bvh_writer.h"

#include <charconv>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>
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

// Source column of each written column, in the order appendHierarchy wrote the joints (identity for
// a skeleton already in depth-first order).
std::vector<Eigen::Index> writtenColumns(const Skeleton& skeleton, const std::vector<int>& order) {
  const std::vector<int> offsets = skeleton.channelOffsets();
  std::vector<Eigen::Index> columns;
  columns.reserve(static_cast<std::size_t>(skeleton.channelCount()));
  for (int joint : order) {
    const auto j = static_cast<std::size_t>(joint);
    for (std::size_t c = 0; c < skeleton.joints[j].channels.size(); ++c)
      columns.push_back(static_cast<Eigen::Index>(offsets[j]) + static_cast<Eigen::Index>(c));
  }
  return columns;
}

// Text is handed to the stream in pieces of about this size: few stream calls, little memory.
constexpr std::size_t kFlushBytes = std::size_t{1} << 16;

}  // namespace

BvhStreamWriter::BvhStreamWriter(std::ostream& out, const Skeleton& skeleton, int frames, double frame_time)
    : out_(out), frames_(frames) {
  skeleton.validate();
  if (!(std::isfinite(frame_time) && frame_time > 0.0))
    throw std::invalid_argument("frame time must be positive and finite, got " + std::to_string(frame_time));
  if (frames < 0) throw std::invalid_argument("cannot write BVH: " + std::to_string(frames) + " frames announced");
  checkWritable(skeleton);

  text_.reserve(kFlushBytes + 4096);
  columns_ = writtenColumns(skeleton, appendHierarchy(text_, skeleton));
  text_ += "MOTION\nFrames: " + std::to_string(frames) + "\nFrame Time: ";
  appendNumber(text_, frame_time);
  text_ += '\n';
  flush();
}

void BvhStreamWriter::writeFrames(const Eigen::Ref<const MatrixRowMajor>& values_block) {
  if (values_block.cols() != static_cast<Eigen::Index>(columns_.size()))
    throw std::invalid_argument("cannot write BVH: a block of " + std::to_string(values_block.cols()) +
                                " channels per frame, the skeleton has " + std::to_string(columns_.size()));
  if (!values_block.allFinite()) throw std::invalid_argument("cannot write BVH: a block holds a non-finite channel value");
  if (values_block.rows() > static_cast<Eigen::Index>(frames_ - written_))
    throw std::invalid_argument("cannot write BVH: " + std::to_string(values_block.rows()) + " more frames after " +
                                std::to_string(written_) + ", the header announced " + std::to_string(frames_));
  for (Eigen::Index frame = 0; frame < values_block.rows(); ++frame) {
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (c > 0) text_ += ' ';
      appendNumber(text_, values_block(frame, columns_[c]));
    }
    text_ += '\n';
    if (text_.size() >= kFlushBytes) flush();
  }
  written_ += static_cast<int>(values_block.rows());
  flush();
}

void BvhStreamWriter::finish() const {
  if (written_ != frames_)
    throw std::invalid_argument("cannot finish BVH: " + std::to_string(written_) + " frames written, the header announced " +
                                std::to_string(frames_));
}

void BvhStreamWriter::flush() {
  out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
  text_.clear();
}

std::string formatBvh(const Motion& motion) {
  motion.validate();
  std::string text;
  // ~9 characters per value is typical of mocap; a good guess saves the reallocations.
  text.reserve(4096 + static_cast<std::size_t>(motion.values.size()) * 9);
  std::ostringstream stream(std::move(text));  // writes into the reserved capacity
  BvhStreamWriter writer(stream, motion.skeleton, motion.frameCount(), motion.frame_time);
  writer.writeFrames(motion.values);
  writer.finish();
  return std::move(stream).str();
}

void writeBvh(const Motion& motion, const std::filesystem::path& file) {
  motion.validate();  // before touching the disk: a bad motion writes nothing
  checkWritable(motion.skeleton);
  writeFileAtomically(file, [&](std::ostream& out) {
    BvhStreamWriter writer(out, motion.skeleton, motion.frameCount(), motion.frame_time);
    writer.writeFrames(motion.values);
    writer.finish();
  });
}

}  // namespace motionstyle
