#pragma once
// Contact projection: the manifold projection with the content's foot contacts kept planted.
//
// The paper's projection L(x) = decode(encode(x)) removes the network's artefacts but "could introduce
// foot sliding" (paper, Discussion), and a style that walks shorter than the content's kept path
// slides its stance feet too; the paper leaves the fix to a post-process. Here the planted feet are
// asked of the projection itself, in the loss network's hidden units, as Holden et al. 2016 edit
// motion under constraints: the change dH of the hidden units that solves
//   min_dH  sum_{j, t in contact} |u_j(t)|^2  +  s * sum_{j, t in swing} |dp_j(t+1) - 2 dp_j(t) + dp_j(t-1)|^2
//           + d * |dH|^2
//   u_j(t) = v(t) + R_y(w(t)) p_j(t+1) - p_j(t)     (eq. 7: contact joint j's step in frame t's root
//                                                    frame, cm per frame; zero = planted)
// where p_j is decoded from H + dH, dp_j its change, "t in swing" a frame where joint j and both its
// neighbours are out of contact, and v, w the root velocities of the path the
// output follows: the content's (PathMode::Content) or the decoded output's own (PathMode::Style, w
// held at its current value). The decoder is affine, so this is a damped linear least-squares problem,
// solved in its dual (below). The smoothness term s runs the correction straight through each swing:
// without it the foot made up a whole stance's slide in the one frame after its release (a 12 cm
// jump); over the stances too it conflicts with the contacts and the dual does not converge.
// Why here rather than only in the IK clean-up: a stance planted on the manifold moves the whole body
// with it (a style's shorter stride lengthened to the kept path), where the clean-up can only stretch
// the legs; measured in docs/decisions.md ("Contacts planted in the projection").

#include <Eigen/Core>
#include <array>
#include <vector>

#include "features/feature_statistics.h"
#include "nn/loss_network.h"
#include "nn/tensor.h"
#include "style/path_mode.h"

namespace motionstyle::style {

struct ContactProjection {
  static constexpr int kMaxIterations = 1000;
  int iterations = 40;       // conjugate-gradient iterations; 0 = the plain projection
  double smoothness = 1.0;   // s, per (cm per frame^2)^2 against (cm per frame)^2
  double damping = 1e-4;     // d, on the squared hidden units

  // Throws std::invalid_argument naming the field: iterations in [0, kMaxIterations], weights >= 0
  // and finite.
  void validate() const;
};

// The problem's operators for one loss network, prepared once (a Stylizer keeps one). The problem is
// solved in its dual, (A K A^T + d I) lambda = -u0, dH = D^T A^T lambda, where D is the decoder's map
// from hidden units to the contact joints' and root velocities' rows and K = D D^T: K is a convolution
// with 15 x 15 blocks over +-(width + 1) frames (two sets: the depooling pairs frames), so an
// iteration costs about 0.5 ms on 1,000 frames where the decoder and its adjoint cost 3 ms. Then a
// line search on the primal objective along dH: 40 iterations stop short of the dual's solution, and
// on a decoder that cannot plant the contacts a full step can raise it.
class ContactPlanter {
 public:
  // Throws std::invalid_argument when the loss network's features are not the representation's.
  explicit ContactPlanter(const nn::LossNetwork<float>& loss_network);

  // hidden: the loss network's hidden units (hidden x pooled), normalised by `normalisation`, of a clip
  // padded by `first_frame`
  // frames before it: decoded, they are 2 * pooled frames and clip frame t is frame first_frame + t;
  // first_frame >= width + 2 and the clip must end width + 2 frames before the decoded ones. content:
  // 66 x frames, contacts: 4 x frames (0/1), the clip's own. Changes hidden in place; nothing when no
  // two consecutive frames share a contact. Throws std::invalid_argument for mismatched shapes or
  // invalid settings. Thread-safe (const).
  void plant(nn::Mat<float>& hidden, const FeatureStatistics& normalisation, const Eigen::MatrixXd& content,
             const Eigen::MatrixXd& contacts, int first_frame, PathMode path, const ContactProjection& settings) const;

 private:
  nn::Mat<float> rows_weight_;     // the decoder's rows the problem reads: kRows x (hidden * width), tap-major
  nn::Mat<float> adjoint_weight_;  // their adjoint: hidden x (kRows * width), taps reversed, transposed
  nn::Vec<float> encoder_bias_;    // b0: decode(H) = Conv(Depool(H) - b0)
  int hidden_ = 0, width_ = 0, reach_ = 0;
  // kernel_[parity]: K's blocks between a decoded frame t of that parity and t + lag, lag = -reach_ ..
  // reach_ side by side (15 x 15 (2 reach_ + 1)): one product per parity applies K.
  std::array<Eigen::MatrixXf, 2> kernel_;
};

}  // namespace motionstyle::style
