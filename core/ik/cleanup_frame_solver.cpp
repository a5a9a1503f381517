#include "ik/cleanup_frame_solver.h"

#include "ik/cleanup_frame_math.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace motionstyle::ik_detail {
namespace {

// Ceres' defaults for Levenberg-Marquardt (Solver::Options), which the Ceres window solve uses, but
// for the initial radius and the function tolerance.
// Ceres starts at 1e4; a frame warm-started from its predecessor is close to its solution, and at 1e4
// the damping (diag(J'J) / radius, where diag(J'J) reaches (contact weight x cm)^2) held the first steps
// back: 6.4 iterations per frame, against 3.9-4.5 at 1e6 with the same quality (docs/decisions.md).
constexpr double kInitialRadius = 1e6;
constexpr double kMaxRadius = 1e16;
constexpr double kMinRadius = 1e-32;
constexpr double kMinDiagonal = 1e-6;
constexpr double kMaxDiagonal = 1e32;
constexpr double kMinRelativeDecrease = 1e-3;
// Ceres' 1e-6 spent the last of 3.5-4.4 iterations per frame on cost changes worth far under a
// millimetre: at 1e-4, 2.7-3.2 iterations, the clean-up 8-15 % faster, bench_ik's quality figures the
// same to 0.01 cm (docs/decisions.md).
constexpr double kFunctionTolerance = 1e-4;
constexpr double kParameterTolerance = 1e-8;
constexpr double kGradientTolerance = 1e-10;

}  // namespace

FrameSolver::FrameSolver(const CleanupModel& model, const CleanupOptions& options, const ProblemConstants& constants)
    : model_(model), options_(options), constants_(constants), nodes_(model.unknownCount() + 1) {
  const auto nodes = static_cast<size_t>(nodes_);
  ancestor_offset_.assign(nodes, 0);
  ancestor_count_.assign(nodes, 0);
  for (int n = 1; n < nodes_; ++n) {
    ancestor_offset_[static_cast<size_t>(n)] = static_cast<int>(ancestors_.size());
    for (int u = model.unknown_parent[static_cast<size_t>(n - 1)];; u = model.unknown_parent[static_cast<size_t>(u)]) {
      ancestors_.push_back(u + 1);
      if (u < 0) break;
    }
    ancestor_count_[static_cast<size_t>(n)] = static_cast<int>(ancestors_.size()) - ancestor_offset_[static_cast<size_t>(n)];
  }
  contact_of_joint_.fill(-1);
  for (size_t i = 0; i < kContactCount; ++i) contact_of_joint_[static_cast<size_t>(index(kContactJoint[i]))] = static_cast<int>(i);
  for (size_t c = 0; c < kCanonicalJointCount; ++c) {
    const std::vector<int>& pivots = model.chains[c].pivots;
    anchor_[c] = pivots.empty() ? 0 : pivots.back() + 1;
    position_weight_[c] = static_cast<int>(c) == index(CanonicalJoint::Hips) ? options.hips_weight : options.position_weight;
  }
  for (bool canonical : model.unknown_is_canonical)
    prior_weight_.push_back(canonical ? options.prior_weight_mapped : options.prior_weight_unmapped);

  moments_.resize(nodes);
  predicted_.resize(static_cast<size_t>(model.unknownCount()));
  hessian_diag_.resize(nodes);
  hessian_off_.resize(ancestors_.size());
  factor_diag_.resize(nodes);
  factor_off_.resize(ancestors_.size());
  gradient_.resize(nodes);
  step_.resize(nodes);
  damping_.resize(nodes);
  for (Pose* pose : {&current_, &candidate_}) {
    pose->rotations.resize(static_cast<size_t>(model.unknownCount()));
    pose->world_rotation.resize(nodes);
    pose->world_position.resize(nodes);
  }
}

void FrameSolver::prepareFrame(const FrameData& frame, FrameRef before_previous, FrameRef previous) {
  frame_ = &frame;
  if (frame.smoothness_scale == 0.0) return;
  root_prediction_ = 2.0 * *previous.root - *before_previous.root;
  for (size_t u = 0; u < predicted_.size(); ++u) {
    const Eigen::Quaterniond& q0 = before_previous.rotations[u];
    const Eigen::Quaterniond& q1 = previous.rotations[u];
    predicted_[u] = q1 * (q0.conjugate() * q1);
  }
}

void FrameSolver::evaluate(Pose& pose) const {
  const FrameData& frame = *frame_;
  pose.world_rotation[0].setIdentity();
  pose.world_position[0] = pose.root;
  for (size_t u = 0; u < pose.rotations.size(); ++u) {
    const auto parent = static_cast<size_t>(model_.unknown_parent[u] + 1);
    const ChainSegment& segment = frame.tree.nodes[u];
    const Eigen::Matrix3d& above = pose.world_rotation[parent];
    const Eigen::Matrix3d rotation = pose.rotations[u].toRotationMatrix();
    pose.world_rotation[u + 1] = segment.has_fixed_rotation ? Eigen::Matrix3d(above * segment.fixed_rotation * rotation)
                                                            : Eigen::Matrix3d(above * rotation);
    pose.world_position[u + 1] = pose.world_position[parent] + above * segment.translation;
  }
  for (size_t c = 0; c < kCanonicalJointCount; ++c) {
    const auto anchor = static_cast<size_t>(anchor_[c]);
    pose.joints[c] = pose.world_position[anchor] + pose.world_rotation[anchor] * frame.tree.tips[c];
  }

  const double cm = constants_.cm_per_unit;
  CleanupTermCosts& costs = pose.costs;
  costs = CleanupTermCosts{};
  for (size_t c = 0; c < kCanonicalJointCount; ++c)
    costs.position += 0.5 * (position_weight_[c] * cm) * (position_weight_[c] * cm) * (pose.joints[c] - frame.targets[c]).squaredNorm();
  for (size_t i = 0; i < kContactCount; ++i) {
    const Eigen::Vector3d& p = pose.joints[static_cast<size_t>(index(kContactJoint[i]))];
    const double lock = frame.lock_weights[i] * cm;
    if (options_.lock_contacts && lock != 0.0) costs.contact += 0.5 * lock * lock * (p - frame.lock_positions[i]).squaredNorm();
    const double depth = constants_.floor_height - constants_.up.dot(p);
    const double floor = options_.floor_weight * cm * depth;
    if (options_.keep_above_floor && depth > 0.0) costs.floor += 0.5 * floor * floor;
  }
  const double smooth = frame.smoothness_scale;
  if (smooth != 0.0) {
    const double root_scale = options_.root_smoothness_weight * smooth * cm;
    costs.smoothness += 0.5 * root_scale * root_scale * (pose.root - root_prediction_).squaredNorm();
    const double rotation_scale = options_.rotation_smoothness_weight * smooth;
    for (size_t u = 0; u < pose.rotations.size(); ++u)
      costs.smoothness += 0.5 * rotation_scale * rotation_scale * rotationDifference(predicted_[u], pose.rotations[u]).squaredNorm();
  }
  for (size_t u = 0; u < pose.rotations.size(); ++u)
    costs.prior += 0.5 * prior_weight_[u] * prior_weight_[u] *
                   rotationDifference(frame.prior_rotations[u], pose.rotations[u]).squaredNorm();
}

// J'J and J'r in world-frame coordinates: a rotation step d_k turns node k's subtree about o_k,
// W_k <- exp([d_k]x) W_k (the local step is W_k' d_k), so a canonical joint c below k moves by
// K_ck = -[p_c - o_k]x, and the root's step moves every joint by I. A joint's position, lock and floor
// residuals share that derivative, so they weigh it together: S_c = s_c I + f_c u u' with
//   s_c = cm^2 (w_pos^2 + w_lock^2),  f_c = cm^2 w_floor^2 [floor active],  u = up,
// and pull with b_c = cm^2 (w_pos^2 (p_c - target) + w_lock^2 (p_c - lock)) - f_c depth_c u. Then, over
// the joints c below node k (l = k or an ancestor of k), with d = p_c - o:
//   g_k  = sum (p_c x b_c) - o_k x sum b_c,
//   H_kl = sum s_c ((d_k . d_l) I - d_l d_k') + sum f_c (d_k x u)(d_l x u)',
// which expand into the moments of s, s p, s p p', f, f (p x u), f (p x u)(p x u)' over the subtree:
// every block costs a few 3 x 3 operations whatever the number of joints below it.
void FrameSolver::linearise(const Pose& pose) {
  const FrameData& frame = *frame_;
  const double cm2 = constants_.cm_per_unit * constants_.cm_per_unit;
  const Eigen::Vector3d& up = constants_.up;
  std::fill(moments_.begin(), moments_.end(), SubtreeMoments{});
  for (size_t c = 0; c < kCanonicalJointCount; ++c) {
    const Eigen::Vector3d& p = pose.joints[c];
    double isotropic = position_weight_[c] * position_weight_[c] * cm2;
    Eigen::Vector3d b = isotropic * (p - frame.targets[c]);
    double floor = 0.0;
    const int contact = contact_of_joint_[c];
    if (contact >= 0) {
      const auto i = static_cast<size_t>(contact);
      const double lock = frame.lock_weights[i] * frame.lock_weights[i] * cm2;
      if (options_.lock_contacts && lock != 0.0) {
        isotropic += lock;
        b += lock * (p - frame.lock_positions[i]);
      }
      const double depth = constants_.floor_height - up.dot(p);
      if (options_.keep_above_floor && depth > 0.0) {
        floor = options_.floor_weight * options_.floor_weight * cm2;
        b -= floor * depth * up;
      }
    }
    SubtreeMoments& m = moments_[static_cast<size_t>(anchor_[c])];
    m.s0 += isotropic;
    m.s1 += isotropic * p;
    m.s2.noalias() += isotropic * p * p.transpose();
    if (floor != 0.0) {
      const Eigen::Vector3d pu = p.cross(up);
      m.f0 += floor;
      m.f1 += floor * pu;
      m.f2.noalias() += floor * pu * pu.transpose();
    }
    m.b += b;
    m.pb += p.cross(b);
  }
  for (int n = nodes_ - 1; n > 0; --n) {  // children before parents: each node's sums cover its subtree
    const SubtreeMoments& m = moments_[static_cast<size_t>(n)];
    SubtreeMoments& parent = moments_[static_cast<size_t>(ancestors_[static_cast<size_t>(ancestor_offset_[static_cast<size_t>(n)])])];
    parent.s0 += m.s0;
    parent.s1 += m.s1;
    parent.s2 += m.s2;
    parent.f0 += m.f0;
    parent.f1 += m.f1;
    parent.f2 += m.f2;
    parent.b += m.b;
    parent.pb += m.pb;
  }

  const bool root_free = model_.root_translation_free;
  for (int n = 0; n < nodes_; ++n) {
    const auto node = static_cast<size_t>(n);
    const SubtreeMoments& m = moments_[node];
    if (n == 0) {
      hessian_diag_[0] = m.s0 * Eigen::Matrix3d::Identity() + m.f0 * up * up.transpose();
      gradient_[0] = m.b;
      continue;
    }
    const Eigen::Vector3d& ok = pose.world_position[node];
    const Eigen::Vector3d oku = ok.cross(up);
    const Eigen::Vector3d s1k = m.s1 - m.s0 * ok;            // sum s d_k
    const Eigen::Vector3d f1k = m.f1 - m.f0 * oku;           // sum f (d_k x u)
    const Eigen::Matrix3d s2k = m.s2 - m.s1 * ok.transpose(); // sum s p d_k'
    const Eigen::Matrix3d f2k = m.f2 - m.f1 * oku.transpose();  // sum f (p x u)(d_k x u)'
    const double trace_k = m.s2.trace() - ok.dot(m.s1);     // sum s p . d_k
    gradient_[node] = m.pb - ok.cross(m.b);
    auto block = [&](const Eigen::Vector3d& ol) -> Eigen::Matrix3d {  // H_kl for an ancestor-or-self l
      const Eigen::Vector3d olu = ol.cross(up);
      const double dot = trace_k - ol.dot(s1k);             // sum s d_k . d_l
      Eigen::Matrix3d h = dot * Eigen::Matrix3d::Identity() - (s2k - ol * s1k.transpose());  // - sum s d_l d_k'
      h += (f2k - olu * f1k.transpose()).transpose();       // sum f (d_k x u)(d_l x u)'
      return h;
    };
    hessian_diag_[node] = block(ok);
    for (int i = 0; i < ancestor_count_[node]; ++i) {
      const auto at = static_cast<size_t>(ancestor_offset_[node] + i);
      const auto ancestor = static_cast<size_t>(ancestors_[at]);
      if (ancestor == 0) {  // K_k' S_c summed: [sum s d_k]x + sum f (d_k x u) u'
        hessian_off_[at] = root_free ? Eigen::Matrix3d(crossMatrix(s1k) + f1k * up.transpose()) : Eigen::Matrix3d::Zero();
      } else {
        hessian_off_[at] = block(pose.world_position[ancestor]);
      }
    }
  }

  const double smooth = frame.smoothness_scale;
  const double rotation_scale = options_.rotation_smoothness_weight * smooth;
  for (size_t u = 0; u < pose.rotations.size(); ++u) {
    const Eigen::Matrix3d& world = pose.world_rotation[u + 1];
    const auto addRotationTerm = [&](const Eigen::Quaterniond& toward, double weight) {
      const RotationResidual r = rotationResidual(toward, pose.rotations[u]);
      const Eigen::Matrix3d jacobian = r.jacobian * world.transpose();  // d_local = W' d_world
      hessian_diag_[u + 1].noalias() += (weight * weight) * jacobian.transpose() * jacobian;
      gradient_[u + 1].noalias() += (weight * weight) * jacobian.transpose() * r.value;
    };
    addRotationTerm(frame.prior_rotations[u], prior_weight_[u]);
    if (rotation_scale != 0.0) addRotationTerm(predicted_[u], rotation_scale);
  }
  if (root_free) {
    const double root_scale = options_.root_smoothness_weight * smooth * constants_.cm_per_unit;
    hessian_diag_[0] += root_scale * root_scale * Eigen::Matrix3d::Identity();
    gradient_[0] += root_scale * root_scale * (pose.root - root_prediction_);
  } else {
    hessian_diag_[0].setIdentity();  // P is fixed: a step of 0
    gradient_[0].setZero();
  }
}

// Block Cholesky of the damped J'J, leaves first (nodes are numbered parents first, so from the last
// node down). Eliminating node n with ancestors a_0 (nearest) .. a_m:
//   L_nn = chol(A_nn),  X_i = L_nn^-1 A_{n a_i},  A_{a_i a_j} -= X_i' X_j  for i <= j,
// where a_j is an ancestor of a_i: every update lands in a block that exists already.
bool FrameSolver::solveDamped(double radius) {
  for (int n = 0; n < nodes_; ++n) {
    const auto node = static_cast<size_t>(n);
    factor_diag_[node] = hessian_diag_[node];
    for (int axis = 0; axis < 3; ++axis) {
      damping_[node][axis] = std::clamp(hessian_diag_[node](axis, axis), kMinDiagonal, kMaxDiagonal) / radius;
      factor_diag_[node](axis, axis) += damping_[node][axis];
    }
  }
  std::copy(hessian_off_.begin(), hessian_off_.end(), factor_off_.begin());
  for (int n = nodes_ - 1; n >= 0; --n) {
    const auto node = static_cast<size_t>(n);
    if (!choleskyInPlace(factor_diag_[node])) return false;
    const int first = ancestor_offset_[node], count = ancestor_count_[node];
    for (int i = 0; i < count; ++i) forwardSolveInPlace(factor_diag_[node], factor_off_[static_cast<size_t>(first + i)]);
    for (int i = 0; i < count; ++i) {
      const Eigen::Matrix3d& xi = factor_off_[static_cast<size_t>(first + i)];
      const auto ai = static_cast<size_t>(ancestors_[static_cast<size_t>(first + i)]);
      factor_diag_[ai].noalias() -= xi.transpose() * xi;
      for (int j = i + 1; j < count; ++j)
        factor_off_[static_cast<size_t>(ancestor_offset_[ai] + j - i - 1)].noalias() -=
            xi.transpose() * factor_off_[static_cast<size_t>(first + j)];
    }
  }
  // L y = -g (leaves first), then L' x = y (parents first).
  for (int n = 0; n < nodes_; ++n) step_[static_cast<size_t>(n)] = -gradient_[static_cast<size_t>(n)];
  for (int n = nodes_ - 1; n >= 0; --n) {
    const auto node = static_cast<size_t>(n);
    forwardSolveInPlace(factor_diag_[node], step_[node]);
    for (int i = 0; i < ancestor_count_[node]; ++i) {
      const auto at = static_cast<size_t>(ancestor_offset_[node] + i);
      step_[static_cast<size_t>(ancestors_[at])].noalias() -= factor_off_[at].transpose() * step_[node];
    }
  }
  for (int n = 0; n < nodes_; ++n) {
    const auto node = static_cast<size_t>(n);
    for (int i = 0; i < ancestor_count_[node]; ++i) {
      const auto at = static_cast<size_t>(ancestor_offset_[node] + i);
      step_[node].noalias() -= factor_off_[at] * step_[static_cast<size_t>(ancestors_[at])];
    }
    backwardSolveInPlace(factor_diag_[node], step_[node]);
  }
  for (const Eigen::Vector3d& s : step_)
    if (!s.allFinite()) return false;
  return true;
}

void FrameSolver::applyStep(const Pose& from, Pose& to) const {
  to.root = model_.root_translation_free ? Eigen::Vector3d(from.root + step_[0]) : from.root;
  for (size_t u = 0; u < from.rotations.size(); ++u)
    to.rotations[u] =
        (from.rotations[u] * rotationFromVector(from.world_rotation[u + 1].transpose() * step_[u + 1])).normalized();
}

CleanupTermCosts FrameSolver::costs(const FrameData& frame, FrameRef before_previous, FrameRef previous,
                                    const Eigen::Vector3d& root, const Eigen::Quaterniond* rotations) {
  prepareFrame(frame, before_previous, previous);
  current_.root = root;
  std::copy(rotations, rotations + current_.rotations.size(), current_.rotations.begin());
  evaluate(current_);
  return current_.costs;
}

Eigen::VectorXd FrameSolver::gradient(const FrameData& frame, FrameRef before_previous, FrameRef previous,
                                      const Eigen::Vector3d& root, const Eigen::Quaterniond* rotations) {
  costs(frame, before_previous, previous, root, rotations);
  linearise(current_);
  Eigen::VectorXd stacked(3 * nodes_);
  stacked.head<3>() = gradient_[0];
  for (int n = 1; n < nodes_; ++n)  // world-frame step d = W d_local: the local gradient is W' g
    stacked.segment<3>(3 * n) = current_.world_rotation[static_cast<size_t>(n)].transpose() * gradient_[static_cast<size_t>(n)];
  return stacked;
}

Eigen::MatrixXd FrameSolver::normalMatrix(const FrameData& frame, FrameRef before_previous, FrameRef previous,
                                          const Eigen::Vector3d& root, const Eigen::Quaterniond* rotations) {
  costs(frame, before_previous, previous, root, rotations);
  linearise(current_);
  Eigen::MatrixXd world = Eigen::MatrixXd::Zero(3 * nodes_, 3 * nodes_);
  Eigen::MatrixXd to_local = Eigen::MatrixXd::Identity(3 * nodes_, 3 * nodes_);  // d_world = T d_local
  for (int n = 0; n < nodes_; ++n) {
    const auto node = static_cast<size_t>(n);
    world.block<3, 3>(3 * n, 3 * n) = hessian_diag_[node];
    for (int i = 0; i < ancestor_count_[node]; ++i) {
      const auto at = static_cast<size_t>(ancestor_offset_[node] + i);
      const int a = ancestors_[at];
      world.block<3, 3>(3 * n, 3 * a) = hessian_off_[at];
      world.block<3, 3>(3 * a, 3 * n) = hessian_off_[at].transpose();
    }
    if (n > 0) to_local.block<3, 3>(3 * n, 3 * n) = current_.world_rotation[node];
  }
  return to_local.transpose() * world * to_local;
}

FrameSolveResult FrameSolver::solve(const FrameData& frame, FrameRef before_previous, FrameRef previous,
                                    Eigen::Vector3d& root, Eigen::Quaterniond* rotations) {
  prepareFrame(frame, before_previous, previous);
  current_.root = root;
  for (size_t u = 0; u < current_.rotations.size(); ++u) current_.rotations[u] = rotations[u].normalized();
  evaluate(current_);
  linearise(current_);

  FrameSolveResult result;
  double radius = kInitialRadius, decrease = 2.0;
  const double parameter_norm = std::sqrt(current_.root.squaredNorm() + static_cast<double>(current_.rotations.size()));
  while (true) {
    double gradient_max = 0.0;
    for (const Eigen::Vector3d& g : gradient_) gradient_max = std::max(gradient_max, g.cwiseAbs().maxCoeff());
    if (gradient_max <= kGradientTolerance) break;
    if (result.iterations >= options_.max_iterations) {
      result.at_iteration_cap = true;
      break;
    }
    ++result.iterations;
    if (!solveDamped(radius)) {  // not positive definite at this damping: as a rejected step
      radius /= decrease;
      decrease *= 2.0;
      if (radius < kMinRadius) break;
      continue;
    }
    applyStep(current_, candidate_);
    evaluate(candidate_);
    double step_norm2 = (candidate_.root - current_.root).squaredNorm();
    for (size_t u = 0; u < current_.rotations.size(); ++u)
      step_norm2 += (candidate_.rotations[u].coeffs() - current_.rotations[u].coeffs()).squaredNorm();
    const double cost = current_.costs.total(), candidate_cost = candidate_.costs.total();
    const bool better = candidate_cost < cost;
    // Converged: the step or the cost change is negligible (the better of the two points is kept).
    if (std::sqrt(step_norm2) <= kParameterTolerance * (parameter_norm + kParameterTolerance) ||
        std::abs(cost - candidate_cost) <= kFunctionTolerance * cost) {
      if (better) std::swap(current_, candidate_);
      break;
    }
    // Model decrease of the damped step: with (H + D) d = -g, -(g'd + d'Hd / 2) = (-g'd + d'Dd) / 2.
    double model_decrease = 0.0;
    for (int n = 0; n < nodes_; ++n) {
      const auto node = static_cast<size_t>(n);
      model_decrease += 0.5 * (-gradient_[node].dot(step_[node]) + step_[node].cwiseAbs2().dot(damping_[node]));
    }
    const double relative_decrease = model_decrease > 0.0 ? (cost - candidate_cost) / model_decrease : -1.0;
    if (better && relative_decrease > kMinRelativeDecrease) {
      std::swap(current_, candidate_);
      radius = std::min(kMaxRadius, radius / std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * relative_decrease - 1.0, 3)));
      decrease = 2.0;
      linearise(current_);
    } else {
      radius /= decrease;
      decrease *= 2.0;
      if (radius < kMinRadius) break;
    }
  }
  root = current_.root;
  std::copy(current_.rotations.begin(), current_.rotations.end(), rotations);
  result.costs = current_.costs;
  return result;
}

}  // namespace motionstyle::ik_detail
