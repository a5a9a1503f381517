// The clean-up's contact locks (cleanup_locks.h): lock heights, the foot's two locks kept a foot's
// length apart, and locks that rise with a style's earlier lift-off.

#include "ik/cleanup_locks.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "features/foot_contacts.h"
#include "features/signal_filters.h"
#include "ik/lock_centre.h"

namespace motionstyle::ik_detail {
namespace {

// The content's contact joints (ContactLabel order) as the columns of feet_world (frames x 12).
constexpr std::array<int, kContactCount> kFeetColumns = {0, 1, 2, 3};

// Height above the floor of the point in columns column..column+2 of `positions` at frame f, file units.
double heightAboveFloor(const CleanupInput& input, const Eigen::MatrixXd& positions, int f, int column) {
  return input.up.dot(positions.block<1, 3>(f, column).transpose()) - input.floor_height;
}

// The median height above the floor of contact joint `label` over frames first..last where the content
// has it planted (at least 0), file units; nothing when it is planted on none of them.
std::optional<double> plantedHeight(const ContactLabels& planted, const CleanupInput& input,
                                    const Eigen::MatrixXd& feet_world, int label, int first, int last) {
  std::vector<double> heights;
  for (int f = first; f <= last && f < planted.rows(); ++f)
    if (planted(f, label) != 0)
      heights.push_back(heightAboveFloor(input, feet_world, f, 3 * label));
  if (heights.empty()) return std::nullopt;
  return std::max(0.0, median(std::move(heights)));
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
// Between the two, where the targets hold the joint |h| <= kLockHeightToleranceCm from the content's
// planted height, the lock moves their way continuously from kLiftDeadZoneCm on, by the share
//   s(|h|) = (max(0, |h| - d) / (T - d))^2,  T = kLockHeightToleranceCm, d = kLiftDeadZoneCm,
// of the way to the rule it meets at T: up by s T (at T, the targets' height), down by s times the way
// to the rest height where that is lower (at -T, the rest height). Why: at T a style that held a foot
// 4.5 cm up was locked on the floor, 4.5 cm under its targets, and at 5.5 cm up on them (CMU 131_01's
// way out of the kneel: happy's toe 9.3 cm from its targets; a heel the style holds 3-6 cm under a
// content's that sinks through its last stance: elderly's knee 8.3 cm; docs/decisions.md, "Stances
// held in the stylizer"). Within d, the network's own wobble, the lock stays at the content's height.
// Where the content does not plant the joint over the segment (a contact found on the output alone, or
// forced on), the lock stands at the rest height, or lower where the content's own joint goes lower over
// the segment (an uneven floor: CMU 07_01's toe 3.6 cm under its rest height at its first step, where
// youthful's toe was locked 7.1 cm over its targets), and the same share moves it up from there, with h
// the targets' LOWEST over the segment above it: a heel the style holds still 4 cm up (Bandai's
// walk-turn-left_active_037 with sad, at its first frames) was locked at the rest height, the knee
// 9.8 cm from its target; the lowest rather than the median so that a foot the targets keep swinging
// through a forced contact stays down.
constexpr double kLockHeightToleranceCm = 5.0;
constexpr double kLiftDeadZoneCm = 1.0;

double partialShare(double away_cm) {
  const double x = std::max(0.0, (away_cm - kLiftDeadZoneCm) / (kLockHeightToleranceCm - kLiftDeadZoneCm));
  return x * x;
}

struct LockHeight {
  double above_floor = 0.0;          // the lock's, file units
  bool raised = false;               // the targets' height, above the content's
  double targets_above_floor = 0.0;  // the targets' median height over the segment, file units
  double targets_over_content_cm = 0.0;  // that height less the content's planted (else rest or lowest), cm
};

LockHeight lockHeight(const ContentFootHeights& feet, const CleanupInput& input, const Eigen::MatrixXd& feet_world,
                      int label, const ContactSegment& range) {
  const double rest = feet.rest[static_cast<size_t>(label)];
  const std::optional<double> planted = plantedHeight(feet.planted, input, feet_world, label, range.first, range.last);
  const int column = 3 * index(kContactJoint[static_cast<size_t>(label)]);
  std::vector<double> heights;
  for (int f = range.first; f <= range.last; ++f)
    heights.push_back(heightAboveFloor(input, input.targets, f, column));
  const double lowest = *std::min_element(heights.begin(), heights.end());
  const double target_height = median(std::move(heights));
  double content_lowest = rest;
  for (int f = range.first; f <= range.last; ++f)
    content_lowest = std::min(content_lowest, heightAboveFloor(input, feet_world, f, 3 * label));
  const double content_height = planted ? *planted : std::max(0.0, content_lowest);
  const double above_content_cm = (target_height - content_height) * input.cm_per_unit;
  if (above_content_cm > kLockHeightToleranceCm) return {target_height, true, target_height, above_content_cm};
  if (!planted) {
    const double share = partialShare((lowest - content_height) * input.cm_per_unit);
    return {content_height + share * kLockHeightToleranceCm / input.cm_per_unit, false, target_height, above_content_cm};
  }
  if (above_content_cm < -kLockHeightToleranceCm) return {rest, false, target_height, above_content_cm};
  const double share = partialShare(std::abs(above_content_cm));
  const double moved = above_content_cm >= 0.0 ? share * kLockHeightToleranceCm / input.cm_per_unit
                                               : share * std::min(0.0, rest - *planted);
  return {*planted + moved, false, target_height, above_content_cm};
}

struct LockSegment {
  int label = 0;
  ContactSegment frames;
  Eigen::Vector3d lock = Eigen::Vector3d::Zero();  // file units
  LockHeight height;
};

// A foot the style holds up whole: where a heel and a toe lock of one foot overlap and only one of them
// is raised (lockHeight), the other is raised to its targets' median height too when the two joints'
// targets stand on average more than kLockHeightToleranceCm over the content's,
//   (over_heel + over_toe) / 2 > kLockHeightToleranceCm.
// Why: the raised one then pivoted down to the other's lock on the content's height
// (makeFootLocksConsistent), both joints several cm under their targets (CMU 131_01's way into the
// kneel, the style holding the heel 6.2 and the toe 5.0 cm up: angry 10.8 -> 7.4 cm; docs/decisions.md,
// "A foot the style holds up whole").
void raiseWholeFeet(std::vector<LockSegment>& segments, int heel, int toe, const Eigen::Vector3d& up) {
  for (LockSegment& a : segments) {
    if (a.label != heel) continue;
    for (LockSegment& b : segments) {
      if (b.label != toe || a.height.raised == b.height.raised) continue;
      if (std::min(a.frames.last, b.frames.last) < std::max(a.frames.first, b.frames.first)) continue;  // apart
      if (0.5 * (a.height.targets_over_content_cm + b.height.targets_over_content_cm) <= kLockHeightToleranceCm) continue;
      LockHeight& low = a.height.raised ? b.height : a.height;
      (a.height.raised ? b.lock : a.lock) += (low.targets_above_floor - low.above_floor) * up;
      low.above_floor = low.targets_above_floor;
      low.raised = true;
    }
  }
}

int frameCount(const LockSegment& segment) { return segment.frames.last - segment.frames.first + 1; }
constexpr int kAnchorLengthRatio = 3;

// Heel and toe locks of one foot that are active together must sit as far apart as the foot is long,
// or the solver, unable to meet both, moves the toe when the heel lock lets go (a visible skate).
// Segments are visited in start order, so that chains of overlaps stay consistent, and the later of
// two overlapping segments is moved along the floor so that the two locks lie the foot's length apart
// (their heights kept), or, where its height is lockHeight's blend and that moves it less than half as
// far, pivoted about the other as below. But where one of the two is raised (lockHeight) and the other is not, the
// raised one moves, up or down: the foot pivots on the joint that is down, so the raised lock keeps its
// place over the floor and takes the height at which it lies the foot's length from the other, on the
// side of it (above or below) where it was: a toe raised a few cm is still under its heel. Moved
// along the floor instead, a heel raised 15 cm toward a toe on the floor came 12 cm from its targets
// (docs/decisions.md). An earlier raised lock already placed against its own partner is not moved again.
// A lock more than kAnchorLengthRatio times shorter than the later one it overlaps most (a landing's
// first frames, found on the output only) is the one moved, where no lock was placed against it or it
// against one already (the chain kept): it anchored a whole stance's lock before.
void makeFootLocksConsistent(std::vector<LockSegment>& segments, int heel, int toe, double foot_length,
                             const Eigen::Vector3d& up) {
  std::vector<LockSegment*> foot;
  for (LockSegment& segment : segments)
    if (segment.label == heel || segment.label == toe) foot.push_back(&segment);
  std::sort(foot.begin(), foot.end(), [](const LockSegment* a, const LockSegment* b) {
    return a->frames.first < b->frames.first;
  });
  std::vector<bool> placed(foot.size(), false);    // moved to lie the foot's length from a partner
  std::vector<bool> anchoring(foot.size(), false);  // a partner was moved to lie the foot's length from it
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
    // A brief anchor moves instead (a 3-frame heel lock of a landing found on the output set the toe's
    // 33-frame lock 5 cm behind its targets: feminine on Bandai's walk_proud_002, 8.3 -> 6.7 cm).
    size_t moved = i, fixed_at = anchor;
    if (!placed[anchor] && !anchoring[anchor] && kAnchorLengthRatio * frameCount(*foot[anchor]) < frameCount(later))
      std::swap(moved, fixed_at);
    LockSegment& moving = *foot[moved];
    const LockSegment& fixed = *foot[fixed_at];
    const bool raise_moving = moving.height.raised && !fixed.height.raised;
    const bool raise_fixed = fixed.height.raised && !moving.height.raised && !placed[fixed_at];
    if (raise_moving || raise_fixed) {
      LockSegment& raised = *foot[raise_moving ? moved : fixed_at];
      const LockSegment& down = *foot[raise_moving ? fixed_at : moved];
      Eigen::Vector3d across = raised.lock - down.lock;
      const double side = up.dot(across) < 0.0 ? -1.0 : 1.0;  // a raised toe can still be under its heel
      across -= up.dot(across) * up;
      const double horizontal = across.norm();
      if (horizontal < foot_length)
        raised.lock = down.lock + across + side * std::sqrt(foot_length * foot_length - horizontal * horizontal) * up;
      else if (horizontal > 1e-9)  // further than the foot is long: brought in, level with the other
        raised.lock = down.lock + across * (foot_length / horizontal);
      placed[raise_moving ? moved : fixed_at] = true;
      anchoring[raise_moving ? fixed_at : moved] = true;
      continue;
    }
    Eigen::Vector3d along = moving.lock - fixed.lock;
    const double height = up.dot(along);
    along -= height * up;
    if (along.norm() < 1e-9) continue;  // no direction to keep: leave it
    const double horizontal_length = std::sqrt(std::max(0.0, foot_length * foot_length - height * height));
    const Eigen::Vector3d slid = fixed.lock + along.normalized() * horizontal_length + height * up;
    // Or, a lock whose height is a blend (lockHeight's partial share, not its targets' own height),
    // pivoted about the other, its place over the floor kept, where that moves it less than half as
    // far (a planted foot's height shows more than its place), never under the lower of the two locks:
    // where the blended heights leave the foot steeper than the targets' (a heel mostly raised toward a
    // forefoot stance, its toe little), the slide put it far from its targets.
    const double side = height < 0.0 ? -1.0 : 1.0;
    const Eigen::Vector3d pivoted =
        fixed.lock + along + side * std::sqrt(std::max(0.0, foot_length * foot_length - along.squaredNorm())) * up;
    const bool pivot = !moving.height.raised && along.norm() < foot_length &&
                       up.dot(pivoted) >= std::min(up.dot(moving.lock), up.dot(fixed.lock)) &&
                       (pivoted - moving.lock).norm() < 0.5 * (slid - moving.lock).norm();
    moving.lock = pivot ? pivoted : slid;
    placed[moved] = true;
    anchoring[fixed_at] = true;
  }
}

// Where the style lands a heel or toe later than the content's contact starts, or lifts it off
// earlier than it ends, the lock holds it still over the floor but not under its targets. Its level
// is the higher of the lock's height and the targets' lowest over the segment (the style's own stance
// height; ContactLocks::down_level); on the frames before the first and after the last at which the
// targets hold the joint within kLiftToleranceCm of that level (ContactLocks::departing, ramps
// included) the joint may rise by
//   lift = max(0, up . target - level - tolerance),
// and, a lock raised to the style's height (ContactLocks::kRisingOrFalling), fall as well where the
// targets are lower: lift = max(floor - level, up . target - level + tolerance) < 0;
// its lock moves by (1 - a_other) x lift + a_other x (tied + roll) along up (plus a_other x the roll's
// move along the floor), a_other the foot's other joint's lock share (its ramp's,
// CleanupOptions::contact_blend_seconds; 0 where it is free), tied the smaller of the two lifts where
// both move the same way (lift_other is 0 unless that joint departs too), else 0, and roll, where
// lift - tied > tolerance, the turn of this lock about the other's, their distance kept, by
// lift - tied - tolerance or as far as the foot's length lets it (rollAbout). A toe rolls on its heel
// only where the heel's lock holds fully (inside its contact, not in its ramp).
// So a lone joint rises (falls) with its targets; a heel and toe both locked move together by the
// smaller move, which keeps the foot's length between them; a joint lifted further rolls on the other,
// which holds still; and in a stance's middle nothing moves, where a lock following the targets' bobs
// would float a planted foot. Each raised lock is marked lifted (ContactLocks::lifted).
// Why: held on the floor, a heel or toe the style lifts (a quicker heel- or toe-off, a toe that lands
// after its heel) pulled the knee and hip 5-15 cm off their targets; a toe turning about a heel still
// in its ramp moved along the floor. Figures: docs/decisions.md, "A toe the style lifts off" onward to
// "A toe that rolls on its heel".
constexpr double kLiftToleranceCm = 1.0;
// A lock raised by more than this is marked lifted: a millimetre, under what the eye sees, over the
// hundredths a lock tied to its held partner moves (a_other is under 1).
constexpr double kLiftedCm = 0.1;

// The turn of one joint's `lock` about its foot's other joint's `pivot` in their vertical plane, their
// distance kept, that raises it by `rise` relative to the pivot, or as far as the foot's length lets it
// (to stand over the pivot): the rise it reaches and its move along the floor (toward the pivot for a
// heel above its toe; away from it at first for a toe below its ankle). None where the lock stands
// straight above or below the pivot.
struct Roll {
  double rise = 0.0;
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();
};
Roll rollAbout(const Eigen::Vector3d& lock, const Eigen::Vector3d& pivot, double rise, const Eigen::Vector3d& up) {
  const Eigen::Vector3d between = lock - pivot;
  const double vertical = up.dot(between);
  const Eigen::Vector3d along = between - vertical * up;
  const double across = along.norm(), length = between.norm();
  if (!(across > 1e-9 * length)) return {};
  const double raised = std::min(vertical + rise, length);
  const double reached_across = std::sqrt(std::max(0.0, length * length - raised * raised));
  return {raised - vertical, (reached_across - across) / across * along};
}

bool isHeel(int label) { return label % 2 == 0; }  // ContactLabel order: heel, toe per foot

void raiseDepartingLocks(ContactLocks& locks, const CleanupInput& input, const CleanupOptions& options) {
  const double tolerance = kLiftToleranceCm / input.cm_per_unit;
  const double position_weight2 = options.position_weight * options.position_weight;
  for (Eigen::Index f = 0; f < locks.weights.rows(); ++f) {
    std::array<double, kContactCount> lift{};
    for (int label = 0; label < kContactCount; ++label) {
      if (locks.weights(f, label) <= 0.0 || locks.departing(f, label) == 0) continue;
      const int column = 3 * index(kContactJoint[static_cast<size_t>(label)]);
      const double height = input.up.dot(input.targets.block<1, 3>(f, column).transpose());
      const double over = height - locks.down_level(f, label);
      lift[static_cast<size_t>(label)] =
          over > tolerance ? over - tolerance
          : locks.departing(f, label) == ContactLocks::kRisingOrFalling && over < -tolerance
              ? std::max(input.floor_height - locks.down_level(f, label), over + tolerance)
              : 0.0;
    }
    std::array<Eigen::Vector3d, kContactCount>& placed = locks.positions[static_cast<size_t>(f)];
    const std::array<Eigen::Vector3d, kContactCount> before = placed;
    for (int label = 0; label < kContactCount; ++label) {
      const double own = lift[static_cast<size_t>(label)];
      if (own == 0.0) continue;
      const double other_weight = locks.weights(f, label ^ 1);
      const double other_share =  // 0 where the other joint is free (also when position_weight is 0)
          other_weight <= 0.0 ? 0.0 : other_weight * other_weight / (other_weight * other_weight + position_weight2);
      const double other = lift[static_cast<size_t>(label ^ 1)];
      const double tied = own > 0.0 ? std::max(0.0, std::min(own, other)) : std::min(0.0, std::max(own, other));
      Roll roll;
      const bool may_roll = isHeel(label) || other_weight >= options.contact_weight;  // a toe: on a held heel
      if (may_roll && own - tied > tolerance && other_share > 0.0)
        roll = rollAbout(before[static_cast<size_t>(label)], before[static_cast<size_t>(label ^ 1)], own - tied - tolerance,
                         input.up);
      const double rise = (1.0 - other_share) * own + other_share * (tied + roll.rise);
      placed[static_cast<size_t>(label)] += rise * input.up + other_share * roll.shift;
      if (rise > kLiftedCm / input.cm_per_unit) locks.lifted(f, label) = 1;
    }
  }
}

}  // namespace

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

ContactLocks contactLocks(const CleanupInput& input, const CleanupOptions& options, const ContentFootHeights& feet,
                          const Eigen::MatrixXd& feet_world) {
  const int frames = static_cast<int>(input.targets.rows());
  const Eigen::Vector3d& up = input.up;
  std::vector<LockSegment> segments;
  for (int label = 0; label < kContactCount; ++label) {
    const int column = 3 * index(kContactJoint[static_cast<size_t>(label)]);
    for (const ContactSegment& range : contactSegments(input.contacts, label)) {
      LockSegment segment{label, range, {}, {}};
      std::vector<Eigen::Vector3d> targets;
      for (int f = range.first; f <= range.last; ++f) targets.push_back(input.targets.block<1, 3>(f, column).transpose());
      segment.height = lockHeight(feet, input, feet_world, label, range);
      segment.lock = lockPoint(targets, up, options.lock_shift_cm / input.cm_per_unit) +
                     (input.floor_height + segment.height.above_floor) * up;
      segments.push_back(segment);
    }
  }

  // The foot's length on the content skeleton (ankle to toe), as it lies when both are planted.
  for (const auto& [heel, toe] : {std::pair{0, 1}, std::pair{2, 3}}) {
    std::vector<double> lengths;
    for (Eigen::Index f = 0; f < feet_world.rows(); ++f)
      lengths.push_back((feet_world.block<1, 3>(f, 3 * heel) - feet_world.block<1, 3>(f, 3 * toe)).norm());
    raiseWholeFeet(segments, heel, toe, up);
    makeFootLocksConsistent(segments, heel, toe, median(lengths), up);
  }

  ContactLocks locks;
  locks.positions.assign(static_cast<size_t>(frames), {});
  locks.weights = Eigen::MatrixXd::Zero(frames, kContactCount);
  locks.segments = static_cast<int>(segments.size());
  locks.departing = Eigen::MatrixXi::Zero(frames, kContactCount);
  locks.down_level = Eigen::MatrixXd::Zero(frames, kContactCount);
  locks.lifted = Eigen::MatrixXi::Zero(frames, kContactCount);
  const double tolerance = kLiftToleranceCm / input.cm_per_unit;
  const int blend = std::max(1, static_cast<int>(std::lround(options.contact_blend_seconds * input.content.fps())));
  for (const LockSegment& segment : segments) {
    const ContactSegment& range = segment.frames;
    const int column = 3 * index(kContactJoint[static_cast<size_t>(segment.label)]);
    double lowest = up.dot(input.targets.block<1, 3>(range.first, column).transpose());
    for (int f = range.first + 1; f <= range.last; ++f)
      lowest = std::min(lowest, up.dot(input.targets.block<1, 3>(f, column).transpose()));
    // raiseDepartingLocks' level; the lowest target lies within it, so every segment has a down frame.
    const double level = std::max(up.dot(segment.lock), lowest);
    // A raised lock is held down only where its targets are within the tolerance either way.
    const bool raised = segment.height.raised;
    int first_down = range.last + 1, last_down = range.first - 1;
    for (int f = range.first; f <= range.last; ++f)
      if (const double over = up.dot(input.targets.block<1, 3>(f, column).transpose()) - level;
          over <= tolerance && (!raised || over >= -tolerance)) {
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
        locks.departing(f, segment.label) = f >= first_down && f <= last_down ? ContactLocks::kHeld
                                            : raised                          ? ContactLocks::kRisingOrFalling
                                                                              : ContactLocks::kRising;
        locks.down_level(f, segment.label) = level;
      }
    }
  }
  raiseDepartingLocks(locks, input, options);
  return locks;
}

}  // namespace motionstyle::ik_detail
