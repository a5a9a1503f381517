#pragma once
// The clean-up's contact locks (cleanup.h's contract: heels and toes locked during each labelled
// contact, at the content's own height or the style's, blended in and out): per solved frame, where
// each heel and toe is held and how strongly. Internal to the clean-up (cleanup.cpp); the decisions
// behind each rule are in docs/decisions.md ("Planted feet on other rigs" onward).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "ik/cleanup.h"
#include "ik/contacts.h"

namespace motionstyle::ik_detail {

// Where the CONTENT clip has each contact joint planted (its own detected contacts) and how high above
// the floor it is then, file units: one median per joint for the whole clip (`rest`), the fallback for
// a lock where the content's foot is not down. A joint never planted in the content keeps the
// low-percentile estimate, which is what detection itself assumes. feet_world: the content's contact
// joints.
struct ContentFootHeights {
  std::array<double, kContactCount> rest{};
  ContactLabels planted;
};

// The clip-wide rest heights and planted frames of the content's contact joints. feet_world: frames x
// 12, the content's heel and toe positions (ContactLabel order), file units.
ContentFootHeights contentFootHeights(const CleanupInput& input, const Eigen::MatrixXd& feet_world);

// Per frame, the lock of each contact joint (its world position) and its weight (0: free).
struct ContactLocks {
  std::vector<std::array<Eigen::Vector3d, kContactCount>> positions;  // per frame, file units
  Eigen::MatrixXd weights;                                            // frames x 4
  // frames x 4: where the frame lies before the first or after the last frame of its segment at
  // which the targets hold the joint down (within kLiftToleranceCm of down_level): the style has not
  // landed yet, or has lifted off already (raiseDepartingLocks). kRising there: the lock may rise with
  // its targets; kRisingOrFalling, a lock raised to the style's height (lockHeight), whose targets
  // hold it down only within kLiftToleranceCm either way: it may also fall with them, to the floor.
  enum Departure : int { kHeld = 0, kRising = 1, kRisingOrFalling = 2 };
  Eigen::MatrixXi departing;
  // frames x 4, along up in file units: the segment's lock height or the targets' lowest over the
  // segment, whichever is higher (the style may hold a stance a little above the lock).
  Eigen::MatrixXd down_level;
  // frames x 4: 1 where raiseDepartingLocks raised the lock more than 1 mm over where the stance holds
  // it (its targets more than kLiftToleranceCm over the stance's level): the joint follows the style
  // off the floor though its contact holds.
  Eigen::MatrixXi lifted;
  int segments = 0;
};

// One lock point per contact segment: the targets' median moved toward their minimax point on the
// floor plane by at most lock_shift_cm (lock_centre.h), at floor + the lock's height (the content's
// planted height, the rest height, or the style's). Its weight is full inside the segment; on either
// side the lock's share of the pull ramps down (CleanupOptions::contact_blend_seconds); where two ramps
// meet, the nearer segment wins. Heel and toe locks of a foot are set the foot's length apart, and a
// joint the style lifts off early or lands late rises with its targets, rolling on the foot's other
// joint where that stays down (cleanup_locks.cpp).
ContactLocks contactLocks(const CleanupInput& input, const CleanupOptions& options, const ContentFootHeights& feet,
                          const Eigen::MatrixXd& feet_world);

}  // namespace motionstyle::ik_detail
