// The float32 inference path against the double reference forward pass.

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "gradient_check.h"
#include "nn/fast_stylizer.h"

namespace motionstyle::nn {
namespace {

using test::MatD;

template <typename To, typename From>
void copyWeights(Conv1d<To>& to, const Conv1d<From>& from) {
  to.weight.value = from.weight.value.template cast<To>();
  if (from.hasBias()) to.bias.value = from.bias.value.template cast<To>();
}

struct Networks {
  TransformationNetwork<float> t;
  LossNetwork<float> loss_network;
  TransformationNetwork<double> t_ref;
  LossNetwork<double> loss_network_ref;
  explicit Networks(bool residual)
      : t({kFeatureCount, 128, 25, residual}), t_ref({kFeatureCount, 128, 25, residual}) {
    t.initialise(1);
    loss_network.initialise(2);
    std::mt19937 rng(3);
    loss_network.encoder.bias.value = test::randomMatrix(256, 1, rng, 0.1).cast<float>();
    for (Conv1d<float>* c : {&t.conv1, &t.conv2, &t.conv3}) c->bias.value = test::randomMatrix(c->outChannels(), 1, rng, 0.1).cast<float>();
    copyWeights(t_ref.conv1, t.conv1);
    copyWeights(t_ref.conv2, t.conv2);
    copyWeights(t_ref.conv3, t.conv3);
    copyWeights(loss_network_ref.encoder, loss_network.encoder);
    copyWeights(loss_network_ref.decoder, loss_network.decoder);
  }
};

double relativeMaxError(const MatD& actual, const MatD& expected) {
  return (actual - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
}

TEST(FastStylizerInvalid, RejectsBadClipsAndMissingTransformationNetwork) {
  LossNetwork<float> loss_network;
  FastStylizer projection_only(loss_network);
  EXPECT_THROW(projection_only.stylize(Mat<float>::Zero(kFeatureCount, 10)), std::invalid_argument);
  EXPECT_THROW(projection_only.project(Mat<float>::Zero(kFeatureCount - 1, 10)), std::invalid_argument);
  EXPECT_THROW(projection_only.project(Mat<float>::Zero(kFeatureCount, 0)), std::invalid_argument);
  TransformationNetwork<float> small({12, 8, 5, false});
  EXPECT_THROW(FastStylizer(small, loss_network), std::invalid_argument);
  EXPECT_THROW(FastStylizer(small, projection_only), std::invalid_argument);
  TransformationNetwork<float> t({kFeatureCount, 16, 5, true});
  const FastStylizer styled(t, projection_only);
  EXPECT_THROW(FastStylizer(t, styled), std::invalid_argument);  // a projection with a transformation already
}

// Built on a prepared projection, a style network gives the other constructor's output bit for bit
// (the projection's spectra are shared, not recomputed), and the projection itself is unchanged.
TEST(FastStylizer, OnASharedProjectionItIsTheSameStylizer) {
  Networks n(true);
  const FastStylizer projection(n.loss_network);
  FastStylizer shared(n.t, projection), own(n.t, n.loss_network);
  std::mt19937 rng(8);
  const Mat<float> x = test::randomMatrix(kFeatureCount, 301, rng).cast<float>();
  EXPECT_EQ(shared.stylize(x), own.stylize(x));
  FastStylizer projection_copy(projection);
  EXPECT_EQ(projection_copy.project(x), FastStylizer(n.loss_network).project(x));
}

TEST(FastStylizer, MatchesTheDoubleReferenceForAnyLength) {
  for (bool residual : {true, false}) {
    Networks n(residual);
    FastStylizer fast(n.t, n.loss_network);
    std::mt19937 rng(4);
    for (int frames : {1, 2, 3, 24, 25, 240, 241, 1001}) {
      const MatD x = test::randomMatrix(kFeatureCount, frames, rng);
      const MatD expected = n.loss_network_ref.project(n.t_ref.apply(x, frames), frames);
      const MatD actual = fast.stylize(x.cast<float>()).cast<double>();
      ASSERT_EQ(actual.cols(), frames);
      EXPECT_LT(relativeMaxError(actual, expected), 1e-4) << frames << (residual ? " residual" : "");
    }
  }
}

TEST(FastStylizer, PolyphaseDecoderEqualsThePlainDecoder) {
  Networks n(true);
  FastStylizer fast(n.loss_network);
  ASSERT_EQ(fast.polyphaseKernel().cols(), 256 * 13);  // 13 taps per phase instead of 25
  std::mt19937 rng(5);
  for (int frames : {1, 6, 7, 100, 481}) {
    const MatD x = test::randomMatrix(kFeatureCount, frames, rng);
    const MatD plain = n.loss_network.project(x.cast<float>(), frames).cast<double>();
    const MatD reference = n.loss_network_ref.project(x, frames);
    const MatD polyphase = fast.project(x.cast<float>()).cast<double>();
    EXPECT_LT(relativeMaxError(polyphase, reference), 1e-5) << frames;
    EXPECT_LT(relativeMaxError(plain, reference), 1e-5) << frames;
  }
}

TEST(FastStylizer, ReusedBuffersGiveTheSameResultAcrossLengths) {
  Networks n(true);
  FastStylizer fast(n.t, n.loss_network);
  std::mt19937 rng(6);
  const Mat<float> a = test::randomMatrix(kFeatureCount, 241, rng).cast<float>();
  const Mat<float> b = test::randomMatrix(kFeatureCount, 60, rng).cast<float>();
  const Mat<float> first = fast.stylize(a);
  fast.stylize(b);
  EXPECT_EQ(fast.stylize(a), first);  // deterministic, and no stale padding from the shorter clip
}

// The hidden units the style refinement edits: encode() is LossNetwork::encode, an edit that leaves
// them alone gives stylize() bit for bit, and an edit reaches the output.
TEST(FastStylizer, EncodesAsTheReferenceAndDecodesEditedHiddenUnits) {
  Networks n(true);
  FastStylizer fast(n.t, n.loss_network);
  std::mt19937 rng(7);
  for (int frames : {61, 240}) {
    const Mat<float> x = test::randomMatrix(kFeatureCount, frames, rng).cast<float>();
    const MatD expected = n.loss_network_ref.encode(x.cast<double>(), frames);
    const Mat<float> hidden = fast.encode(x);
    ASSERT_EQ(hidden.rows(), expected.rows());
    ASSERT_EQ(hidden.cols(), expected.cols());
    EXPECT_LT(relativeMaxError(hidden.cast<double>(), expected), 1e-5) << frames;

    const Mat<float> plain = fast.stylize(x);
    Mat<float> untouched, edited;
    int seen_columns = 0;
    fast.stylize(x, untouched, [&](Mat<float>& h) { seen_columns = static_cast<int>(h.cols()); });
    EXPECT_EQ(seen_columns, (frames + 1) / 2);
    EXPECT_EQ(untouched, plain);
    fast.stylize(x, edited, [](Mat<float>& h) { h.col(h.cols() / 2).array() += 1.0f; });
    EXPECT_GT((edited - plain).cwiseAbs().maxCoeff(), 1e-3f) << frames;
    EXPECT_THROW(fast.stylize(x, edited, [](Mat<float>& h) { h.resize(h.rows(), 1); }), std::invalid_argument);
  }
}

}  // namespace
}  // namespace motionstyle::nn
