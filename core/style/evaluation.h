#pragma once
// Evaluation of a style network on clips it never trained on (motionstyle-cli eval), as a JSON report.
//
// Per clip, with C the content's features, Y = Stylizer::stylize(C).features (T then the manifold
// projection, strength 1: the output the user gets, its stances held in the clip's own rig) and S the
// style clip paired with C (style_pairing.h):
//   reconstruction_mse        mean over values of (L(C) - C)^2 in NORMALISED units, L = decode(encode(.))
//   reconstruction_joint_error_cm   mean distance between the joints of L(C) and C in the root frame
//                             (the 63 position values), reference cm
//   content_distance          eq. 4 unweighted, mean over hidden units and pooled frames of
//                             (enc(X) - enc(C))^2: "before" X = L(C) (what the projection alone costs),
//                             "after" X = Y
//   style_distance            eq. 5 unweighted, mean over entries of (Gram(enc(X)) - Gram(enc(S)))^2 with
//                             nn::gramMatrix: "before" X = C, "after" X = Y; ratio = after / before;
//                             "projection_only" X = L(C), the content through the projection alone, and
//                             projection_ratio = projection_only / before: how much of the change the
//                             projection makes without the style network (ratio vs projection_ratio)
//   bone_error_cm             mean over frames and the 20 bones of | |p_child - p_parent| - l_b |, l_b the
//                             content's mean bone length; for C and for Y (the raw output, no IK)
//   foot_skate_cm_s           mean horizontal speed of a foot over the frame pairs (t, t+1) at which the
//                             CONTENT labels a joint of it in contact at both frames, at the slower of
//                             those joints (ik/metrics.h), world positions at the reference scale, cm
//                             per second; for C and for Y
//   familiarity               the reading of reconstruction_joint_error_cm (familiarity.h)
//   network_path              how far the NETWORK's own root motion strays from C's (root_path.h):
//                             distance_ratio, end_error_fraction; the output judged above follows
//                             `path` (path_mode.h), by default C's own path
//   stylize_seconds           wall time of stylize(C)
// "Reference cm": characters are scaled to kReferenceSkeletalHeightCm (features/representation.h), so
// figures compare across characters; the Bandai actors are at about their real size.
// Summary: frame-weighted means over the clips, plus frames per second of stylize.
// Encoders: the style network's own loss network (the one it was trained against) for the distances,
// the given loss network for the reconstruction figures.

#include <string>
#include <vector>

#include "nn/network_file.h"
#include "style/motion_dataset.h"
#include "style/path_mode.h"
#include "style/style_refinement.h"

namespace motionstyle::style {

struct ClipEvaluation {
  std::string file;
  std::string style_clip;
  int frames = 0;
  double reconstruction_mse = 0;
  double reconstruction_joint_error_cm = 0;
  double content_distance_before = 0;
  double content_distance_after = 0;
  double style_distance_before = 0;
  double style_distance_after = 0;
  double style_distance_projection = 0;  // X = L(C): the projection alone, no style network
  double bone_error_cm_content = 0;
  double bone_error_cm_output = 0;
  double foot_skate_cm_s_content = 0;
  double foot_skate_cm_s_output = 0;
  double network_path_distance_ratio = 1;
  double network_path_end_error_fraction = 0;
  double stylize_seconds = 0;
};

struct EvaluationReport {
  std::string loss_network_file;
  std::string network_file;
  bool loss_network_matches_network = true;  // the given loss network is the network's own loss network
  std::vector<ClipEvaluation> clips;
  ClipEvaluation mean;                      // frame-weighted means (file = "mean")
  double stylize_frames_per_second = 0;
  double seconds = 0;                       // wall time of the whole evaluation
};

// clips: the content clips; styles: the style clips; pairing[i] indexes `styles` for clips[i]. The
// network runs as the Stylizer does with `refinement`.
EvaluationReport evaluateStyleNetwork(const nn::LossNetworkModel& loss_network, const nn::StyleModel& network,
                                      const std::vector<MotionClip>& clips, const std::vector<MotionClip>& styles,
                                      const std::vector<int>& pairing, PathMode path = PathMode::Content,
                                      const StyleRefinement& refinement = {});

// The distances of the report for one output: eq. 4 between `output` and `content`, eq. 5 of `content`
// and of `output` to the style clip's Gram matrix, all through `encoder` (features 66 x frames in
// representation units; `style_gram` from nn::styleGram). The style ratio says how much style was added.
struct StyleDistances {
  double content_after = 0;
  double style_before = 0;
  double style_after = 0;
  double styleRatio() const { return style_before > 0 ? style_after / style_before : 0.0; }
};
StyleDistances measureStyleDistances(const nn::LossNetwork<float>& encoder, const FeatureStatistics& normalisation,
                                     const Eigen::MatrixXd& content, const Eigen::MatrixXd& output,
                                     const nn::Mat<float>& style_gram);
// Gram(L(S)) of a style clip's features (representation units) through `encoder`.
nn::Mat<float> styleGramOf(const nn::LossNetwork<float>& encoder, const FeatureStatistics& normalisation,
                           const Eigen::MatrixXd& style);

// Figures used by the report, public for tests and the GUI's metrics panel. features: 66 x frames,
// representation units. foot skate uses `contacts` (4 x frames) and the anchor's fps.
double boneLengthError(const Eigen::MatrixXd& features, const Eigen::VectorXd& bone_lengths);
double footSkate(const Eigen::MatrixXd& features, const Eigen::MatrixXd& contacts, const FeatureAnchor& anchor);

std::string evaluationJson(const EvaluationReport& report);

}  // namespace motionstyle::style
