#pragma once
// Clean-up: turns target joint positions (e.g. the style network's output, converted back into the
// clip's file space by the caller) into a clean clip on the user's OWN skeleton:
//   - bone lengths exact BY CONSTRUCTION (only rotations and the root position are solved; every other
//     joint keeps the content's per-frame local translation),
//   - heels and toes locked to one world position during each labelled contact (blended in and out);
//     where the targets lift a heel or toe before its contact ends (or land it after it starts), the
//     lock holds it still over the floor only and lets it rise with them: alone while the other joint
//     of that foot is free, with it by the smaller lift while both are locked (a quicker toe-off kept),
//     and one lifted past that rolling up on the other joint where that stays down (a toe only on a
//     heel held fully; cleanup_locks.h), those frames marked lifted (CleanupReport::lifted_contacts),
//   - foot joints kept above the floor and, during contact, at the height the content's own foot has
//     there (its median over the contact where the content has that foot planted, else the clip's
//     rest height: captured floors are not flat; the rest height too where the targets hold the foot
//     more than 5 cm below the content's, as where the content kneels on its instep, and the targets'
//     own height where they hold it more than 5 cm above the content's (or above the rest height
//     where the content never plants it there), as a style that runs on the forefoot, and between 1
//     and 5 cm above or below, a lock that moves their way continuously (cleanup_locks.cpp); both joints of
//     a foot at their targets' height where the two stand more than 5 cm above on average, as a style
//     that holds the whole foot up),
//   - joints outside the 21 canonical ones (fingers, clavicles, extra spine, twist) following the
//     content clip's own rotations.
// Everything happens in the clip's FILE SPACE (file length units, file axes), because that is what is
// exported. Thresholds, weights and reported figures are in centimetres via `cm_per_unit`.
//
// Rotations solved as quaternions frame by frame on the joint tree (cleanup_frame_solver.h), the clip in
// chunks on all cores (cleanup_solver.cpp); Ceres, the reference, never appears in this header.

#include <Eigen/Core>
#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "features/feature_layout.h"
#include "mapping/joint_mapping.h"
#include "motion/kinematics.h"
#include "motion/motion.h"

namespace motionstyle {

enum class CleanupSolver { KinematicTree, Ceres };

struct CleanupOptions {
  // --- Cost weights. Each residual is (weight x error), errors in cm or radians, so the weights do not
  // depend on the file's unit. The solver minimises the sum of squared residuals.
  double position_weight = 1.0;         // mapped joint world position vs target, per cm
  // The hips follow their target more firmly than the other joints, so that the character keeps the
  // output's root path (the content's, when its path is kept: style/path_mode.h) while the locked feet
  // and the legs take up what the targets cannot all have. Per cm.
  double hips_weight = 1.0;
  // Locked feet win over the targets: planted feet do not skate (the choice of 40: docs/decisions.md).
  double contact_weight = 40.0;         // heel/toe vs its contact lock position, per cm
  double floor_weight = 20.0;           // foot joint below the floor (one-sided), per cm of depth
  double root_smoothness_weight = 0.5;  // root position second difference (per frame), per cm
  double rotation_smoothness_weight = 5.0;  // solved rotation second difference (per frame), per radian
  double prior_weight_mapped = 2.0;     // rotation vs the content's, joints that are canonical joints, per rad
  // The rig's joints between canonical ones (clavicles, extra spine and neck segments), per rad: held
  // closer to the content than the canonical joints, yet free enough to carry a style's shoulders (the
  // girdle moves 24-26 degrees in Bandai's styles). At 20 the clavicles stayed within 8 degrees of the
  // content's and an angry zombie's shoulder 8.5 cm from its target; at 10 they swing up to 26, at 5 up
  // to 55 (docs/decisions.md, "The clavicles' prior").
  double prior_weight_unmapped = 10.0;

  // --- Contacts. Inside a contact segment the lock has contact_weight. Over contact_blend_seconds
  // before and after it (rounded to frames, at least 1) the lock's share of the pull on the joint,
  // a = w_lock^2 / (w_lock^2 + position_weight^2), ramps with a smoothstep between 0 and 1, so the
  // joint glides between its lock and its targets instead of popping. 0.04 s (one frame at 30 fps, two at
  // 60): at 0.06 a foot that a style lifts off quickly lagged 8-10 cm behind its targets for the ramp
  // (most of the worst residuals at stance ends); shorter still adds pops (docs/decisions.md).
  double contact_blend_seconds = 0.04;
  // How far a lock may move from its stance's median toward the point nearest all its targets, cm
  // (ik/lock_centre.h): enough for a foot the network slides through a long stance (the shifts that
  // halve such slides were all under 3 cm), not enough to pull a stance's still part off its targets
  // toward a step inside it.
  double lock_shift_cm = 5.0;
  bool lock_contacts = true;
  bool keep_above_floor = true;

  // --- Strategy and bounds.
  // KinematicTree (default): each frame solved alone by a Levenberg-Marquardt that follows the joint
  // tree (analytic Jacobians, no fill-in), warm-started from the previous frame's solution, whose two
  // predecessors enter the smoothness terms as constants. Ceres: the same cost solved by Ceres with
  // automatic differentiation, alone or in windows of window_frames frames advancing by
  // window_frames - window_overlap; the reference the tree solver is tested against, several times
  // slower (docs/decisions.md, "Clean-up speed").
  CleanupSolver solver = CleanupSolver::KinematicTree;
  int window_frames = 1;         // > 1 only with CleanupSolver::Ceres
  int window_overlap = 0;
  int max_iterations = 25;       // Levenberg-Marquardt iterations per solve (frame or window), >= 1
  // The clip is solved in chunks of about chunk_frames frames (at least two once the clip is six
  // lead-ins long, and up to four of at least three lead-ins each for a clip of a few hundred frames,
  // so that two cores stay balanced when one is preempted; of equal work), each starting
  // chunk_lead_in frames early from the content's pose (those frames are solved and dropped), so that
  // chunks are independent and run on `threads` cores at once. The result depends on the chunk size,
  // never on the thread count. 40 frames of lead-in leave a chunk within 0.5 mm of one sweep over the
  // whole clip (the smoothness terms' memory of a different start decays per frame, whatever the
  // frame rate).
  int chunk_frames = 480;
  int chunk_lead_in = 40;
  int threads = 0;               // chunks solved at once; 0: one per hardware thread
  // Wall-clock budget for the whole clip. Infinite (the default): every frame is solved, however long
  // the clip. A finite budget is the caller's explicit choice (the CLI's --time-limit): the frames past
  // it are left at their warm start, counted in frames_unsolved and named in a warning. Why: a result
  // that was not produced must never pass for one.
  double max_total_seconds = std::numeric_limits<double>::infinity();
  // Frames per block: the content's local poses are computed, and the result handed out
  // (cleanupMotionInBlocks), this many frames at a time. Memory depends on it; the result only in
  // the last bits (the vectorised sines and cosines round by a value's place in its block).
  int block_frames = kMotionBlockFrames;

  // --- Warnings.
  double unreachable_warning_cm = 1.0;  // a limb whose targets are further apart than it can reach
  double residual_warning_cm = 10.0;    // a mapped joint left further than this from its target
  // A heel or toe its contact holds further than this under its target (the style lifts the foot while
  // the contact track holds it down): the warning names the frames, where the user may end the contact
  // to follow the style. Why: much of a clean clip's worst residual comes from here, the knee and hip
  // following a foot held 5-15 cm under the style's heel-off (docs/decisions.md, "A heel the contact
  // holds down").
  double held_down_warning_cm = 5.0;
  // The frame rate whose frame numbers the warnings name: the clip the user sees or exports, when the
  // solve runs at another rate (style/stylized_cleanup.h solves 120 fps content at 60 fps). A run of
  // solve frames a..b is named by the frames of this rate it overlaps in time:
  //   floor(a * r) .. ceil((b + 1) * r) - 1,  r = warning_fps / the solve's fps.
  // 0 (the default): the solve's own frames.
  double warning_fps = 0.0;

  // Throws std::invalid_argument for a negative or non-finite weight (a warning threshold too), an empty window, an overlap not
  // smaller than the window, a window over 1 frame for the tree solver, max_iterations < 1, a
  // non-positive budget, chunk_frames < 1, chunk_lead_in < 0, threads < 0, block_frames < 1 or a
  // negative or non-finite warning_fps or lock_shift_cm.
  void validate() const;
};

struct CleanupInput {
  CleanupInput(const Motion& content_, const JointMapping& mapping_, Eigen::MatrixXd targets_,
               Eigen::MatrixXi contacts_, const Eigen::Vector3d& up_ = Eigen::Vector3d::UnitY(),
               double floor_height_ = 0.0, double cm_per_unit_ = 1.0)
      : content(content_), mapping(mapping_), targets(std::move(targets_)), contacts(std::move(contacts_)),
        up(up_), floor_height(floor_height_), cm_per_unit(cm_per_unit_) {}

  const Motion& content;         // the user's clip: skeleton (kept whole), frame time, per-frame values
  const JointMapping& mapping;   // joints[c] = index into content.skeleton.joints of canonical joint c
  // frames x 63: world positions of the 21 canonical joints (feature order), FILE units and axes.
  Eigen::MatrixXd targets;
  // frames x 4 (ContactLabel order: left heel = LeftAnkle, left toe, right heel, right toe), 0 or 1.
  Eigen::MatrixXi contacts;
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();  // unit vector in file space (+Y, +Z, ...)
  double floor_height = 0.0;    // file units along `up`
  double cm_per_unit = 1.0;     // centimetres per file unit, > 0

  // Throws std::invalid_argument naming the first problem: an invalid content clip or mapping, a
  // mapping index out of range, frame counts that differ (content, targets, contacts), a column count
  // other than 63 / 4, a non-finite target, a contact value other than 0/1, an up vector that is not
  // unit length, a non-finite floor, a non-positive cm_per_unit, or an empty clip.
  void validate() const;
};

struct CleanupTermCosts {  // 0.5 x sum of squared residuals over all frames (Ceres' convention)
  double position = 0.0;
  double contact = 0.0;
  double floor = 0.0;
  double smoothness = 0.0;
  double prior = 0.0;
  double total() const { return position + contact + floor + smoothness + prior; }
};

// One warning of a clean-up: its text and the frames it names, so that a front end can show them.
struct CleanupWarning {
  std::string text;     // e.g. "targets unreachable: left arm stretched by 12.0 cm at frames 40-60"
  int first_frame = -1;  // the frames it names, inclusive (CleanupOptions::warning_fps); -1: none
  int last_frame = -1;
  // A contact that holds a foot under the style's lift: its ContactLabel, whose contact ended over the
  // frames is the fix the text names (a front end offers it as an action); -1 for every other warning.
  int contact = -1;
};

// The first frame, at a rate `rate_ratio` times the solve's, that overlaps solve frame `frame` in time:
// floor(frame * rate_ratio), 1e-9 added so that 2 x 67 stays 134 whatever the ratio's rounding. How a
// warning names its first frame (CleanupOptions::warning_fps), and how a front end names any solve frame.
int frameAtRate(int frame, double rate_ratio);

struct CleanupReport {
  CleanupTermCosts final_costs;
  int frames = 0;
  int solves = 0;                  // solves (frames or windows), lead-in frames included
  int total_iterations = 0;        // summed over solves
  int solves_at_iteration_cap = 0;  // solves that stopped at max_iterations
  int frames_unsolved = 0;         // frames left at their warm start because the time budget ran out
  int chunks = 0;                  // the clip's chunks (CleanupOptions::chunk_frames)
  int chunks_reused = 0;           // taken unchanged from CleanupControl::memory
  int chunks_warm = 0;             // re-solved from CleanupControl::memory's last solution
  double seconds = 0.0;            // wall clock of cleanupMotion
  int unknown_rotations = 0;       // joints whose rotation is solved (per frame)
  int contact_segments = 0;        // over the four contact tracks
  // Height above the floor of each contact joint while the content has it planted, the median over the
  // clip (ContactLabel order), file units: the lock height of a contact where the content's foot is
  // not down (elsewhere, the content's own height over that contact).
  std::array<double, kContactCount> contact_rest_heights{};
  // frames x 4 (ContactLabel order), 0/1: where the clean-up lets a contact joint follow the style off
  // the floor though its contact holds (a heel or toe the style lands later or lifts off earlier than
  // the content by more than 1 cm, its lock raised over its stance's level: cleanup_locks.cpp). A foot
  // skates only on the floor, so the skate figure of a stylized clip leaves these frames out.
  Eigen::MatrixXi lifted_contacts;
  // Residual of the result on the mapped joints vs the targets, cm.
  double mean_position_residual_cm = 0.0;
  double max_position_residual_cm = 0.0;
  std::vector<CleanupWarning> warnings;
};

// The warnings' texts, in order (for a log or a metrics file).
inline std::vector<std::string> warningTexts(const CleanupReport& report) {
  std::vector<std::string> texts;
  for (const CleanupWarning& warning : report.warnings) texts.push_back(warning.text);
  return texts;
}

// What a clean-up keeps for the next one of the same clip, for re-solving after a small edit: per chunk
// (CleanupOptions::chunk_frames) a digest of everything its solve reads (content, targets, contact
// locks, options) and its solution. The next clean-up given the same memory
//   - reuses a chunk whose digest is unchanged as it is (what a full solve would give, exactly);
//   - re-solves a changed chunk of the same clip and options from its last solution: the sweep's
//     first frame there, every later frame at the frame before's new solution moved by the last
//     solution's step between the two (a strength step moves every frame a little, and neighbouring
//     frames alike; another style's solution brings its motion, not its pose);
//   - solves anything else (another clip, other options, another length) from scratch.
// It holds every solved frame (about 1 KB each on a 24-joint rig): for interactive clips, not for
// streaming a long clip. A chunk's slot is written whole once its solve ends, so a cancelled clean-up
// leaves the memory consistent (the chunks it finished, the rest from before: a live edit that drops a
// just-started job keeps its warm starts); any other failure empties it. One clean-up at a time per
// memory.
class CleanupMemory {
 public:
  CleanupMemory();
  ~CleanupMemory();
  CleanupMemory(const CleanupMemory&) = delete;
  CleanupMemory& operator=(const CleanupMemory&) = delete;
  // This memory's solutions replaced by copies of `other`'s (about 1 KB a frame): a clean-up of other
  // targets on the same clip then starts from them, and `other` keeps its own.
  void copySolutionsFrom(const CleanupMemory& other);
  struct Chunks;
  Chunks& chunks() { return *chunks_; }  // ik/cleanup_solver.cpp's

 private:
  std::unique_ptr<Chunks> chunks_;
};

// How a caller steers one clean-up beyond its options: a cancel flag (checked before every frame;
// OperationCancelled when it turns true) and a memory of the previous clean-up of the clip.
struct CleanupControl {
  const std::atomic<bool>* cancel = nullptr;
  CleanupMemory* memory = nullptr;
};

// One block of the cleaned clip (frames first_frame .. first_frame + values.rows() - 1).
struct CleanedBlock {
  int first_frame = 0;
  const MatrixRowMajor& values;  // the cleaned channel values, as Motion::values
  const Eigen::MatrixXd& world;  // the same frames' world positions of every joint, file units
};
using CleanedBlockSink = std::function<void(const CleanedBlock&)>;

// cleanupMotion handing the result out in blocks of frames (options.block_frames, in frame order)
// instead of returning it, so that a long clip can be written and measured as it is solved: beyond
// what `input` holds, memory grows with the clip only by the contact locks (128 bytes per frame)
// and, while the locks are planned, the feet's positions (96 bytes per frame). The values are exactly
// those cleanupMotion returns. `report` is filled after the last block.
void cleanupMotionInBlocks(const CleanupInput& input, const CleanupOptions& options, const CleanedBlockSink& sink,
                           CleanupReport* report, const CleanupControl& control = {});

// Solves the clip. Returns a Motion on content's skeleton (same hierarchy, names, offsets, channel
// layout, frame time and source) whose values are the solved rotations (degrees, each joint's own Euler
// order) and root positions (file units). Throws std::invalid_argument from the validate steps.
// `report` may be null. Never hangs: every solve is capped in iterations and by the time budget;
// unreachable targets give a best-effort result and a warning. When `world` is not null it receives
// the result's world positions of every joint (frames x 3 joints, file units: worldPositions() of the
// returned Motion up to rounding), which the clean-up computes anyway.
Motion cleanupMotion(const CleanupInput& input, const CleanupOptions& options, CleanupReport* report,
                     const CleanupControl& control = {}, Eigen::MatrixXd* world = nullptr);

}  // namespace motionstyle
