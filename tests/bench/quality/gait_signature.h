#pragma once
// The gait signature: nine figures of how a clip walks or runs, read from its features (66 x frames,
// root frame, reference cm; feature_layout.h) without any network, so that they judge a stylized clip
// apart from the loss network that the style networks were trained with and that eval's style ratio
// and content distance are measured in. Means over the clip's frames of:
//   head height, hips height, forward trunk lean (hips to neck, atan2(forward, up), rad), knee and elbow
//   angles (rad, both sides), hands' height over the hips, stance width (the ankles' sideways distance),
//   hands' sideways distance from the hips; and the arm swing (the standard deviation of each wrist's
//   forward offset from the hips, both sides).
// The share of a style's signature an output took on:
//   mean over the figures with |s_k - c_k| > resolution_k of clamp((o_k - c_k) / (s_k - c_k), -1, 2)
// (c the content's, s the style clip's, o the output's figures): 1 when the output moved every figure the
// style differs in by the style's whole difference, 0 when it moved none, negative away from the style.
// Speed and cadence are left out: the path is kept (path_mode.h), so they are the content's.
// Why: issue 12's reporter measured "how much of the style's gait signature was added"; fitting the
// output motion to eval's style ratio through the loss network improved that ratio while this share
// fell (docs/decisions.md, "The motion fit, judged by the gait signature").

#include <Eigen/Core>
#include <array>

namespace motionstyle::bench {

// The figures, in the signature's order (cm, or rad for the lean and the angles).
enum GaitFigure : int {
  kHeadHeight, kHipsHeight, kTrunkLean, kKneeAngle, kElbowAngle, kHandHeight, kStanceWidth, kHandSpread,
  kArmSwing, kGaitFigureCount
};
using GaitSignature = std::array<double, kGaitFigureCount>;

// Throws std::invalid_argument unless features is 66 x frames with frames >= 1.
GaitSignature gaitSignature(const Eigen::MatrixXd& features);

// The share above; 0 when the style differs from the content in no figure.
double gaitSignatureShare(const GaitSignature& content, const GaitSignature& style, const GaitSignature& output);

}  // namespace motionstyle::bench
