#pragma once
// Skeleton: the editable description of a rig exactly as a BVH file states it.
//
// Joints are stored parents-before-children, in the file's depth-first order, so a single forward pass
// over `joints` visits every parent before its children (forward kinematics relies on this).
// End Sites are kept as joints with `end_site == true` and no channels, so that a round trip through
// the BVH writer reproduces the hierarchy, and so that mappings can name a chain's tip (e.g. a hand end).
//
// Units: offsets are in the file's own length unit; nothing here converts them. Up axis: as in the file.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace motionstyle {

enum class ChannelType : std::uint8_t { Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation };

constexpr bool isRotation(ChannelType c) { return c >= ChannelType::Xrotation; }
constexpr int axisOf(ChannelType c) { return static_cast<int>(c) % 3; }  // 0 = X, 1 = Y, 2 = Z
std::string_view channelName(ChannelType c);                              // "Xposition", ...

struct Joint {
  std::string name;                          // unique among non-end-site joints
  int parent = -1;                           // index into Skeleton::joints; -1 only for the root
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // rest translation from the parent, file units
  std::vector<ChannelType> channels;         // in file order; empty for End Sites
  bool end_site = false;
};

class Skeleton {
 public:
  std::vector<Joint> joints;

  int jointCount() const { return static_cast<int>(joints.size()); }
  // Total number of animation channels (the width of one BVH frame line).
  int channelCount() const;
  // Index of the first channel of joint j within a frame line (End Sites: the next joint's start).
  std::vector<int> channelOffsets() const;
  // Index of the joint with this name, or -1. End Sites are named "<parent>_End" unless they
  // carry a name of their own.
  int find(std::string_view name) const;
  std::vector<int> children(int joint) const;

  // Throws std::invalid_argument describing the first inconsistency: no joints, a root that is not
  // joint 0, a parent index not before its child, duplicate names, an End Site with channels or
  // children, a channel list with repeats, more than 3 rotation or 3 position channels, a non-finite
  // offset.
  void validate() const;
};

}  // namespace motionstyle
