#include "bvh/bvh_hierarchy.h"

#include <cmath>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_text.h"
#include "common/errors.h"

namespace motionstyle::bvh_detail {
namespace {

constexpr std::string_view kChannelList = "Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation";

std::optional<ChannelType> channelFromName(std::string_view name) {
  static constexpr ChannelType kAll[] = {ChannelType::Xposition, ChannelType::Yposition, ChannelType::Zposition,
                                         ChannelType::Xrotation, ChannelType::Yrotation, ChannelType::Zrotation};
  for (ChannelType type : kAll)
    if (equalsIgnoreCase(name, channelName(type))) return type;
  return std::nullopt;
}

class HierarchyParser {
 public:
  HierarchyParser(LineCursor& cursor, const std::string& source) : cursor_(cursor), source_(source) {}

  Skeleton parse() {
    if (!nextLine()) {
      // A byte order mark is not whitespace: a text holding one is not empty, only truncated.
      if (!cursor_.skippedByteOrderMark()) {
        line_number_ = 1;
        fail("expected HIERARCHY, got an empty file");
      }
      fail("expected HIERARCHY, got the end of the file (truncated hierarchy)");
    }
    if (!(words_.size() == 1 && equalsIgnoreCase(words_[0], "HIERARCHY")))
      fail("expected HIERARCHY as the first line, got " + excerpt(line_));
    readLine("ROOT <name>");
    if (words_.empty() || !equalsIgnoreCase(words_[0], "ROOT")) fail("expected ROOT <name>, got " + excerpt(line_));
    openJoint(/*end_site=*/false);

    // One body line at a time for the innermost open joint: no recursion, so nesting costs no stack.
    while (!open_.empty()) {
      const OpenJoint top = open_.back();
      const bool in_end_site = skeleton_.joints[static_cast<std::size_t>(top.index)].end_site;
      if (!nextLine()) failExpectingBody(top, "the end of the file (truncated hierarchy)");
      if (words_.size() == 1 && words_[0] == "}") {
        open_.pop_back();
      } else if (!in_end_site && !words_.empty() && equalsIgnoreCase(words_[0], "JOINT")) {
        openJoint(/*end_site=*/false);
      } else if (!in_end_site && isEndSite()) {
        openJoint(/*end_site=*/true);
      } else {
        failExpectingBody(top, excerpt(line_));
      }
    }
    nameEndSites();
    return std::move(skeleton_);
  }

 private:
  struct OpenJoint {
    int index;
    int line;
  };

  [[noreturn]] void fail(const std::string& detail) const { throw InputError(source_, line_number_, detail); }

  // Next non-blank line, trimmed and split into words; false at the end of the text (the line number
  // then names the last line).
  bool nextLine() {
    if (!cursor_.nextNonBlank(line_, line_number_)) {
      line_number_ = cursor_.lastLine();
      return false;
    }
    line_ = trim(line_);
    splitWords(line_, words_);
    return true;
  }

  // nextLine, failing at the end of the text; `expected` names what it interrupts.
  void readLine(const std::string& expected) {
    if (!nextLine()) fail("expected " + expected + ", got the end of the file (truncated hierarchy)");
  }

  // Built only on failure: joint names can be long, and this runs for every line of a hierarchy.
  [[noreturn]] void failExpectingBody(const OpenJoint& open, const std::string& got) const {
    const Joint& joint = skeleton_.joints[static_cast<std::size_t>(open.index)];
    const std::string opened = " (opened on line " + std::to_string(open.line) + ")";
    if (joint.end_site)
      fail("expected '}' closing the End Site of " + excerpt(skeleton_.joints[static_cast<std::size_t>(joint.parent)].name) +
           opened + ", got " + got);
    fail("expected JOINT, End Site or '}' closing joint " + excerpt(joint.name) + opened + ", got " + got);
  }

  bool isEndSite() const {
    return words_.size() == 2 && equalsIgnoreCase(words_[0], "End") && equalsIgnoreCase(words_[1], "Site");
  }

  // The current line is "ROOT name", "JOINT name" or "End Site": reads its '{', OFFSET and CHANNELS.
  void openJoint(bool end_site) {
    if (skeleton_.jointCount() >= kBvhMaxJoints)
      fail("expected at most " + std::to_string(kBvhMaxJoints) + " joints (End Sites included), got more");
    if (static_cast<int>(open_.size()) >= kBvhMaxDepth)
      fail("expected joints nested at most " + std::to_string(kBvhMaxDepth) + " deep, got deeper");

    Joint joint;
    joint.end_site = end_site;
    joint.parent = open_.empty() ? -1 : open_.back().index;
    const int header_line = line_number_;
    std::string label = "End Site";
    if (!end_site) {
      joint.name = std::string(jointName());
      label = std::string(words_[0]) + " " + excerpt(joint.name);
      const auto [previous, inserted] = name_lines_.try_emplace(joint.name, line_number_);
      if (!inserted)
        fail("expected a unique joint name, got a second " + excerpt(joint.name) + " (first declared on line " +
             std::to_string(previous->second) + ")");
    }

    readLine("'{' after " + label);
    if (line_ != "{") fail("expected '{' after " + label + " (line " + std::to_string(header_line) + "), got " + excerpt(line_));

    readLine("OFFSET x y z of " + label);
    if (words_.empty() || !equalsIgnoreCase(words_[0], "OFFSET"))
      fail("expected OFFSET x y z of " + label + ", got " + excerpt(line_));
    if (words_.size() != 4)
      fail("expected 3 numbers after OFFSET, got " + std::to_string(words_.size() - 1) + " in " + excerpt(line_));
    for (int axis = 0; axis < 3; ++axis) joint.offset[axis] = number(words_[static_cast<std::size_t>(axis) + 1], "OFFSET");

    if (!end_site) readChannels(joint, label);
    skeleton_.joints.push_back(std::move(joint));
    open_.push_back({skeleton_.jointCount() - 1, header_line});
  }

  std::string_view jointName() const {
    std::string_view name = trim(line_.substr(words_[0].size()));
    if (name.empty()) fail("expected a name after " + std::string(words_[0]) + ", got nothing");
    for (char c : name) {
      const auto byte = static_cast<unsigned char>(c);
      if (byte < 0x20 || byte == 0x7F || c == '{' || c == '}')
        fail("expected a joint name (no braces or control characters), got " + excerpt(name));
    }
    return name;
  }

  void readChannels(Joint& joint, const std::string& label) {
    readLine("CHANNELS of " + label);
    if (words_.empty() || !equalsIgnoreCase(words_[0], "CHANNELS"))
      fail("expected CHANNELS <count> <names...> of " + label + ", got " + excerpt(line_));
    long long count = 0;
    if (words_.size() < 2 || !parseCount(words_[1], 1'000'000, count))
      fail("expected a channel count after CHANNELS, got " + excerpt(words_.size() < 2 ? std::string_view() : words_[1]));
    const std::size_t listed = words_.size() - 2;
    if (static_cast<std::size_t>(count) != listed)
      fail("expected " + std::to_string(count) + " channel names as CHANNELS states, got " + std::to_string(listed));
    if (count != 3 && count != 6)
      fail("expected 3 or 6 channels on " + label + ", got " + std::to_string(count) +
           " (joints without channels or with partial channel sets are not supported)");
    int rotations = 0;
    for (std::size_t i = 2; i < words_.size(); ++i) {
      const std::optional<ChannelType> type = channelFromName(words_[i]);
      if (!type) fail("expected a channel name (" + std::string(kChannelList) + "), got " + excerpt(words_[i]));
      for (ChannelType seen : joint.channels)
        if (seen == *type) fail("expected distinct channels on " + label + ", got " + excerpt(words_[i]) + " twice");
      rotations += isRotation(*type) ? 1 : 0;
      joint.channels.push_back(*type);
    }
    // 3 distinct channels mixing rotations and positions (e.g. Xposition Yrotation Zrotation).
    if (rotations != 0 && rotations != 3)
      fail("expected the 3 rotation channels together (or none) on " + label + ", got " + std::to_string(rotations));
  }

  double number(std::string_view word, std::string_view context) const {
    double value = 0.0;
    switch (parseNumber(word, value)) {
      case NumberStatus::Ok:
        if (!(std::abs(value) <= kBvhMaxMagnitude))
          fail("expected a value within +-" + formatBound(kBvhMaxMagnitude) + " in " + std::string(context) + ", got " +
               excerpt(word) + " (no skeleton is that large)");
        return value;
      case NumberStatus::NotFinite: fail("expected a finite number in " + std::string(context) + ", got " + excerpt(word));
      case NumberStatus::OutOfRange:
        fail("expected a number within double range in " + std::string(context) + ", got " + excerpt(word));
      case NumberStatus::NotANumber: break;
    }
    fail("expected a number in " + std::string(context) + ", got " + excerpt(word));
  }

  // End Sites carry no name in the file: "<parent>_End", made unique against every joint name.
  void nameEndSites() {
    std::unordered_set<std::string> taken;
    for (const Joint& joint : skeleton_.joints)
      if (!joint.end_site) taken.insert(joint.name);
    std::unordered_map<std::string, int> next_suffix;  // keeps many End Sites on one joint linear
    for (Joint& joint : skeleton_.joints) {
      if (!joint.end_site) continue;
      const std::string base = skeleton_.joints[static_cast<std::size_t>(joint.parent)].name + "_End";
      std::string name = base;
      int& suffix = next_suffix.try_emplace(base, 2).first->second;
      while (taken.count(name) != 0) name = base + std::to_string(suffix++);
      taken.insert(name);
      joint.name = std::move(name);
    }
  }

  LineCursor& cursor_;
  const std::string& source_;
  Skeleton skeleton_;
  std::vector<OpenJoint> open_;
  std::unordered_map<std::string, int> name_lines_;
  std::string_view line_;
  int line_number_ = 0;
  std::vector<std::string_view> words_;
};

}  // namespace

Skeleton parseHierarchy(LineCursor& cursor, const std::string& source) {
  return HierarchyParser(cursor, source).parse();
}

}  // namespace motionstyle::bvh_detail
