#include "style/contact_projection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "features/feature_layout.h"
#include "nn/compute_pool.h"
#include "nn/conv1d.h"
#include "nn/layers.h"

namespace motionstyle::style {
namespace {

// The decoded rows the problem reads: x, y, z of each contact joint, then the three root velocities.
constexpr int kFootRows = 3 * kContactCount;
constexpr int kRows = kFootRows + 3;

int featureRow(int row) {
  if (row < kFootRows) return 3 * index(kContactJoint[static_cast<std::size_t>(row / 3)]) + row % 3;
  return kSidewaysVelocity + (row - kFootRows);
}

// Pooled column a decoded frame's tap reads: frame t's tap k sees depooled frame t + k - width/2.
int pooledOf(int t, int k, int width) {
  const int depooled = t + k - width / 2;
  return depooled >= 0 ? depooled / 2 : -((1 - depooled) / 2);
}

Eigen::Matrix3d turnAbout(double w) {
  Eigen::Matrix3d turn;
  turn << std::cos(w), 0.0, std::sin(w), 0.0, 1.0, 0.0, -std::sin(w), 0.0, std::cos(w);
  return turn;
}

struct Contact {
  int label;             // ContactLabel: rows 3 * label .. 3 * label + 2
  int frame;             // decoded frame t; the step t -> t + 1 is planted
  Eigen::Matrix3d turn;  // R_y(w(t))
};

// A swing frame of a contact joint: the joint and its two neighbours are out of contact.
struct Swing {
  int label;
  int frame;  // decoded frame t; the correction's second difference at t is asked to be zero
};

// A: a change of the decoded rows (physical units) -> the residuals: the contact steps, then the
// correction's second differences over the swings, scaled by sqrt(s).
class PlantProblem {
 public:
  PlantProblem(std::vector<Contact> contacts, std::vector<Swing> swings, double smoothness, bool own_root)
      : contacts_(std::move(contacts)), swings_(std::move(swings)), smooth_(std::sqrt(smoothness)),
        own_root_(own_root) {}

  Eigen::Index size() const { return 3 * static_cast<Eigen::Index>(contacts_.size() + swings_.size()); }

  Eigen::VectorXd apply(const Eigen::MatrixXd& rows) const {
    Eigen::VectorXd out(size());
    Eigen::Index at = 0;
    for (const Contact& k : contacts_) {
      out.segment<3>(at) = k.turn * rows.block<3, 1>(3 * k.label, k.frame + 1) - rows.block<3, 1>(3 * k.label, k.frame);
      if (own_root_) {
        out(at) += rows(kFootRows, k.frame);
        out(at + 2) += rows(kFootRows + 1, k.frame);
      }
      at += 3;
    }
    for (const Swing& w : swings_) {
      const int r = 3 * w.label;
      out.segment<3>(at) = smooth_ * (rows.block<3, 1>(r, w.frame + 1) - 2.0 * rows.block<3, 1>(r, w.frame) +
                                      rows.block<3, 1>(r, w.frame - 1));
      at += 3;
    }
    return out;
  }

  // A^T, into `rows` (kRows x decoded frames, zeroed here).
  void transpose(const Eigen::VectorXd& residuals, Eigen::MatrixXd& rows) const {
    rows.setZero();
    Eigen::Index at = 0;
    for (const Contact& k : contacts_) {
      const Eigen::Vector3d r = residuals.segment<3>(at);
      rows.block<3, 1>(3 * k.label, k.frame + 1) += k.turn.transpose() * r;
      rows.block<3, 1>(3 * k.label, k.frame) -= r;
      if (own_root_) {
        rows(kFootRows, k.frame) += r(0);
        rows(kFootRows + 1, k.frame) += r(2);
      }
      at += 3;
    }
    for (const Swing& w : swings_) {
      const Eigen::Vector3d g = smooth_ * residuals.segment<3>(at);
      const int r = 3 * w.label;
      rows.block<3, 1>(r, w.frame + 1) += g;
      rows.block<3, 1>(r, w.frame) -= 2.0 * g;
      rows.block<3, 1>(r, w.frame - 1) += g;
      at += 3;
    }
  }

 private:
  std::vector<Contact> contacts_;
  std::vector<Swing> swings_;
  double smooth_;
  bool own_root_;
};

}  // namespace

void ContactProjection::validate() const {
  if (iterations < 0 || iterations > kMaxIterations)
    throw std::invalid_argument("contact projection iterations must be in [0, " + std::to_string(kMaxIterations) +
                                "], got " + std::to_string(iterations));
  if (!(std::isfinite(smoothness) && smoothness >= 0.0))
    throw std::invalid_argument("contact projection smoothness must be finite and >= 0");
  if (!(std::isfinite(damping) && damping >= 0.0))
    throw std::invalid_argument("contact projection damping must be finite and >= 0");
}

ContactPlanter::ContactPlanter(const nn::LossNetwork<float>& loss_network)
    : encoder_bias_(loss_network.encoder.bias.value.col(0)),
      hidden_(loss_network.shape().hidden),
      width_(loss_network.shape().width),
      reach_(loss_network.shape().width + 1) {
  if (loss_network.shape().features != kFeatureCount)
    throw std::invalid_argument("ContactPlanter: the loss network must take the representation's 66 features");
  rows_weight_.resize(kRows, hidden_ * width_);
  for (int row = 0; row < kRows; ++row) rows_weight_.row(row) = loss_network.decoder.weight.value.row(featureRow(row));
  adjoint_weight_.resize(hidden_, kRows * width_);
  for (int k = 0; k < width_; ++k)
    adjoint_weight_.middleCols((width_ - 1 - k) * kRows, kRows) =
        rows_weight_.middleCols(k * hidden_, hidden_).transpose();
  // K between decoded frames t and t': sum over the pooled columns both read of (their taps' W_k summed)
  // products, i.e. the sum of W_k W_k'^T over tap pairs that read the same pooled column.
  const Eigen::MatrixXd weight = rows_weight_.cast<double>();
  std::vector<Eigen::MatrixXd> pair(static_cast<std::size_t>(width_ * width_));
  for (int k = 0; k < width_; ++k)
    for (int l = 0; l < width_; ++l)
      pair[static_cast<std::size_t>(k * width_ + l)] =
          weight.middleCols(k * hidden_, hidden_) * weight.middleCols(l * hidden_, hidden_).transpose();
  const int origin = 4 * width_;  // any even frame far from the edges
  for (int parity = 0; parity < 2; ++parity) {
    const int t = origin + parity;
    Eigen::MatrixXd kernel = Eigen::MatrixXd::Zero(kRows, kRows * (2 * reach_ + 1));
    for (int lag = -reach_; lag <= reach_; ++lag)
      for (int k = 0; k < width_; ++k)
        for (int l = 0; l < width_; ++l)
          if (pooledOf(t, k, width_) == pooledOf(t + lag, l, width_))
            kernel.middleCols((lag + reach_) * kRows, kRows) += pair[static_cast<std::size_t>(k * width_ + l)];
    kernel_[static_cast<std::size_t>(parity)] = kernel.cast<float>();
  }
}

void ContactPlanter::plant(nn::Mat<float>& hidden, const FeatureStatistics& normalisation,
                           const Eigen::MatrixXd& content, const Eigen::MatrixXd& contacts, int first_frame,
                           PathMode path, const ContactProjection& settings) const {
  settings.validate();
  const int pooled = static_cast<int>(hidden.cols());
  const int frames = static_cast<int>(content.cols());
  const int decoded = 2 * pooled;
  if (hidden.rows() != hidden_ || content.rows() != kFeatureCount || contacts.rows() != kContactCount ||
      contacts.cols() != frames || first_frame < reach_ + 1 || first_frame + frames + reach_ + 1 > decoded)
    throw std::invalid_argument("ContactPlanter::plant: the hidden units, content and contacts do not match");
  if (settings.iterations == 0) return;

  Eigen::VectorXd scale(kRows), mean(kRows);
  for (int row = 0; row < kRows; ++row) {
    scale(row) = normalisation.std(featureRow(row));
    mean(row) = normalisation.mean(featureRow(row));
  }
  // The decoded rows now, physical, over the clip's frames and one either side ([from, to)): frame t
  // reads the depooled frames t - width/2 .. t + width/2, all inside the padded clip.
  const int from = first_frame - 1, to = first_frame + frames + 1, half = width_ / 2;
  nn::Mat<float> depooled = nn::AverageDepool2<float>::apply(hidden);
  depooled.colwise() -= encoder_bias_;
  nn::Mat<float> decoded_rows(kRows, to - from);
  nn::correlatePadded(rows_weight_, depooled.data() + static_cast<Eigen::Index>(from - half) * hidden_, hidden_, width_,
                      decoded_rows.data(), to - from);
  Eigen::MatrixXd current = Eigen::MatrixXd::Zero(kRows, decoded);
  current.middleCols(from, to - from) = (scale.asDiagonal() * decoded_rows.cast<double>()).colwise() + mean;

  const bool own_root = path == PathMode::Style;
  std::vector<Contact> planted;
  std::vector<Eigen::Vector3d> steps;  // u_j(t) at dH = 0
  for (int label = 0; label < kContactCount; ++label)
    for (int t = 0; t + 1 < frames; ++t) {
      if (contacts(label, t) < 0.5 || contacts(label, t + 1) < 0.5) continue;
      const int at = first_frame + t;
      const Contact k{label, at, turnAbout(own_root ? current(kFootRows + 2, at) : content(kTurningVelocity, t))};
      const Eigen::Vector3d velocity =
          own_root ? Eigen::Vector3d(current(kFootRows, at), 0.0, current(kFootRows + 1, at))
                   : Eigen::Vector3d(content(kSidewaysVelocity, t), 0.0, content(kForwardVelocity, t));
      steps.push_back(velocity + k.turn * current.block<3, 1>(3 * label, at + 1) - current.block<3, 1>(3 * label, at));
      planted.push_back(k);
    }
  if (planted.empty()) return;
  std::vector<Swing> swings;
  if (settings.smoothness > 0.0)
    for (int label = 0; label < kContactCount; ++label)
      for (int t = 1; t + 1 < frames; ++t)
        if (contacts(label, t - 1) < 0.5 && contacts(label, t) < 0.5 && contacts(label, t + 1) < 0.5)
          swings.push_back({label, first_frame + t});
  const PlantProblem problem(planted, std::move(swings), settings.smoothness, own_root);
  Eigen::VectorXd start = Eigen::VectorXd::Zero(problem.size());  // the residuals at dH = 0 (swings: zero)
  for (std::size_t i = 0; i < steps.size(); ++i) start.segment<3>(3 * static_cast<Eigen::Index>(i)) = steps[i];

  // M lambda = (A S K S A^T + d) lambda, S = diag(scale): A reads physical rows, K normalised ones.
  Eigen::MatrixXd rows(kRows, decoded), convolved(kRows, decoded);
  // K runs in float (the networks' precision; a product per parity of 15 x 795 by 795 x frames/2).
  Eigen::MatrixXf rows_in(kRows, decoded), rows_out = Eigen::MatrixXf::Zero(kRows, decoded);
  const auto applyM = [&](const Eigen::VectorXd& lambda) {
    problem.transpose(lambda, rows);
    rows_in = (scale.asDiagonal() * rows).cast<float>();
    nn::parallelItems(2, kRows * kRows * (2 * reach_ + 1) * (to - from) / 2, [&](int first_parity, int end_parity) {
    for (int parity = first_parity; parity < end_parity; ++parity) {
      const int begin = from + ((from % 2) != parity ? 1 : 0);  // the first frame of this parity
      const int count = (to - begin + 1) / 2;
      if (count <= 0) continue;
      // Column j stacks frames t - reach .. t + reach around t = begin + 2j (zero outside [from, to)).
      const Eigen::Map<const Eigen::MatrixXf, Eigen::Unaligned, Eigen::OuterStride<>> around(
          rows_in.data() + static_cast<Eigen::Index>(begin - reach_) * kRows, kRows * (2 * reach_ + 1), count,
          Eigen::OuterStride<>(2 * kRows));
      Eigen::Map<Eigen::MatrixXf, Eigen::Unaligned, Eigen::OuterStride<>> out(
          rows_out.data() + static_cast<Eigen::Index>(begin) * kRows, kRows, count, Eigen::OuterStride<>(2 * kRows));
      out.noalias() = kernel_[static_cast<std::size_t>(parity)] * around;
    }
    });
    convolved = scale.asDiagonal() * rows_out.cast<double>();
    return Eigen::VectorXd(problem.apply(convolved) + settings.damping * lambda);
  };

  // Conjugate gradients on M lambda = -start.
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(start.size());
  Eigen::VectorXd residual = -start, direction = residual;
  double gamma = residual.squaredNorm();
  for (int it = 0; it < settings.iterations && gamma > 0.0; ++it) {
    const Eigen::VectorXd image = applyM(direction);
    const double alpha = gamma / direction.dot(image);
    lambda += alpha * direction;
    residual -= alpha * image;
    const double next = residual.squaredNorm();
    direction = residual + (next / gamma) * direction;
    gamma = next;
  }

  // The step along dH = J^T lambda that minimises the primal objective, in [0, 1]
  // (J dH = (M - d) lambda, |dH|^2 = lambda . J dH).
  const Eigen::VectorXd moved = applyM(lambda) - settings.damping * lambda;
  const double curvature = moved.squaredNorm() + settings.damping * lambda.dot(moved);
  const double step = curvature > 0.0 ? std::clamp(-start.dot(moved) / curvature, 0.0, 1.0) : 0.0;
  if (step == 0.0) return;
  lambda *= step;

  // dH = D^T S A^T lambda: the decoder's adjoint, a correlation with the flipped, transposed kernel
  // over the depooled frames [from - half, to + half), then the depooling's adjoint (pairs summed).
  problem.transpose(lambda, rows);
  nn::Mat<float> change = nn::Mat<float>::Zero(kRows, to - from + 4 * half);
  change.middleCols(2 * half, to - from) = (scale.asDiagonal() * rows.middleCols(from, to - from)).cast<float>();
  const int first_depooled = from - half, count = to - from + 2 * half;
  nn::Mat<float> depooled_change(hidden_, count);
  nn::correlatePadded(adjoint_weight_, change.data(), kRows, width_, depooled_change.data(), count);
  for (int j = 0; j < count; ++j) hidden.col((first_depooled + j) / 2) += depooled_change.col(j);
}

}  // namespace motionstyle::style
