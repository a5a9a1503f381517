#include "mapping/rig_structure.h"

#include <algorithm>
#include <cctype>
#include <deque>
#include <string>

namespace motionstyle::mapping_detail {

namespace {

bool equalsLowered(std::string_view lowered, std::string_view alias) {
  if (lowered.size() != alias.size()) return false;
  for (size_t i = 0; i < alias.size(); ++i)
    if (lowered[i] != static_cast<char>(std::tolower(static_cast<unsigned char>(alias[i])))) return false;
  return true;
}

}  // namespace

RigStructure::RigStructure(const Skeleton& skeleton) : skeleton_(skeleton) {
  const size_t count = skeleton.joints.size();
  children_.resize(count);
  depth_.assign(count, 0);
  height_.assign(count, 0);
  rest_positions_.resize(count);
  readings_.resize(count);
  flat_names_.resize(count);
  // Parents precede children (Skeleton::validate), so one forward pass sees every parent first.
  for (size_t j = 0; j < count; ++j) {
    const Joint& joint = skeleton.joints[j];
    rest_positions_[j] = joint.offset;
    if (joint.parent >= 0) {
      const auto p = static_cast<size_t>(joint.parent);
      children_[p].push_back(static_cast<int>(j));
      depth_[j] = depth_[p] + 1;
      rest_positions_[j] += rest_positions_[p];
    }
    readings_[j] = readJointName(joint.name);
    flat_names_[j] = flattenJointName(joint.name);
  }
  for (size_t j = count; j-- > 1;) {
    const auto p = static_cast<size_t>(skeleton.joints[j].parent);
    height_[p] = std::max(height_[p], height_[j] + 1);
  }
  // "Zero offset" is relative to the rig's scale: files come in metres, centimetres, inches or CMU units.
  std::vector<double> lengths;
  for (size_t j = 1; j < count; ++j) {
    const double length = skeleton.joints[j].offset.norm();
    if (length > 0.0) lengths.push_back(length);
  }
  if (!lengths.empty()) {
    const auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
    std::nth_element(lengths.begin(), middle, lengths.end());
    coincidence_tolerance_ = 1e-4 * *middle;
  }
}

bool RigStructure::isAncestor(int ancestor, int joint) const {
  if (ancestor < 0 || joint < 0) return false;
  for (int j = parent(joint); j >= 0; j = parent(j))
    if (j == ancestor) return true;
  return false;
}

int RigStructure::commonAncestor(std::span<const int> joints) const {
  if (joints.empty()) return -1;
  int common = joints[0];
  for (int joint : joints.subspan(1)) {
    while (common >= 0 && common != joint && !isAncestor(common, joint)) common = parent(common);
    if (common < 0) return -1;
  }
  return common;
}

std::vector<int> RigStructure::pathBetween(int ancestor, int joint) const {
  std::vector<int> path;
  for (int j = parent(joint); j >= 0 && j != ancestor; j = parent(j)) path.push_back(j);
  std::reverse(path.begin(), path.end());
  return path;
}

int RigStructure::aliasRank(int joint, BodySide side, Aliases aliases, bool accept_unsided) const {
  for (const JointNameReading& reading : readings_[static_cast<size_t>(joint)]) {
    if (reading.side != side && !(accept_unsided && reading.side == BodySide::Center)) continue;
    for (size_t a = 0; a < aliases.size(); ++a)
      if (equalsLowered(reading.base, aliases[a])) return static_cast<int>(a);
  }
  return -1;
}

int RigStructure::findByName(BodySide side, Aliases aliases) const {
  int best = -1;
  int best_rank = 0;
  for (int j = 0; j < skeleton_.jointCount(); ++j) {
    if (isEndSite(j)) continue;
    const int rank = aliasRank(j, side, aliases, false);
    if (rank < 0) continue;
    if (best < 0 || rank < best_rank || (rank == best_rank && depth_[static_cast<size_t>(j)] < depth_[static_cast<size_t>(best)])) {
      best = j;
      best_rank = rank;
    }
  }
  return best;
}

int RigStructure::nearestNamedAncestor(int joint, BodySide side, Aliases aliases) const {
  for (int j = parent(joint); j >= 0; j = parent(j))
    if (aliasRank(j, side, aliases, true) >= 0) return j;
  return -1;
}

int RigStructure::nearestNamedDescendant(int joint, BodySide side, Aliases aliases, bool include_end_sites) const {
  // Breadth first, so the shallowest match wins; file order breaks ties.
  std::deque<int> queue(children(joint).begin(), children(joint).end());
  while (!queue.empty()) {
    const int j = queue.front();
    queue.pop_front();
    if ((include_end_sites || !isEndSite(j)) && aliasRank(j, side, aliases, true) >= 0) return j;
    for (int child : children(j)) queue.push_back(child);
  }
  return -1;
}

int RigStructure::mainChild(int joint) const {
  int best = -1;
  for (int child : children(joint)) {
    if (isEndSite(child)) continue;
    if (best < 0 || subtreeHeight(child) > subtreeHeight(best)) best = child;
  }
  return best;
}

int RigStructure::endSiteChild(int joint) const {
  for (int child : children(joint))
    if (isEndSite(child)) return child;
  return -1;
}

double RigStructure::restDistance(int a, int b) const {
  return (rest_positions_[static_cast<size_t>(a)] - rest_positions_[static_cast<size_t>(b)]).norm();
}

}  // namespace motionstyle::mapping_detail
