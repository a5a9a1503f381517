// Clean-up orchestration: validation, contact locks and rest heights, the solve
// (cleanup_solver.cpp), the output Motion and the report's warnings.

#include "ik/cleanup.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "features/foot_contacts.h"
#include "features/signal_filters.h"
#include "ik/cleanup_model.h"
#include "ik/cleanup_solver.h"
#include "ik/cleanup_warnings.h"
#include "ik/contacts.h"
#include "ik/lock_centre.h"
#include "motion/kinematics.h"

namespace motionstyle {
namespace {

using ik_detail::CleanupModel;

void requireWeight(double value, const char* name) {
  if (!std::isfinite(value) || value < 0.0)
    throw std::invalid_argument(std::string("cleanup options: ") + name + " must be finite and >= 0");
}

// The content's contact joints (ContactLabel order) as the columns of feet_world (frames x 12).
constexpr std::array<int, kContactCount> kFeetColumns = {0, 1, 2, 3};

// Where the CONTENT clip has each contact joint planted (its own detected contacts) and how high above
// the floor it is then, file units: one median per joint for the whole clip (`rest`), the fallback for
// a lock where the content's foot is not down. A joint never planted in the content keeps the
// low-percentile estimate, which is what detection itself assumes. feet_world: the content's contact
// joints.
struct ContentFootHeights {
  std::array<double, kContactCount> rest{};
  ContactLabels planted;
};

// The median height above the floor of contact joint `label` over frames first..last where the content
// has it planted (at least 0), file units; nothing when it is planted on none of them.
std::optional<double> plantedHeight(const ContactLabels& planted, const CleanupInput& input,
                                    const Eigen::MatrixXd& feet_world, int label, int first, int last) {
  std::vector<double> heights;
  for (int f = first; f <= last && f < planted.rows(); ++f)
    if (planted(f, label) != 0)
      heights.push_back(input.up.dot(feet_world.block<1, 3>(f, 3 * label).transpose()) - input.floor_height);
  if (heights.empty()) return std::nullopt;
  return std::max(0.0, median(std::move(heights)));
}

ContentFootHeights contentFootHeights(const CleanupInput& input, const Eigen::MatrixXd& feet_world) {
  const double body_height = restPoseBodyHeight(input.content.skeleton, input.up);
  ContentFootHeights feet;
  feet.rest = estimateRestHeights(feet_world, kFeetColumns, input.up, input.floor_height, body_height);
  feet.planted = detectContacts(feet_world, kFeetColumns, input.up, input.floor_height, input.content.fps(), body_height);
  const int last = static_cast<int>(feet.planted.rows()) - 1;
  for (int label = 0; label < kContactCount; ++label)
    if (const std::optional<double> height = plantedHeight(feet.planted, input, feet_world, label, 0, last))
      feet.rest[static_cast<size_t>(label)] = *height;
  return feet;
}

// The height above the floor of one lock: the content's own height of that joint over the segment
// where the content has it planted, else the clip's rest height. Why per segment: captured floors are
// not flat (CMU 07_01's left ankle rests 6.0 cm up in one step and 8.9 in the next); one clip-wide
// height lifted or sank every step by the difference. Where the targets hold the joint more than
// kLockHeightToleranceCm from the content's height over the segment, the content's height is not the
// target foot's:
//   - the targets hold it LOWER: the content's foot was not standing on its sole there (a kneel: CMU
//     131_01's ankle planted 15 cm up on its instep, while a style network stands the character up),
//     so the content's height says nothing of the floor under the target's foot: the rest height;
//   - the targets hold it HIGHER: the style raised it (a run on the forefoot, the heel 8-14 cm up
//     through the content's heel contact): the lock keeps it still where the targets hold it, the
//     median of their heights (`raised`). Locked on the floor it was pulled 8-14 cm down, most of the
//     other studios' runs' worst residual (docs/decisions.md, "A heel the style raises"). The same
//     against the rest height where the content never plants the joint over the segment (a run's
//     quick stance: Bandai's run 012 with masculine, 9.7 -> 4.6 cm).
constexpr double kLockHeightToleranceCm = 5.0;

struct LockHeight {
  double above_floor = 0.0;  // file units
  bool raised = false;       // the targets' height, above the content's
};

LockHeight lockHeight(const ContentFootHeights& feet, const CleanupInput& input, const Eigen::MatrixXd& feet_world,
                      int label, const ContactSegment& range) {
  const double rest = feet.rest[static_cast<size_t>(label)];
  const std::optional<double> planted = plantedHeight(feet.planted, input, feet_world, label, range.first, range.last);
  const int column = 3 * index(kContactJoint[static_cast<size_t>(label)]);
  std::vector<double> heights;
  for (int f = range.first; f <= range.last; ++f)
    heights.push_back(input.up.dot(input.targets.block<1, 3>(f, column).transpose()) - input.floor_height);
  const double target_height = median(std::move(heights));
  const double above_content_cm = (target_height - planted.value_or(rest)) * input.cm_per_unit;
  if (above_content_cm > kLockHeightToleranceCm) return {target_height, true};
  if (!planted || above_content_cm < -kLockHeightToleranceCm) return {rest, false};
  return {*planted, false};
}

struct ContactLocks {
  std::vector<std::array<Eigen::Vector3d, kContactCount>> positions;  // per frame, file units
  Eigen::MatrixXd weights;                                            // frames x 4
  // frames x 4: 1 where the frame lies before the first or after the last frame of its segment at
  // which the targets hold the joint down (within kLoneLiftToleranceCm of the lock): the style has not
  // landed yet, or has lifted off already (raiseLoneLocks).
  Eigen::MatrixXi departing;
  int segments = 0;
};

struct LockSegment {
  int label = 0;
  ContactSegment frames;
  Eigen::Vector3d lock = Eigen::Vector3d::Zero();  // file units
  bool raised = false;                               // LockHeight::raised
};

// Heel and toe locks of one foot that are active together must sit as far apart as the foot is long,
// or the solver, unable to meet both, moves the toe when the heel lock lets go (a visible skate).
// Segments are visited in start order, so that chains of overlaps stay consistent, and the later of
// two overlapping segments is moved along the floor so that the two locks lie the foot's length apart
// (their heights kept). But where one of the two is raised (lockHeight) and the other is not, the
// raised one moves, up or down: the foot pivots on the joint that is down, so the raised lock keeps its
// place over the floor and takes the height at which it lies the foot's length from the other. Moved
// along the floor instead, a heel raised 15 cm toward a toe on the floor came 12 cm from its targets
// (docs/decisions.md). An earlier raised lock already placed against its own partner is not moved again.
void makeFootLocksConsistent(std::vector<LockSegment>& segments, int heel, int toe, double foot_length,
                             const Eigen::Vector3d& up) {
  std::vector<LockSegment*> foot;
  for (LockSegment& segment : segments)
    if (segment.label == heel || segment.label == toe) foot.push_back(&segment);
  std::sort(foot.begin(), foot.end(), [](const LockSegment* a, const LockSegment* b) {
    return a->frames.first < b->frames.first;
  });
  std::vector<bool> placed(foot.size(), false);  // moved to lie the foot's length from a partner
  for (size_t i = 0; i < foot.size(); ++i) {
    LockSegment& later = *foot[i];
    size_t anchor = i;
    int best_overlap = 0;
    for (size_t j = 0; j < i; ++j) {
      if (foot[j]->label == later.label) continue;
      const int overlap = std::min(foot[j]->frames.last, later.frames.last) -
                          std::max(foot[j]->frames.first, later.frames.first) + 1;
      if (overlap > best_overlap) {
        best_overlap = overlap;
        anchor = j;
      }
    }
    if (anchor == i) continue;
    const bool raise_later = later.raised && !foot[anchor]->raised;
    const bool raise_anchor = foot[anchor]->raised && !later.raised && !placed[anchor];
    if (raise_later || raise_anchor) {
      LockSegment& raised = raise_later ? later : *foot[anchor];
      const LockSegment& down = raise_later ? *foot[anchor] : later;
      Eigen::Vector3d across = raised.lock - down.lock;
      across -= up.dot(across) * up;
      const double horizontal = across.norm();
      if (horizontal < foot_length)
        raised.lock = down.lock + across + std::sqrt(foot_length * foot_length - horizontal * horizontal) * up;
      else if (horizontal > 1e-9)  // further than the foot is long: brought in, level with the other
        raised.lock = down.lock + across * (foot_length / horizontal);
      placed[raise_later ? i : anchor] = true;
      continue;
    }
    const LockSegment& fixed = *foot[anchor];
    Eigen::Vector3d along = later.lock - fixed.lock;
    const double height = up.dot(along);
    along -= height * up;
    if (along.norm() < 1e-9) continue;  // no direction to keep: leave it
    const double horizontal_length = std::sqrt(std::max(0.0, foot_length * foot_length - height * height));
    later.lock = fixed.lock + along.normalized() * horizontal_length + height * up;
    placed[i] = true;
  }
}

// Where the style lands a heel or toe later than the content's contact starts, or lifts it off
// earlier than it ends, the lock holds it still over the floor but not under its targets: on the
// frames before the first and after the last at which the targets hold the joint within
// kLoneLiftToleranceCm of its lock (ContactLocks::departing, ramps included), and while the other
// joint of that foot is not locked, the lock rises with the targets by
//   lift = max(0, up . (target - lock) - tolerance) x (1 - a_other),
// a_other the other joint's lock share (its ramp's, CleanupOptions::contact_blend_seconds), so that
// the lift fades in and out with the other lock instead of jumping. Why: the toe of a quicker
// toe-off was held on the floor while its targets rose 9.5 cm (CMU 131_01's kneel exit with elderly:
// 11.7 cm from them, 6.9 with the lift); its horizontal place, which alone makes a skate, stays
// locked. Not with both joints locked: the foot's length ties them, one rising moves the other
// along the floor (3-9 cm/s of skate), nor in a stance's middle, where a lock rising with the
// targets' bobs would float a planted foot (docs/decisions.md, "A toe the style lifts off").
constexpr double kLoneLiftToleranceCm = 1.0;

void raiseLoneLocks(ContactLocks& locks, const CleanupInput& input, const CleanupOptions& options) {
  const double tolerance = kLoneLiftToleranceCm / input.cm_per_unit;
  const double position_weight2 = options.position_weight * options.position_weight;
  for (Eigen::Index f = 0; f < locks.weights.rows(); ++f)
    for (int label = 0; label < kContactCount; ++label) {
      if (locks.weights(f, label) <= 0.0 || locks.departing(f, label) == 0) continue;
      const double other_weight = locks.weights(f, label ^ 1);  // ContactLabel order: heel, toe per foot
      const double other_share =  // 0 where the other joint is free (also when position_weight is 0)
          other_weight <= 0.0 ? 0.0 : other_weight * other_weight / (other_weight * other_weight + position_weight2);
      Eigen::Vector3d& lock = locks.positions[static_cast<size_t>(f)][static_cast<size_t>(label)];
      const int column = 3 * index(kContactJoint[static_cast<size_t>(label)]);
      const double above = input.up.dot(input.targets.block<1, 3>(f, column).transpose() - lock) - tolerance;
      if (above > 0.0) lock += above * (1.0 - other_share) * input.up;
    }
}

// One lock point per contact segment: the targets' median moved toward their minimax point on the
// floor plane by at most lock_shift_cm (lock_centre.h), at floor + lockHeight. Its weight is full
// inside the segment; on either side the lock's share of the pull ramps down
// (CleanupOptions::contact_blend_seconds); where two ramps meet, the nearer segment wins.
ContactLocks contactLocks(const CleanupInput& input, const CleanupOptions& options, const ContentFootHeights& feet,
                          const Eigen::MatrixXd& feet_world) {
  const int frames = static_cast<int>(input.targets.rows());
  const Eigen::Vector3d& up = input.up;
  std::vector<LockSegment> segments;
  for (int label = 0; label < kContactCount; ++label) {
    const int column = 3 * index(kContactJoint[static_cast<size_t>(label)]);
    for (const ContactSegment& range : contactSegments(input.contacts, label)) {
      LockSegment segment{label, range, {}};
      std::vector<Eigen::Vector3d> targets;
      for (int f = range.first; f <= range.last; ++f) targets.push_back(input.targets.block<1, 3>(f, column).transpose());
      const LockHeight height = lockHeight(feet, input, feet_world, label, range);
      segment.lock = lockPoint(targets, up, options.lock_shift_cm / input.cm_per_unit) +
                     (input.floor_height + height.above_floor) * up;
      segment.raised = height.raised;
      segments.push_back(segment);
    }
  }

  // The foot's length on the content skeleton (ankle to toe), as it lies when both are planted.
  for (const auto& [heel, toe] : {std::pair{0, 1}, std::pair{2, 3}}) {
    std::vector<double> lengths;
    for (Eigen::Index f = 0; f < feet_world.rows(); ++f)
      lengths.push_back((feet_world.block<1, 3>(f, 3 * heel) - feet_world.block<1, 3>(f, 3 * toe)).norm());
    makeFootLocksConsistent(segments, heel, toe, median(lengths), up);
  }

  ContactLocks locks;
  locks.positions.assign(static_cast<size_t>(frames), {});
  locks.weights = Eigen::MatrixXd::Zero(frames, kContactCount);
  locks.segments = static_cast<int>(segments.size());
  locks.departing = Eigen::MatrixXi::Zero(frames, kContactCount);
  const double tolerance = kLoneLiftToleranceCm / input.cm_per_unit;
  const int blend = std::max(1, static_cast<int>(std::lround(options.contact_blend_seconds * input.content.fps())));
  for (const LockSegment& segment : segments) {
    const ContactSegment& range = segment.frames;
    const int column = 3 * index(kContactJoint[static_cast<size_t>(segment.label)]);
    int first_down = range.last + 1, last_down = range.first - 1;
    for (int f = range.first; f <= range.last; ++f)
      if (up.dot(input.targets.block<1, 3>(f, column).transpose() - segment.lock) <= tolerance) {
        first_down = std::min(first_down, f);
        last_down = f;
      }
    for (int f = std::max(0, range.first - blend); f <= std::min(frames - 1, range.last + blend); ++f) {
      const int distance = f < range.first ? range.first - f : (f > range.last ? f - range.last : 0);
      const double share = smoothstep(1.0 - distance / static_cast<double>(blend + 1));
      const double weight = share >= 1.0 ? options.contact_weight
                                         : std::min(options.contact_weight,
                                                    options.position_weight * std::sqrt(share / (1.0 - share)));
      if (weight > locks.weights(f, segment.label)) {
        locks.weights(f, segment.label) = weight;
        locks.positions[static_cast<size_t>(f)][static_cast<size_t>(segment.label)] = segment.lock;
        // Never down (a lock the targets hold above it throughout): lockHeight placed it, no lift.
        locks.departing(f, segment.label) = last_down >= first_down && (f < first_down || f > last_down);
      }
    }
  }
  raiseLoneLocks(locks, input, options);
  return locks;
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
    const ContentFootHeights content_feet = contentFootHeights(input, feet_world);
    rest = content_feet.rest;
    locks = contactLocks(input, options, content_feet, feet_world);
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
