// The contact projection (contact_projection.h): invalid input first, then that its solution plants
// the contact steps of the decoded motion (eq. 7) under either path, changes only the hidden units
// within the decoder's reach of a contact, and leaves a clip without contacts as it was.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "features/feature_layout.h"
#include "style/contact_projection.h"

namespace motionstyle {
namespace {

constexpr int kHidden = 24, kWidth = 7, kFirst = 16, kFrames = 60;
constexpr int kPooled = (kFirst + kFrames + 16) / 2;

struct Fixture {
  nn::LossNetwork<float> loss{nn::LossNetworkShape{kFeatureCount, kHidden, kWidth}};
  FeatureStatistics normalisation;
  nn::Mat<float> hidden;
  Eigen::MatrixXd content = Eigen::MatrixXd::Zero(kFeatureCount, kFrames);
  Eigen::MatrixXd contacts = Eigen::MatrixXd::Zero(kContactCount, kFrames);

  Fixture() {
    loss.initialise(7);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    normalisation.mean = Eigen::VectorXd::Zero(kFeatureCount);
    normalisation.std = Eigen::VectorXd::Constant(kFeatureCount, 1.0);
    for (int f = 0; f < kFeatureCount; ++f) {
      normalisation.mean(f) = 10.0 * (u(rng) - 0.5);
      normalisation.std(f) = 2.0 + 8.0 * u(rng);
    }
    normalisation.std(kTurningVelocity) = 0.01;  // radians per frame: a walk turns slowly
    normalisation.mean(kTurningVelocity) = 0.0;
    hidden = nn::Mat<float>(kHidden, kPooled);
    for (Eigen::Index i = 0; i < hidden.size(); ++i) hidden.data()[i] = static_cast<float>(u(rng));
    for (int t = 0; t < kFrames; ++t) {
      content(kSidewaysVelocity, t) = 0.3 * (u(rng) - 0.5);
      content(kForwardVelocity, t) = 2.0 + 0.5 * u(rng);
      content(kTurningVelocity, t) = 0.02 * (u(rng) - 0.5);
    }
    contacts.block(0, 5, 2, 15).setOnes();   // left heel and toe
    contacts.block(2, 30, 2, 20).setOnes();  // right heel and toe
  }

  // Decoded physical rows of the features (66 x decoded frames).
  Eigen::MatrixXd decoded(const nn::Mat<float>& h) const {
    Eigen::MatrixXd x = loss.decode(h, kPooled).cast<double>();
    for (int f = 0; f < kFeatureCount; ++f)
      x.row(f) = (x.row(f).array() * normalisation.std(f) + normalisation.mean(f)).matrix();
    return x;
  }

  // The largest contact step |u_j(t)| (eq. 7) of the decoded motion under `path`.
  double largestStep(const nn::Mat<float>& h, style::PathMode path) const {
    const Eigen::MatrixXd x = decoded(h);
    double largest = 0.0;
    for (int label = 0; label < kContactCount; ++label)
      for (int t = 0; t + 1 < kFrames; ++t) {
        if (contacts(label, t) < 0.5 || contacts(label, t + 1) < 0.5) continue;
        const int at = kFirst + t;
        const Eigen::MatrixXd& root = path == style::PathMode::Content ? content : x;
        const int root_at = path == style::PathMode::Content ? t : at;
        const double w = root(kTurningVelocity, root_at);
        Eigen::Matrix3d turn;
        turn << std::cos(w), 0.0, std::sin(w), 0.0, 1.0, 0.0, -std::sin(w), 0.0, std::cos(w);
        const int row = 3 * index(kContactJoint[static_cast<std::size_t>(label)]);
        const Eigen::Vector3d v(root(kSidewaysVelocity, root_at), 0.0, root(kForwardVelocity, root_at));
        largest = std::max(largest, (v + turn * x.block<3, 1>(row, at + 1) - x.block<3, 1>(row, at)).norm());
      }
    return largest;
  }
};

TEST(ContactProjectionInvalid, SettingsOutOfRangeAreNamed) {
  style::ContactProjection settings;
  settings.iterations = -1;
  EXPECT_THROW(settings.validate(), std::invalid_argument);
  settings.iterations = style::ContactProjection::kMaxIterations + 1;
  EXPECT_THROW(settings.validate(), std::invalid_argument);
  settings = {};
  settings.smoothness = -1.0;
  EXPECT_THROW(settings.validate(), std::invalid_argument);
  settings = {};
  settings.damping = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(settings.validate(), std::invalid_argument);
}

TEST(ContactProjectionInvalid, MismatchedShapesThrow) {
  Fixture f;
  const style::ContactPlanter planter(f.loss);
  const style::ContactProjection settings;
  nn::Mat<float> h = f.hidden;
  EXPECT_THROW(planter.plant(h, f.normalisation, f.content, f.contacts.leftCols(10), kFirst, style::PathMode::Content,
                             settings),
               std::invalid_argument);
  EXPECT_THROW(planter.plant(h, f.normalisation, f.content.topRows(60), f.contacts, kFirst, style::PathMode::Content,
                             settings),
               std::invalid_argument);
  EXPECT_THROW(planter.plant(h, f.normalisation, f.content, f.contacts, 2, style::PathMode::Content, settings),
               std::invalid_argument);  // within the decoder's reach of the padded clip's start
  nn::Mat<float> narrow = f.hidden.leftCols(kPooled - 20);
  EXPECT_THROW(planter.plant(narrow, f.normalisation, f.content, f.contacts, kFirst, style::PathMode::Content, settings),
               std::invalid_argument);
  EXPECT_EQ(h, f.hidden);
}

TEST(ContactProjection, PlantsTheContactStepsUnderEitherPath) {
  Fixture f;
  const style::ContactPlanter planter(f.loss);
  style::ContactProjection settings;
  settings.iterations = 400;
  settings.smoothness = 0.0;
  settings.damping = 1e-8;
  for (const style::PathMode path : {style::PathMode::Content, style::PathMode::Style}) {
    nn::Mat<float> h = f.hidden;
    const double before = f.largestStep(h, path);
    planter.plant(h, f.normalisation, f.content, f.contacts, kFirst, path, settings);
    const double after = f.largestStep(h, path);
    EXPECT_GT(before, 1.0);
    EXPECT_LT(after, 1e-2 * before) << "path " << style::pathModeName(path);
  }
}

TEST(ContactProjection, ChangesOnlyTheHiddenUnitsWithinReachOfAContact) {
  Fixture f;
  f.contacts.setZero();
  f.contacts.block(0, 20, 1, 6).setOnes();  // frames 20..25: decoded kFirst + 20 .. kFirst + 25
  const style::ContactPlanter planter(f.loss);
  nn::Mat<float> h = f.hidden;
  style::ContactProjection settings;
  settings.smoothness = 0.0;  // (the smoothness term spreads the change over the whole clip on purpose)
  planter.plant(h, f.normalisation, f.content, f.contacts, kFirst, style::PathMode::Content, settings);
  const int reach = kWidth / 2 + 1;  // pooled columns a decoded frame reads, either side
  for (int s = 0; s < kPooled; ++s) {
    const bool near = 2 * s + 1 >= kFirst + 20 - 2 * reach && 2 * s <= kFirst + 25 + 2 * reach;
    if (!near) {
      EXPECT_EQ(h.col(s), f.hidden.col(s)) << "pooled column " << s;
    }
  }
  EXPECT_NE(h, f.hidden);
}

TEST(ContactProjection, WithoutContactsOrIterationsNothingChanges) {
  Fixture f;
  const style::ContactPlanter planter(f.loss);
  nn::Mat<float> h = f.hidden;
  planter.plant(h, f.normalisation, f.content, Eigen::MatrixXd::Zero(kContactCount, kFrames), kFirst,
                style::PathMode::Content, {});
  EXPECT_EQ(h, f.hidden);
  style::ContactProjection none;
  none.iterations = 0;
  planter.plant(h, f.normalisation, f.content, f.contacts, kFirst, style::PathMode::Content, none);
  EXPECT_EQ(h, f.hidden);
}

}  // namespace
}  // namespace motionstyle
