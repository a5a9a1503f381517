#pragma once
// Builders shared by the motion tests: small hand-made skeletons and random (fixed-seed) motions.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "motion/motion.h"
#include "motion/skeleton.h"

namespace motionstyle::test {

using C = ChannelType;

inline Joint makeJoint(std::string name, int parent, Eigen::Vector3d offset, std::vector<ChannelType> channels) {
  Joint joint;
  joint.name = std::move(name);
  joint.parent = parent;
  joint.offset = offset;
  joint.channels = std::move(channels);
  return joint;
}

inline Joint makeEndSite(std::string name, int parent, Eigen::Vector3d offset) {
  Joint joint = makeJoint(std::move(name), parent, offset, {});
  joint.end_site = true;
  return joint;
}

// A tree covering every channel layout kinematics must handle: a 6-channel root, all six Euler orders,
// one- and two-axis joints, a joint with only some position channels, a joint with no channels at all,
// a 6-channel non-root joint, and End Sites.
inline Skeleton mixedSkeleton() {
  Skeleton s;
  s.joints.push_back(makeJoint("Root", -1, {0, 0, 0}, {C::Xposition, C::Yposition, C::Zposition, C::Zrotation, C::Yrotation, C::Xrotation}));
  s.joints.push_back(makeJoint("A_XYZ", 0, {0, 10, 0}, {C::Xrotation, C::Yrotation, C::Zrotation}));
  s.joints.push_back(makeJoint("B_XZY", 1, {1, 8, 0}, {C::Xrotation, C::Zrotation, C::Yrotation}));
  s.joints.push_back(makeJoint("C_YXZ", 2, {0, 7, 2}, {C::Yrotation, C::Xrotation, C::Zrotation}));
  s.joints.push_back(makeEndSite("C_YXZ_End", 3, {0, 3, 0}));
  s.joints.push_back(makeJoint("D_YZX", 0, {5, -2, 0}, {C::Yrotation, C::Zrotation, C::Xrotation}));
  s.joints.push_back(makeJoint("E_ZXY", 5, {0, -9, 1}, {C::Zrotation, C::Xrotation, C::Yrotation}));
  s.joints.push_back(makeJoint("F_ZYX", 6, {0, -9, -1}, {C::Zrotation, C::Yrotation, C::Xrotation}));
  s.joints.push_back(makeJoint("G_OneAxis", 7, {0, -1, 3}, {C::Xrotation}));
  s.joints.push_back(makeEndSite("G_OneAxis_End", 8, {0, 0, 2}));
  s.joints.push_back(makeJoint("H_TwoAxes", 0, {-5, -2, 0}, {C::Zrotation, C::Xrotation}));
  s.joints.push_back(makeJoint("I_SixChannels", 10, {0, -9, 0}, {C::Zrotation, C::Xrotation, C::Yrotation, C::Xposition, C::Yposition, C::Zposition}));
  s.joints.push_back(makeJoint("J_PartialPosition", 11, {0.5, -9, 0.25}, {C::Yposition, C::Yrotation, C::Xrotation, C::Zrotation}));
  s.joints.push_back(makeJoint("K_NoChannels", 12, {0, -2, 1}, {}));
  s.joints.push_back(makeEndSite("K_NoChannels_End", 13, {0, 0, 1.5}));
  return s;
}

// Random walk per channel (fixed seed): rotations start anywhere in [-300, 300] degrees and move at
// most `max_step_degrees` per frame; positions start near the offsets and wander a few units. Joints
// with two rotation axes keep their second angle in (-90, 90) so that the walk never crosses the
// ambiguity a two-axis joint cannot resolve (b and 180 - b with c = 180 are not expressible).
inline Motion randomMotion(const Skeleton& skeleton, int frames, unsigned seed, double max_step_degrees = 10.0) {
  Motion motion;
  motion.skeleton = skeleton;
  motion.frame_time = 1.0 / 30.0;
  motion.values.resize(frames, skeleton.channelCount());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> start(-300.0, 300.0);
  std::uniform_real_distribution<double> step(-max_step_degrees, max_step_degrees);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int column = 0;
  for (const Joint& joint : skeleton.joints) {
    int rotation_index = 0;
    int rotation_count = 0;
    for (ChannelType c : joint.channels) rotation_count += isRotation(c) ? 1 : 0;
    for (ChannelType c : joint.channels) {
      if (isRotation(c)) {
        const bool bounded = rotation_count == 2 && rotation_index == 1;
        double angle = bounded ? 0.5 * start(rng) * 0.25 : start(rng);
        for (int f = 0; f < frames; ++f) {
          motion.values(f, column) = angle;
          angle += step(rng);
          if (bounded) angle = std::clamp(angle, -80.0, 80.0);
        }
        ++rotation_index;
      } else {
        double position = joint.offset[axisOf(c)] + 3.0 * unit(rng);
        for (int f = 0; f < frames; ++f) {
          motion.values(f, column) = position;
          position += 0.5 * unit(rng);
        }
      }
      ++column;
    }
  }
  return motion;
}

}  // namespace motionstyle::test
