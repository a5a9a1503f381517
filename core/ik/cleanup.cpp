// Clean-up orchestration: validation, the contact locks (cleanup_locks.h), the solve
// (cleanup_solver.cpp), the output Motion and the report's warnings.

#include "ik/cleanup.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "ik/cleanup_locks.h"
#include "ik/cleanup_model.h"
#include "ik/cleanup_solver.h"
#include "ik/cleanup_warnings.h"
#include "ik/contacts.h"
#include "motion/kinematics.h"

namespace motionstyle {
namespace {

using ik_detail::CleanupModel;
using ik_detail::ContactLocks;
using ik_detail::ContentFootHeights;

void requireWeight(double value, const char* name) {
  if (!std::isfinite(value) || value < 0.0)
    throw std::invalid_argument(std::string("cleanup options: ") + name + " must be finite and >= 0");
}

}  // namespace

int frameAtRate(int frame, double rate_ratio) { return static_cast<int>(std::floor(frame * rate_ratio + 1e-9)); }

void CleanupOptions::validate() const {
  requireWeight(position_weight, "position_weight");
  requireWeight(hips_weight, "hips_weight");
  requireWeight(contact_weight, "contact_weight");
  requireWeight(floor_weight, "floor_weight");
  requireWeight(root_smoothness_weight, "root_smoothness_weight");
  requireWeight(rotation_smoothness_weight, "rotation_smoothness_weight");
  requireWeight(prior_weight_mapped, "prior_weight_mapped");
  requireWeight(prior_weight_unmapped, "prior_weight_unmapped");
  requireWeight(unreachable_warning_cm, "unreachable_warning_cm");
  requireWeight(residual_warning_cm, "residual_warning_cm");
  requireWeight(held_down_warning_cm, "held_down_warning_cm");
  if (!std::isfinite(contact_blend_seconds) || contact_blend_seconds < 0.0)
    throw std::invalid_argument("cleanup options: contact_blend_seconds must be finite and >= 0");
  if (!std::isfinite(lock_shift_cm) || lock_shift_cm < 0.0)
    throw std::invalid_argument("cleanup options: lock_shift_cm must be finite and >= 0");
  if (window_frames < 1) throw std::invalid_argument("cleanup options: window_frames must be >= 1");
  if (window_overlap < 0 || window_overlap >= window_frames)
    throw std::invalid_argument("cleanup options: window_overlap must lie in [0, window_frames)");
  if (solver == CleanupSolver::KinematicTree && window_frames != 1)
    throw std::invalid_argument("cleanup options: the kinematic tree solver solves one frame at a time (window_frames 1)");
  if (chunk_frames < 1) throw std::invalid_argument("cleanup options: chunk_frames must be >= 1");
  if (chunk_lead_in < 0) throw std::invalid_argument("cleanup options: chunk_lead_in must be >= 0");
  if (max_iterations < 1) throw std::invalid_argument("cleanup options: max_iterations must be >= 1");
  if (!(max_total_seconds > 0.0))  // +infinity: no budget
    throw std::invalid_argument("cleanup options: max_total_seconds must be positive");
  if (threads < 0) throw std::invalid_argument("cleanup options: threads must be >= 0 (0: every hardware thread)");
  if (block_frames < 1) throw std::invalid_argument("cleanup options: block_frames must be >= 1");
  if (!std::isfinite(warning_fps) || warning_fps < 0.0)
    throw std::invalid_argument("cleanup options: warning_fps must be finite and >= 0 (0: the solve's own frames)");
}

void CleanupInput::validate() const {
  content.validate();
  const Skeleton& skeleton = content.skeleton;
  for (size_t c = 0; c < mapping.joints.size(); ++c) {
    const int joint = mapping.joints[c];
    if (joint < 0 || joint >= skeleton.jointCount())
      throw std::invalid_argument("cleanup: mapping of canonical joint " + std::to_string(c) + " is " +
                                  std::to_string(joint) + ", outside the skeleton's 0.." +
                                  std::to_string(skeleton.jointCount() - 1));
  }
  mapping.validate(skeleton);
  const int frames = content.frameCount();
  if (frames == 0) throw std::invalid_argument("cleanup: the content clip has no frames");
  if (targets.rows() != frames || targets.cols() != 3 * kCanonicalJointCount)
    throw std::invalid_argument("cleanup: targets are " + std::to_string(targets.rows()) + " x " +
                                std::to_string(targets.cols()) + ", expected " + std::to_string(frames) +
                                " frames x 63 (the content's frame count)");
  if (contacts.rows() != frames || contacts.cols() != kContactCount)
    throw std::invalid_argument("cleanup: contacts are " + std::to_string(contacts.rows()) + " x " +
                                std::to_string(contacts.cols()) + ", expected " + std::to_string(frames) +
                                " frames x 4 (the content's frame count)");
  for (Eigen::Index f = 0; f < frames; ++f) {
    if (!targets.row(f).allFinite())
      throw std::invalid_argument("cleanup: target positions of frame " + std::to_string(f) + " are not finite");
    for (Eigen::Index label = 0; label < kContactCount; ++label)
      if (contacts(f, label) != 0 && contacts(f, label) != 1)
        throw std::invalid_argument("cleanup: contact label " + std::to_string(contacts(f, label)) + " at frame " +
                                    std::to_string(f) + " (expected 0 or 1)");
  }
  if (!up.allFinite() || std::abs(up.norm() - 1.0) > 1e-6)
    throw std::invalid_argument("cleanup: the up axis must be a unit vector");
  if (!std::isfinite(floor_height)) throw std::invalid_argument("cleanup: the floor height must be finite");
  if (!std::isfinite(cm_per_unit) || !(cm_per_unit > 0.0))
    throw std::invalid_argument("cleanup: cm_per_unit must be positive and finite");
}

void cleanupMotionInBlocks(const CleanupInput& input, const CleanupOptions& options, const CleanedBlockSink& sink,
                           CleanupReport* report, const CleanupControl& control) {
  const auto start_time = std::chrono::steady_clock::now();
  options.validate();
  input.validate();
  const Motion& content = input.content;
  const CleanupModel model = ik_detail::buildCleanupModel(content.skeleton, input.mapping.joints);

  std::array<double, kContactCount> rest{};
  ContactLocks locks;
  {
    const std::array<int, kContactCount> feet = contactJoints(input.mapping);
    const Eigen::MatrixXd feet_world = worldPositions(content, feet);  // frames x 12, freed after planning
    const ContentFootHeights content_feet = ik_detail::contentFootHeights(input, feet_world);
    rest = content_feet.rest;
    locks = ik_detail::contactLocks(input, options, content_feet, feet_world);
  }

  // Final frames gather into blocks of options.block_frames: the content's local poses of the block with
  // the solved rotations and root put in, then channel values (continuing the previous block's Euler
  // branches), world positions, warnings, and the sink.
  ik_detail::CleanupWarnings warnings(input, options);
  const int unknowns = model.unknownCount();
  const int frames = content.frameCount();
  int block_first = 0;
  std::vector<Eigen::Vector3d> block_roots;
  std::vector<Eigen::Quaterniond> block_rotations;
  Eigen::RowVectorXd seed = content.values.row(0);  // frame 0 continues from the content's own angles
  // The joints whose channels the solve changes (their rotations, and the root's translation); every
  // other channel keeps the content's own value.
  std::vector<int> solved_joints = model.unknown_joints;
  if (model.root_translation_free && std::find(solved_joints.begin(), solved_joints.end(), 0) == solved_joints.end())
    solved_joints.push_back(0);
  auto flushBlock = [&]() {
    const int count = static_cast<int>(block_roots.size());
    const LocalPoses content_block = localPoses(content, block_first, count);
    LocalPoses poses = content_block;
    for (int f = 0; f < count; ++f) {
      if (model.root_translation_free) poses.translation(f, 0) = block_roots[static_cast<size_t>(f)];
      for (int u = 0; u < unknowns; ++u)
        poses.rotation(f, model.unknown_joints[static_cast<size_t>(u)]) =
            block_rotations[static_cast<size_t>(f) * static_cast<size_t>(unknowns) + static_cast<size_t>(u)];
    }
    MatrixRowMajor values = content.values.middleRows(block_first, count);
    writeChannelValues(content.skeleton, poses, solved_joints, seed.data(), values);
    const Eigen::MatrixXd world = worldPositions(content.skeleton, poses);
    warnings.add(block_first, content_block, world);
    sink(CleanedBlock{block_first, values, world});
    seed = values.row(count - 1);
    block_first += count;
    block_roots.clear();
    block_rotations.clear();
  };
  auto onFinalFrame = [&](int frame, const Eigen::Vector3d& root, const Eigen::Quaterniond* rotations) {
    block_roots.push_back(root);
    block_rotations.insert(block_rotations.end(), rotations, rotations + unknowns);
    if (static_cast<int>(block_roots.size()) == options.block_frames || frame == frames - 1) flushBlock();
  };

  const ik_detail::SolverInput solver_input{model, content, input.mapping[CanonicalJoint::Hips], input.targets, locks.positions,
                                            locks.weights, {input.cm_per_unit, input.up, input.floor_height},
                                            options.max_total_seconds, control};
  const ik_detail::SolverOutput solved = ik_detail::solveCleanup(solver_input, options, onFinalFrame);

  CleanupReport summary;
  summary.final_costs = solved.costs;
  summary.frames = frames;
  summary.solves = solved.solves;
  summary.total_iterations = solved.total_iterations;
  summary.solves_at_iteration_cap = solved.solves_at_iteration_cap;
  summary.frames_unsolved = solved.frames_unsolved;
  summary.chunks = solved.chunks;
  summary.chunks_reused = solved.chunks_reused;
  summary.chunks_warm = solved.chunks_warm;
  summary.unknown_rotations = unknowns;
  summary.contact_segments = locks.segments;
  summary.contact_rest_heights = rest;
  summary.lifted_contacts = std::move(locks.lifted);
  warnings.finish(summary);
  if (solved.frames_unsolved > 0)
    summary.warnings.push_back({"time budget of " + ik_detail::formatFixed(options.max_total_seconds, 2) +
                                " s exhausted: the last " + std::to_string(solved.frames_unsolved) +
                                " frames were not optimised (warm start only)"});
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  if (report) *report = std::move(summary);
}

Motion cleanupMotion(const CleanupInput& input, const CleanupOptions& options, CleanupReport* report,
                     const CleanupControl& control, Eigen::MatrixXd* world) {
  Motion result = input.content;
  if (world != nullptr) world->resize(result.frameCount(), 3 * result.skeleton.jointCount());
  cleanupMotionInBlocks(input, options,
                        [&](const CleanedBlock& block) {
                          result.values.middleRows(block.first_frame, block.values.rows()) = block.values;
                          if (world != nullptr) world->middleRows(block.first_frame, block.world.rows()) = block.world;
                        },
                        report, control);
  return result;
}

}  // namespace motionstyle
