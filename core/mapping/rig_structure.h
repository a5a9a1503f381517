#pragma once
// RigStructure: the questions the automatic mapper asks about a rig's hierarchy and joint names
// (ancestors, nearest named descendant, main chain, rest-pose distances). Internal to core/mapping.

#include <Eigen/Core>
#include <span>
#include <string_view>
#include <vector>

#include "mapping/joint_names.h"
#include "motion/skeleton.h"

namespace motionstyle::mapping_detail {

// Alias lists name joints in display form ("LowerLeg"); names are compared lower-cased to the
// readings of joint_names.h.
using Aliases = std::span<const std::string_view>;

class RigStructure {
 public:
  // `skeleton` must be valid (Skeleton::validate) and outlive this object.
  explicit RigStructure(const Skeleton& skeleton);

  const Skeleton& skeleton() const { return skeleton_; }
  int parent(int joint) const { return skeleton_.joints[static_cast<size_t>(joint)].parent; }
  bool isEndSite(int joint) const { return skeleton_.joints[static_cast<size_t>(joint)].end_site; }
  const std::string& name(int joint) const { return skeleton_.joints[static_cast<size_t>(joint)].name; }
  const std::vector<int>& children(int joint) const { return children_[static_cast<size_t>(joint)]; }

  // True when `ancestor` is a proper ancestor of `joint`.
  bool isAncestor(int ancestor, int joint) const;
  // Lowest common ancestor of the joints (the joint itself counts as its own ancestor); -1 if empty.
  int commonAncestor(std::span<const int> joints) const;
  // The joints strictly between `ancestor` and `joint`, top-down.
  std::vector<int> pathBetween(int ancestor, int joint) const;

  // Rank of the best alias the joint's name matches on `side` (0 = first alias), or -1. With
  // accept_unsided, a name without a side marker matches as well.
  int aliasRank(int joint, BodySide side, Aliases aliases, bool accept_unsided) const;
  // Among all non-End-Site joints named like an alias on `side`: the best alias, then the shallowest.
  int findByName(BodySide side, Aliases aliases) const;
  // The nearest proper ancestor named like an alias on `side` (or without a side), or -1.
  int nearestNamedAncestor(int joint, BodySide side, Aliases aliases) const;
  // The shallowest proper descendant named like an alias on `side` (or without a side), or -1.
  int nearestNamedDescendant(int joint, BodySide side, Aliases aliases, bool include_end_sites) const;
  // The non-End-Site child with the deepest subtree (first in file order on ties), or -1.
  int mainChild(int joint) const;
  // The first End Site child, or -1.
  int endSiteChild(int joint) const;
  // Number of levels below the joint (0 for a leaf), End Sites included.
  int subtreeHeight(int joint) const { return height_[static_cast<size_t>(joint)]; }

  // Rest-pose distance between two joints, in file units.
  double restDistance(int a, int b) const;
  // True when two joints are at the same rest position (up to 1e-4 of the rig's typical bone length).
  bool samePlace(int a, int b) const { return restDistance(a, b) <= coincidence_tolerance_; }

  // The joint's name, lower-cased without namespace or separators (for "contains" tests).
  const std::string& flatName(int joint) const { return flat_names_[static_cast<size_t>(joint)]; }

 private:
  const Skeleton& skeleton_;
  std::vector<std::vector<int>> children_;
  std::vector<int> depth_;
  std::vector<int> height_;
  std::vector<Eigen::Vector3d> rest_positions_;
  std::vector<std::vector<JointNameReading>> readings_;
  std::vector<std::string> flat_names_;
  double coincidence_tolerance_ = 0.0;
};

}  // namespace motionstyle::mapping_detail
