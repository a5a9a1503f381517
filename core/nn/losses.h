#pragma once
// Every loss term of the paper (eq. 3-10), each as value + gradient.
//
// Convention for every function here: it returns the UNWEIGHTED value of its term and, when `grad` is
// not null, ADDS weight * d(term)/d(input) into *grad, which must already have the input's shape. The
// caller sums weight * value for the total (eq. 10, see transformation_objective.h).
//
// Spaces: the networks see NORMALISED frames x_n = (x - mean) / std (per feature, 66 values,
// feature_layout.h). The reconstruction, content and style terms live in that space or in the hidden
// units. The motion-constraint terms (eq. 7-9) act on the DE-NORMALISED frame x = x_n * std + mean, in
// the representation's units (cm and cm/frame in the root frame, rad/frame), and chain the gradient
// back to x_n (d/dx_n = std * d/dx).

#include <vector>

#include "features/feature_layout.h"
#include "features/feature_statistics.h"
#include "nn/tensor.h"

namespace motionstyle::nn {

// The normalisation x_n = (x - mean) / std is FeatureStatistics (features/feature_statistics.h).

// Bones for eq. 8: bone b joins canonical joint b + 1 to its parent kCanonicalParent[b + 1] (every
// joint but the hips has a parent, so there are 20).
constexpr int kBoneCount = kCanonicalJointCount - 1;

// Mean squared error, mean over every entry of (output - target)^2. Eq. 3's reconstruction term
// (normalised frames) and eq. 4's content term (hidden units, contentLoss) both use it.
template <typename S>
S meanSquaredError(const Mat<S>& output, const Mat<S>& target, S weight, Mat<S>* grad);

// Eq. 4, content: mean over hidden units and (pooled) time of (L(T(I)) - L(I))^2. `target` = L(I) is
// constant for a content clip: compute it once per clip and reuse it (it is the biggest speed lever
// of training after the GEMMs). Shapes must match.
template <typename S>
S contentLoss(const Mat<S>& hidden, const Mat<S>& target, S weight, Mat<S>* grad) {
  return meanSquaredError(hidden, target, weight, grad);
}

// Eq. 3's sparsity term: mean over every entry of the given parameters of |w| (a mean, so that alpha
// does not depend on the layer sizes). Its gradient weight * sign(w) / count goes into each
// parameter's grad. sign(0) = 0.
template <typename S>
S meanAbsoluteWeight(const std::vector<Parameter<S>*>& parameters, S weight);

// Eq. 6, Gram matrix of ONE window's hidden units h (channels x frames): h h^T / frames.
// DEVIATION from the paper, on purpose: the paper sums over time; we divide by the frame count so that
// clips of different lengths (a style clip vs a 240-frame training window) compare. The style weight
// absorbs the constant factor for a fixed window length.
template <typename S>
Mat<S> gramMatrix(const Mat<S>& hidden);

// Eq. 5, style: mean over windows b and entries of (Gram(h_b) - G_b)^2, where G_b is
// style_grams[b], or style_grams[0] for every window when only one is given (one style clip).
// hidden: channels x (B*frames) = L(T(I)); each G channels x channels, precomputed per style clip.
template <typename S>
S styleLoss(const Mat<S>& hidden, int frames, const std::vector<Mat<S>>& style_grams, S weight,
            Mat<S>* grad);

// Eq. 7, foot contact (no foot sliding). For each contact label c (left heel = LeftAnkle, left toe,
// right heel, right toe: kContactJoint) and each frame t with contacts(c, t) = 1 and t + 1 in the same
// window, the foot's world displacement from t to t+1, expressed in frame t's root frame:
//     d = v(t) + R_y(w(t)) p_j(t+1) - p_j(t),   v(t) = (sideways(t), 0, forward(t)),
// with p_j the joint's root-frame position, w(t) the turning velocity (rad/frame) and R_y the
// right-handed rotation about +Y. This follows from P_j(t) = r(t) + R(t) p_j(t) (feature_layout.h).
// The paper writes the linearised w x p_j; we use the exact rotation. loss = mean over the labelled
// (t, c) of |d|^2 in cm^2 (0 when nothing is labelled).
// x_normalised: 66 x (B*frames); contacts: kContactCount x (B*frames), 0 or 1.
template <typename S>
S footContactLoss(const Mat<S>& x_normalised, int frames, const Mat<S>& contacts,
                  const FeatureStatistics& normalisation, S weight, Mat<S>* grad);

// Eq. 8, bone lengths: mean over the kBoneCount bones and every frame of (|p_c - p_parent| - l_b)^2
// in cm^2, where l_b = bone_lengths(b, window) are the target lengths in cm (the content clip's own).
// The derivative of |u| is u / |u|, taken as 0 when |u| < 1e-6 cm, so zero-length bones (a hand end
// at the wrist) are safe. bone_lengths: kBoneCount x B.
template <typename S>
S boneLengthLoss(const Mat<S>& x_normalised, int frames, const Mat<S>& bone_lengths,
                 const FeatureStatistics& normalisation, S weight, Mat<S>* grad);

// Eq. 9, trajectory: mean over frames of (w - w')^2 + (v_x - v_x')^2 + (v_z - v_z')^2 with the
// content's de-normalised velocities as targets (w in rad/frame, v in cm/frame). Both 66 x N; the
// gradient flows only into x_normalised.
template <typename S>
S trajectoryLoss(const Mat<S>& x_normalised, const Mat<S>& target_normalised,
                 const FeatureStatistics& normalisation, S weight, Mat<S>* grad);

}  // namespace motionstyle::nn
