#pragma once
// The kind of locomotion a clip is, read from its motion: the labels a style network's stored style
// targets carry (train_models.sh gives each style clip its kind; training pairs every content clip with
// the target of its file's label, pairTargets). The style refinement aims at the target of the clip's
// kind, as T was trained to, not at whichever target is nearest T's output: a turning walk's output is
// nearer the style's straight walk than its turn, and CMU 131_01's walk nearer some styles' run
// (docs/decisions.md, "The refinement aims at the clip's own kind").
//
//   run              when at least kRunFlightShare of the frames have no heel or toe in contact: a run's
//                    flight; a walk always has a foot down (Bandai's walks and turns: at most 5 % of their
//                    frames, CMU's walks 10-12 %; its runs 23-68 % but the elderly's shuffling runs,
//                    1-19 %, which are read as walks). Without contacts (0 x 0): when the mean forward
//                    speed is at least kRunSpeedCmPerSecond (Bandai's walks at most 156, runs 162-356)
//   walk-turn-left   otherwise, when the mean turning rate is at least kTurnDegreesPerSecond to the left
//                    (Bandai's walks at most 2.3 deg/s either way, its turning walks 13-46)
//   walk-turn-right  the same to the right
//   walk             otherwise: any other clip, standing or kneeling too
// Rates in the representation's units (reference cm, kDefaultFeatureFps).

#include <Eigen/Core>
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "nn/network_file.h"

namespace motionstyle::style {

constexpr double kRunFlightShare = 0.2;
constexpr double kRunSpeedCmPerSecond = 200.0;
constexpr double kTurnDegreesPerSecond = 8.0;

// Every kind, as the style targets label them.
constexpr std::array<std::string_view, 4> kLocomotionKinds = {"walk", "run", "walk-turn-left", "walk-turn-right"};
bool isLocomotionKind(std::string_view kind);
// The kinds for a message: "walk, run, walk-turn-left or walk-turn-right".
std::string locomotionKindList();
// A kind to aim at given by a caller: "" (none given) or one of kLocomotionKinds. Throws
// std::invalid_argument "<what> '<kind>' is none of walk, run, ..." for any other.
void requireKindOrNone(const std::string& kind, std::string_view what);
// In words for the user: "walk", "run", "walk turning left", "walk turning right" (the kind itself
// for any other string).
std::string locomotionKindText(std::string_view kind);

// features: 66 x frames (frames >= 1), representation units; contacts: 4 x frames, 0/1, or 0 x 0.
// Returns "run", "walk-turn-left", "walk-turn-right" or "walk". Throws std::invalid_argument for other
// shapes.
std::string locomotionKind(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts);

// The target a clip of `kind` is paired with, as training pairs it (pairTargets): the one labelled
// `kind`; a turn without its own target, the walk's; else the default (label ""); -1 when none is.
int styleTargetFor(const std::vector<nn::StyleTarget>& targets, const std::string& kind);

}  // namespace motionstyle::style
