#pragma once
// How familiar a clip is to a loss network: the network is a loss network trained on the motion the
// style networks learnt from, so how well it reconstructs a clip says how close the clip is to that
// motion, and so how much to trust a stylized result (the paper's manifold projection distorts what it
// cannot reconstruct).
//
//   error(t)  = mean over the 21 canonical joints j of | p_j(L(C))(t) - p_j(C)(t) |
//               in the root frame, reference cm (features/feature_layout.h), L = decode(encode(.))
//   clip      = mean of error(t) over the frames
//
// The reading of the clip figure (thresholds calibrated on clips of other studios, docs/decisions.md):
//   familiar  <= kFamiliarMaxCm   results like those on the training data
//   unusual   <= kUnusualMaxCm    results usable; adapting the networks to such clips helps
//   far        > kUnusualMaxCm    results will be weak: adapt the networks to clips like this one

#include <Eigen/Core>
#include <string>
#include <vector>

#include "nn/network_file.h"
#include "style/stylizer.h"

namespace motionstyle::style {

constexpr double kFamiliarMaxCm = 1.5;
constexpr double kUnusualMaxCm = 2.5;

enum class FamiliarityLevel { Familiar, Unusual, Far };

struct Familiarity {
  std::vector<double> per_frame_cm;  // error(t), one per feature frame (60 fps)
  double mean_cm = 0.0;              // the clip figure
  double worst_second_cm = 0.0;      // the largest mean over any one second of frames
  FamiliarityLevel level = FamiliarityLevel::Familiar;
};

// features: 66 x frames (frames >= 1), representation units. Throws std::invalid_argument otherwise.
Familiarity measureFamiliarity(const nn::LossNetworkModel& loss_network, const Eigen::MatrixXd& features);
// The same through a style network's own loss network.
Familiarity measureFamiliarity(const nn::StyleModel& network, const Eigen::MatrixXd& features);
// The same through a Stylizer's prepared network (cheaper when one network reads many clips).
Familiarity measureFamiliarity(const Stylizer& stylizer, const Eigen::MatrixXd& features);
// The reading from a reconstruction already computed: reconstructed = L(features), both 66 x frames
// (for callers that need L(C) for more than this, e.g. evaluation.h).
Familiarity familiarityFromReconstruction(const Eigen::MatrixXd& features, const Eigen::MatrixXd& reconstructed);

FamiliarityLevel familiarityLevel(double mean_cm);
// "familiar", "unusual", "far"
const char* familiarityName(FamiliarityLevel level);
// One plain sentence for the user: the reading and the next step, e.g.
// "unusual (2.1 cm): results usable; adapt the networks to your clips for better ones".
std::string familiaritySummary(const Familiarity& familiarity);

}  // namespace motionstyle::style
