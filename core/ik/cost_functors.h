#pragma once
// Private to core/ik (includes Ceres): the clean-up's cost terms as templated functors for automatic
// differentiation. Residuals are in centimetres (positions) or radians (rotations), times a weight, so
// the weights do not depend on the file's unit.
//
// Parameter blocks:
//   root position P: 3 doubles, file units (constant when the root has no position channels);
//   rotation q: 4 doubles, Ceres order [w, x, y, z], unit length (ceres::QuaternionManifold).
// Chain functors (position, contact, floor) take [P, q_pivot0, ..., q_pivot(n-1)] and run the chain's
// forward kinematics (cleanup_model.h) on the Jet type; they are wrapped in
// ceres::DynamicAutoDiffCostFunction because chain lengths differ per joint and per rig.

#include <ceres/rotation.h>

#include <algorithm>
#include <vector>

#include "ik/cleanup_model.h"

namespace motionstyle::ik_detail {

// World position of canonical joint c (file units) for parameters [P, q_pivot0, ..., q_pivot(n-1)],
// down its chain of pivots k_0 .. k_{n-1} (cleanup_model.h):
//   v = t_c;  v = s_{k_i} + M_{k_i} R(q_i) v  for i = n-1 .. 0;  p = P + v.
template <typename T>
void canonicalJointPosition(const CleanupModel& model, const FrameData& frame, int canonical,
                            T const* const* parameters, T* position) {
  const std::vector<int>& pivots = model.chains[static_cast<size_t>(canonical)].pivots;
  const Eigen::Vector3d& tip = frame.tree.tips[static_cast<size_t>(canonical)];
  T v[3] = {T(tip.x()), T(tip.y()), T(tip.z())};
  for (size_t k = pivots.size(); k-- > 0;) {
    T rotated[3];
    ceres::UnitQuaternionRotatePoint(parameters[1 + k], v, rotated);
    const ChainSegment& segment = frame.tree.nodes[static_cast<size_t>(pivots[k])];
    for (int i = 0; i < 3; ++i) {
      T value = T(segment.translation[i]);
      if (segment.has_fixed_rotation) {
        for (int j = 0; j < 3; ++j) value += segment.fixed_rotation(i, j) * rotated[j];
      } else {
        value += rotated[i];
      }
      v[i] = value;
    }
  }
  for (int i = 0; i < 3; ++i) position[i] = parameters[0][i] + v[i];
}

// The residual of a joint pulled toward a point: r = scale * (p_c(P, q) - point)  [3 residuals].
template <typename T>
void scaledOffsetFrom(const CleanupModel& model, const FrameData& frame, int canonical, T const* const* parameters,
                      const Eigen::Vector3d& point, double scale, T* residuals) {
  T p[3];
  canonicalJointPosition(model, frame, canonical, parameters, p);
  for (int i = 0; i < 3; ++i) residuals[i] = scale * (p[i] - point[i]);
}

// 2 * vector part of conj(a) * b, with the sign of the product's w made non-negative: the rotation
// vector from a to b for small angles (radians), never flipping between q and -q.
template <typename T>
void rotationDifference(const T* a, const T* b, T* out) {
  const T a_conj[4] = {a[0], -a[1], -a[2], -a[3]};
  T product[4];
  ceres::QuaternionProduct(a_conj, b, product);
  const T sign = product[0] < T(0) ? T(-2) : T(2);
  for (int i = 0; i < 3; ++i) out[i] = sign * product[1 + i];
}

// Position of mapped joint c vs its target:
//   r = w_pos * cm_per_unit * (p_c(P, q) - target_c)            [3 residuals, cm]
struct MappedPositionCost {
  const CleanupModel* model;
  const FrameData* frame;
  const ProblemConstants* constants;
  int canonical;
  double weight;

  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    scaledOffsetFrom(*model, *frame, canonical, parameters, frame->targets[static_cast<size_t>(canonical)],
                     weight * constants->cm_per_unit, residuals);
    return true;
  }
};

// Heel or toe vs its contact lock (one world point per contact segment, at floor + rest height):
//   r = w_lock(f) * cm_per_unit * (p_c(P, q) - lock_i)          [3 residuals, cm]
// w_lock(f) = contact_weight inside the segment, smoothstep-blended to 0 over a few frames outside it.
struct ContactLockCost {
  const CleanupModel* model;
  const FrameData* frame;
  const ProblemConstants* constants;
  int canonical;
  int contact;  // ContactLabel index

  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    const double weight = frame->lock_weights[static_cast<size_t>(contact)];
    if (weight == 0.0) {
      for (int i = 0; i < 3; ++i) residuals[i] = T(0);
      return true;
    }
    scaledOffsetFrom(*model, *frame, canonical, parameters, frame->lock_positions[static_cast<size_t>(contact)],
                     weight * constants->cm_per_unit, residuals);
    return true;
  }
};

// Foot joint above the floor (one-sided):
//   r = w_floor * cm_per_unit * max(0, floor - up . p_c(P, q))   [1 residual, cm of depth]
struct FloorCost {
  const CleanupModel* model;
  const FrameData* frame;
  const ProblemConstants* constants;
  int canonical;
  double weight;

  template <typename T>
  bool operator()(T const* const* parameters, T* residuals) const {
    T p[3];
    canonicalJointPosition(*model, *frame, canonical, parameters, p);
    const Eigen::Vector3d& up = constants->up;
    const T height = up.x() * p[0] + up.y() * p[1] + up.z() * p[2];
    const T depth = T(constants->floor_height) - height;
    residuals[0] = depth > T(0) ? (weight * constants->cm_per_unit) * depth : T(0);
    return true;
  }
};

// Root acceleration (second difference over three consecutive frames):
//   r = w_root * s * cm_per_unit * (P_f - 2 P_{f-1} + P_{f-2})     [3 residuals, cm per frame^2]
// s = 1 when both previous frames exist, else 0 (FrameData::smoothness_scale of frame f).
struct RootAccelerationCost {
  const FrameData* frame;
  const ProblemConstants* constants;
  double weight;

  template <typename T>
  bool operator()(const T* p0, const T* p1, const T* p2, T* residuals) const {
    const double scale = weight * frame->smoothness_scale * constants->cm_per_unit;
    for (int i = 0; i < 3; ++i) residuals[i] = scale * (p2[i] - 2.0 * p1[i] + p0[i]);
    return true;
  }
};

// Rotation acceleration: deviation of q_f from the constant-angular-velocity prediction
//   q_pred = q_{f-1} * (conj(q_{f-2}) * q_{f-1}),
//   r = w_rot * s * 2 vec(conj(q_pred) * q_f)                    [3 residuals, radians per frame^2]
struct RotationAccelerationCost {
  const FrameData* frame;
  double weight;

  template <typename T>
  bool operator()(const T* q0, const T* q1, const T* q2, T* residuals) const {
    const double scale = weight * frame->smoothness_scale;
    if (scale == 0.0) {
      for (int i = 0; i < 3; ++i) residuals[i] = T(0);
      return true;
    }
    const T q0_conj[4] = {q0[0], -q0[1], -q0[2], -q0[3]};
    T velocity[4];
    ceres::QuaternionProduct(q0_conj, q1, velocity);
    T predicted[4];
    ceres::QuaternionProduct(q1, velocity, predicted);
    T difference[3];
    rotationDifference(predicted, q2, difference);
    for (int i = 0; i < 3; ++i) residuals[i] = scale * difference[i];
    return true;
  }
};

// Prior toward the content clip's own local rotation of the same joint and frame:
//   r = w_prior * 2 vec(conj(q_content) * q)                     [3 residuals, radians]
// w_prior is small on canonical joints (their positions decide) and larger on the others
// (clavicles, twist and connector joints), which positions alone cannot pin down.
struct RotationPriorCost {
  const FrameData* frame;
  int unknown;  // index into CleanupModel::unknown_joints
  double weight;

  template <typename T>
  bool operator()(const T* q, T* residuals) const {
    const Eigen::Quaterniond& prior = frame->prior_rotations[static_cast<size_t>(unknown)];
    const T prior_array[4] = {T(prior.w()), T(prior.x()), T(prior.y()), T(prior.z())};
    T difference[3];
    rotationDifference(prior_array, q, difference);
    for (int i = 0; i < 3; ++i) residuals[i] = weight * difference[i];
    return true;
  }
};

}  // namespace motionstyle::ik_detail
