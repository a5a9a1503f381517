// Acceptance on RAW STYLIZED OUTPUT, without the shipped networks (resources/models: CC BY-NC data,
// left out of some builds, and retrained now and then): the test builds a style model whose output is
// damaged the way a trained network's is, and runs it through the real pipeline, style::Stylizer (the float32 fast path,
// manifold projection included) then style::cleanUpStylizedClip (the content's contacts and those
// detected on the output locked, the Ceres clean-up on the content's own skeleton, the metrics before
// and after).
//   - Loss network: a hand-set loss network whose projection is a low-pass filter, the kind of loss a
//     trained one has. Hidden unit pairs carry +x + B and -x + B (B keeps the ReLU linear and is taken
//     off again by the decoder's "- b0"), so after max-pooling their difference is the mean of each
//     pair of frames; the decoder's taps (1/4, 1/2, 1/4) over the depooled frames then interpolate
//     between those means: a 3-4 frame blur, like a trained projection's.
//   - Transformation network: the residual form (output = input + T(input)) with fixed-seed random
//     weights and its output layer scaled down, so that every feature (joint positions, root motion)
//     gets a perturbation that follows the content: joints move off their bones (the stylizer then
//     sets the bone lengths), feet slide during contact, the root drifts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <tuple>
#include <utility>
#include <vector>

#include "bvh/bvh_reader.h"
#include "ik/contacts.h"
#include "features/feature_statistics.h"
#include "features/foot_contacts.h"
#include "features/representation.h"
#include "mapping/joint_mapping.h"
#include "motion/kinematics.h"
#include "motion/resample.h"
#include "nn/network_file.h"
#include "style/stylized_cleanup.h"
#include "style/evaluation.h"
#include "style/stylizer.h"
#include "style/training.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

// Output-layer scale: raw bone errors of ~1.3-1.5 cm mean, as the shipped networks give on this clip
// (1.1-1.6 cm over the nine styles, resources/models/README.md).
constexpr float kDamage = 1.4f;
constexpr float kHiddenBias = 50.0f;  // normalised units: far above any feature, so ReLU stays linear

nn::LossNetwork<float> lowPassLossNetwork() {
  constexpr int width = 25, centre = width / 2;
  nn::LossNetwork<float> network(nn::LossNetworkShape{kFeatureCount, 2 * kFeatureCount, width});
  Eigen::MatrixXf& encoder = network.encoder.weight.value;  // hidden x (features * width), tap-major
  Eigen::MatrixXf& decoder = network.decoder.weight.value;  // features x (hidden * width)
  encoder.setZero();
  decoder.setZero();
  network.encoder.bias.value.setConstant(kHiddenBias);
  const int hidden = 2 * kFeatureCount;
  for (int f = 0; f < kFeatureCount; ++f) {
    encoder(f, centre * kFeatureCount + f) = 1.0f;                   // +x
    encoder(kFeatureCount + f, centre * kFeatureCount + f) = -1.0f;  // -x
    for (const auto& [tap, share] : {std::pair{centre - 1, 0.25f}, std::pair{centre, 0.5f}, std::pair{centre + 1, 0.25f}}) {
      decoder(f, tap * hidden + f) = 0.5f * share;                     // (max + min) / 2 = pair mean
      decoder(f, tap * hidden + kFeatureCount + f) = -0.5f * share;
    }
  }
  return network;
}

// output_scale multiplies the transformation's (already 0.1-scaled) output layer.
nn::StyleModel networkLikeModel(const MotionFeatures& content, std::uint32_t seed, float output_scale) {
  nn::StyleModel model{nn::TransformationNetwork<float>(nn::TransformationShape{kFeatureCount, 32, 25, true}),
                       lowPassLossNetwork(), computeFeatureStatistics({content.values}), {}, {}};
  model.transformation.initialise(seed);
  model.transformation.conv3.weight.value *= output_scale;
  model.metadata.representation = style::currentRepresentation();
  return model;
}

class CleanupStylized : public ::testing::Test {
 protected:
  void SetUp() override {
    content = readBvh(test::fixture("cmu_131_01.bvh"));
    mapping = mapJoints(content.skeleton, content.source);
    features = extractFeatures(content, mapping);
  }
  style::StylizedCleanup stylizeAndClean(const nn::StyleModel& model) const {
    return style::cleanUpStylizedClip(content, mapping, style::Stylizer(model).stylize(features, 1.0));
  }
  // The stylized clip's content contacts of `label` (ContactLabel order) whose last frame is at least
  // `min_span` frames after their first, in order.
  static std::vector<ContactSegment> stancesOf(const style::StylizedClip& clip, int label, int min_span) {
    const Eigen::MatrixXi contacts = (clip.contacts.transpose().array() > 0.5).cast<int>();
    std::vector<ContactSegment> stances;
    for (const ContactSegment& segment : contactSegments(contacts, label))
      if (segment.last - segment.first >= min_span) stances.push_back(segment);
    return stances;
  }

  Motion content;
  JointMapping mapping;
  MotionFeatures features;
};

TEST_F(CleanupStylized, RejectsAStylizedClipOfAnotherLength) {
  const style::Stylizer stylizer(networkLikeModel(features, 11, 1.0f));
  style::StylizedClip stylized = stylizer.stylize(features, 1.0);
  stylized.features.conservativeResize(Eigen::NoChange, stylized.features.cols() - 10);
  stylized.world_positions.conservativeResize(stylized.world_positions.rows() - 10, Eigen::NoChange);
  stylized.contacts.conservativeResize(Eigen::NoChange, stylized.contacts.cols() - 10);
  EXPECT_THROW(style::cleanUpStylizedClip(content, mapping, stylized), std::invalid_argument);
}

// On a decoder that can plant feet (the low-pass one), the stylizer plants the content's contacts: its
// raw output slides far less than the same network's without them, under either path.
TEST_F(CleanupStylized, TheStylizerPlantsTheContentsContacts) {
  // Solved to the end and without the swings' smoothness, which this three-tap decoder cannot meet
  // together with the contacts (the shipped settings stop early: contact_projection.h).
  style::ContactProjection solved;
  solved.iterations = 300;
  solved.smoothness = 0.0;
  const style::Stylizer stylizer(networkLikeModel(features, 11, kDamage), "the test network", {}, solved);
  // The network's output on the path it follows, in the reference proportions it is planted in (before
  // the bone lengths are set, and before the clip's own proportions are put back: both move the feet a
  // little frame by frame, which the clean-up's locks take up).
  FeatureAnchor reference = features.anchor;
  reference.proportions = referenceProportions();
  reference.rig = {};
  reference.retarget_height_shift = 0.0;
  const auto skate = [&](const Eigen::MatrixXd& contacts, style::PathMode path) {
    Eigen::MatrixXd output = stylizer.networkOutput(features.values, contacts, path);
    style::applyPathMode(output, features.values, path);
    return style::footSkate(output, features.contacts, reference);
  };
  for (const style::PathMode path : {style::PathMode::Content, style::PathMode::Style}) {
    const double sliding = skate({}, path), planted = skate(features.contacts, path);
    std::printf("[ figures  ] %s path: skate %.2f cm/s planted, %.2f without\n", style::pathModeName(path), planted,
                sliding);
    EXPECT_GT(sliding, 5.0);
    EXPECT_LT(planted, 0.5 * sliding);
  }
}

TEST_F(CleanupStylized, TheLowPassProjectionKeepsTheMotionButDamagesIt) {
  // Zero transformation output: what is left is the projection alone, which must be close to the content
  // (a few cm) but not exact, or the clean-up below would have nothing to repair.
  const nn::StyleModel model = networkLikeModel(features, 11, 0.0f);
  const Eigen::MatrixXd projected = style::Stylizer(model).stylizeFeatures(features.values, {}, 1.0);
  const double mean_change = (projected - features.values).topRows(3 * kCanonicalJointCount).cwiseAbs().mean();
  EXPECT_GT(mean_change, 0.01);
  EXPECT_LT(mean_change, 2.0);
}

TEST_F(CleanupStylized, RawOutputMeetsTheCleanUpGoals) {
  for (const std::uint32_t seed : {11u, 12u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const style::StylizedCleanup run = stylizeAndClean(networkLikeModel(features, seed, kDamage));
    const ClipMetrics& raw = run.raw;
    const ClipMetrics& clean = run.cleaned;
    std::printf("[ figures  ] seed %u raw: skate %.1f cm/s, bone error mean %.2f max %.2f cm, penetration %.2f cm | "
                "cleaned: %d contact steps, skate %.3f cm/s, penetration %.3f cm, residual %.2f cm (max %.2f), bone error %.1e cm\n",
                seed, raw.foot_skate_cm_s, raw.bone_error_mean_cm, raw.bone_error_max_cm, raw.penetration_max_cm,
                clean.contact_steps, clean.foot_skate_cm_s, clean.penetration_max_cm, clean.residual_mean_cm, clean.residual_max_cm,
                clean.bone_error_max_cm);
    // The input really is damaged like a network's output (its bones already have their lengths: the
    // stylizer sets them, style/stylizer.h)...
    EXPECT_LT(raw.bone_error_max_cm, 1e-3);
    EXPECT_GT(raw.foot_skate_cm_s, 5.0);
    // ...and the clean-up meets the acceptance goals on it.
    // Every contact of the content is locked (the network was trained to hold those feet still).
    const Eigen::MatrixXi content_contacts = (features.contacts.transpose().array() > 0.5).cast<int>();
    ASSERT_EQ(run.contacts.rows(), content_contacts.rows());
    EXPECT_TRUE((run.contacts.array() >= content_contacts.array()).all());
    ASSERT_GT(clean.contact_steps, raw.contact_steps / 2) << "the output should have plenty of contact";
    EXPECT_LE(clean.foot_skate_cm_s, 0.5);
    EXPECT_LE(clean.penetration_max_cm, 0.5);
    EXPECT_LE(clean.residual_mean_cm, 2.0);
    EXPECT_LE(clean.bone_error_max_cm, 1e-4);
    EXPECT_EQ(run.report.frames_unsolved, 0);
    // Back at the content's rate (120 -> 60 -> 120 fps may drop the last frame).
    EXPECT_NEAR(run.motion.frameCount(), content.frameCount(), 1);
    EXPECT_DOUBLE_EQ(run.motion.fps(), content.fps());
  }
}

// Which of the content's stances are locked, and what the skate figure sees. The network's feet jitter
// (0.5-1.5 cm a frame) on a stance they keep: it is locked (a rule on the path length read that
// jitter as 180 cm/s of travel and locked almost nothing). A stance the style moved 60 cm is not locked,
// and its sliding is in the cleaned skate, which is measured over the contacts the user sees (the
// content's, under the overrides), not over the locks, where it was 0 by construction.
TEST_F(CleanupStylized, AJitteringStanceIsLockedAndAMovedStepIsNotButItsSlidingCounts) {
  const style::Stylizer stylizer(networkLikeModel(features, 11, 0.0f));  // the projection alone: feet nearly still
  const style::StylizedClip plain = stylizer.stylize(features, 1.0);
  const std::vector<ContactSegment> stances = stancesOf(plain, 0, 12);
  ASSERT_GE(stances.size(), 2u) << "the fixture walks: its left heel has stances of 0.2 s and more";
  const ContactSegment jittered = stances[0], moved = stances[1];
  const double units_per_cm = 1.0 / plain.anchor.convention.cm_per_unit;
  const Eigen::RowVector3d side = plain.anchor.convention.fileUp().unitOrthogonal().transpose();
  const int column = 3 * index(CanonicalJoint::LeftAnkle);
  style::StylizedClip stylized = plain;
  for (int f = jittered.first; f <= jittered.last; ++f)
    stylized.world_positions.block<1, 3>(f, column) += (f % 2 == 0 ? 1.5 : -1.5) * units_per_cm * side;
  for (int f = moved.first; f <= moved.last; ++f)
    stylized.world_positions.block<1, 3>(f, column) +=
        3.0 * kLockableSpreadCm * (static_cast<double>(f - moved.first) / (moved.last - moved.first) - 0.5) *
        units_per_cm * side;  // 60 cm across the stance, +-30 about its middle

  const style::StylizedCleanup kept = style::cleanUpStylizedClip(content, mapping, plain);
  const style::StylizedCleanup run = style::cleanUpStylizedClip(content, mapping, stylized);
  ASSERT_EQ(run.contacts.rows(), plain.frameCount()) << "solved at the network's 60 fps";
  for (int f = jittered.first; f <= jittered.last; ++f) EXPECT_EQ(run.contacts(f, 0), 1) << "jittered stance, frame " << f;
  const int middle = (moved.first + moved.last) / 2;
  EXPECT_EQ(run.contacts(middle, 0), 0) << "a stance the style moved 60 cm is not held at one point";
  EXPECT_LE(kept.cleaned.foot_skate_cm_s, 0.5);
  EXPECT_GT(run.cleaned.foot_skate_cm_s, 1.0) << "the moved stance slides (one stance of many), and the figure says so";
  EXPECT_EQ(run.cleaned.contact_steps, kept.cleaned.contact_steps) << "the same tracks are judged";
}

// A foot the style lifts off before the content's stance ends (the left foot's targets raised 2 cm a
// frame over the stance's last five frames) is lifted with its targets, and those frames are marked
// lifted (CleanupReport::lifted_contacts): the foot skates only on the floor, so the skate figure
// leaves them out (fewer steps judged), where it counted the foot's move through the air before.
TEST_F(CleanupStylized, AFootTheStyleLiftsOffEarlyIsLeftOutOfTheSkateWhileLifted) {
  const style::Stylizer stylizer(networkLikeModel(features, 11, 0.0f));
  const style::StylizedClip plain = stylizer.stylize(features, 1.0);
  const std::vector<ContactSegment> stances = stancesOf(plain, 1, 12);
  ASSERT_FALSE(stances.empty()) << "the fixture walks: its left toe has stances of 0.2 s and more";
  const ContactSegment stance = stances.front();
  const double units_per_cm = 1.0 / plain.anchor.convention.cm_per_unit;
  const Eigen::RowVector3d up = plain.anchor.convention.fileUp().transpose();
  style::StylizedClip stylized = plain;
  for (int f = stance.last - 4; f <= stance.last; ++f)
    for (CanonicalJoint joint : {CanonicalJoint::LeftAnkle, CanonicalJoint::LeftToe})
      stylized.world_positions.block<1, 3>(f, 3 * index(joint)) += 2.0 * (f - stance.last + 5) * units_per_cm * up;

  const style::StylizedCleanup kept = style::cleanUpStylizedClip(content, mapping, plain);
  const style::StylizedCleanup run = style::cleanUpStylizedClip(content, mapping, stylized);
  ASSERT_EQ(run.report.lifted_contacts.rows(), plain.frameCount()) << "solved at the network's 60 fps";
  EXPECT_EQ(kept.report.lifted_contacts.col(1).segment(stance.first, stance.last - stance.first + 1).sum(), 0);
  int lifted = 0;
  for (int f = stance.last - 4; f <= stance.last; ++f) lifted += run.report.lifted_contacts(f, 1);
  EXPECT_GE(lifted, 3) << "the toe follows the style up over the stance's last frames";
  EXPECT_EQ(run.report.lifted_contacts.col(1).segment(stance.first, stance.last - stance.first - 4).sum(), 0)
      << "not before the lift";
  EXPECT_LT(run.cleaned.contact_steps, kept.cleaned.contact_steps) << "the lifted steps are left out";
  EXPECT_LE(run.cleaned.foot_skate_cm_s, 0.5);
}

// A stance only the output has (the content's contact ends before the output's foot leaves the floor)
// is locked while the output's foot is down and ends where it rises past the detector's height
// (foot_contacts.h): with the detector's hysteresis (release at 1.5x its thresholds) such a stance held
// on while the style lifted the foot, and the clean-up held the rising foot down. Here the content's
// left foot contact is cut at the middle of a long stance, and from there the output's foot (still,
// mid-stance) rises 1.5 cm a frame (60 fps) from the 4th frame on.
TEST_F(CleanupStylized, AStanceOnlyTheOutputHasEndsWhereItsFootRisesPastTheDetectorsHeight) {
  const style::Stylizer stylizer(networkLikeModel(features, 11, 0.0f));
  const style::StylizedClip plain = stylizer.stylize(features, 1.0);
  const std::vector<ContactSegment> stances = stancesOf(plain, 0, 30);
  ASSERT_FALSE(stances.empty()) << "the fixture walks: its left heel has stances of 0.5 s and more";
  const ContactSegment stance = stances.front();
  const double units_per_cm = 1.0 / plain.anchor.convention.cm_per_unit;
  const Eigen::Vector3d up = plain.anchor.convention.fileUp();
  constexpr int kRising = 14, kStill = 3;
  constexpr double kRiseCm = 1.5;
  const int cut = (stance.first + stance.last) / 2;  // the content's contact ends before this frame
  const int last = std::min(stance.last, cut + kRising - 1);
  const auto rise_cm = [&](int f) { return std::max(0, std::min(f, last) - cut + 1 - kStill) * kRiseCm; };
  style::StylizedClip stylized = plain;
  for (CanonicalJoint joint : {CanonicalJoint::LeftAnkle, CanonicalJoint::LeftToe})
    for (int f = cut; f <= stance.last; ++f) {
      stylized.contacts(joint == CanonicalJoint::LeftAnkle ? 0 : 1, f) = 0.0;
      stylized.world_positions.block<1, 3>(f, 3 * index(joint)) += rise_cm(f) * units_per_cm * up.transpose();
    }
  const style::StylizedCleanup run = style::cleanUpStylizedClip(content, mapping, stylized);
  ASSERT_EQ(run.contacts.rows(), plain.frameCount()) << "solved at the network's 60 fps";
  const double threshold_cm =
      ContactDetectionOptions{}.height_threshold * restPoseBodyHeight(content.skeleton, up) / units_per_cm;
  int locked_up = 0, risen = 0;
  for (int f = cut; f <= last; ++f) {
    if (rise_cm(f) < threshold_cm - 1.0) {
      EXPECT_EQ(run.contacts(f, 0), 1) << "the output's heel still down, frame " << f;
    }
    if (rise_cm(f) > threshold_cm + 1.0) {
      ++risen;
      locked_up += run.contacts(f, 0);
    }
  }
  ASSERT_GE(risen, 5);
  EXPECT_EQ(locked_up, 0) << "frames locked with the heel risen past the detector's height (" << threshold_cm << " cm)";
}

// A 120 fps clip is solved at 60 fps: the clean-up's warnings still name the clip's own frames, the
// ones on the timeline and in the exported file. A contact forced on the left foot for half a second
// where the content's left ankle travels furthest holds it far from its targets there.
TEST_F(CleanupStylized, WarningsNameTheContentsFramesWhenSolvedAtAnotherRate) {
  ASSERT_NEAR(content.fps(), 120.0, 0.01);
  constexpr int kSpan = 60;
  const Eigen::MatrixXd world = worldPositions(content);
  const int ankle = mapping[CanonicalJoint::LeftAnkle];
  int kFirst = 0;
  double travel = 0.0;
  for (int start = 0; start + kSpan <= content.frameCount(); start += 10) {
    const double moved = (world.block(start + kSpan - 1, 3 * ankle, 1, 3) - world.block(start, 3 * ankle, 1, 3)).norm() *
                         features.anchor.convention.cm_per_unit;
    if (moved > travel) std::tie(kFirst, travel) = std::pair{start, moved};
  }
  const int kLast = kFirst + kSpan - 1;
  ASSERT_GT(travel, 30.0) << "the content walks";  // cm
  Eigen::MatrixXi overrides = Eigen::MatrixXi::Constant(content.frameCount(), kContactCount, -1);
  overrides.block(kFirst, 0, kSpan, 2).setOnes();  // left heel and toe (ContactLabel order)
  // The network's own contacts stay unplanted: the forced contact is then the clip's one large residual.
  style::ContactProjection unplanted;
  unplanted.iterations = 0;
  const style::StylizedClip stylized =
      style::Stylizer(networkLikeModel(features, 11, kDamage), "the test network", {}, unplanted).stylize(features, 1.0);
  const style::StylizedCleanup run = style::cleanUpStylizedClip(content, mapping, stylized, {}, 0.0, overrides);
  ASSERT_NEAR(run.fps, 60.0, 0.01);
  int named = 0;
  for (const std::string& warning : warningTexts(run.report)) {
    std::printf("[ warning  ] %s\n", warning.c_str());
    int first = 0, last = 0;
    const std::size_t at = warning.find(" at frames ");
    if (warning.find("large residual: Left") == std::string::npos || at == std::string::npos) continue;
    ASSERT_EQ(std::sscanf(warning.c_str() + at, " at frames %d-%d", &first, &last), 2) << warning;
    // Within the forced contact, give or take its blend (contact_blend_seconds, 0.04 s: 5 frames at 120 fps).
    EXPECT_GE(first, kFirst - 8) << warning;
    EXPECT_LE(last, kLast + 8) << warning;
    ++named;
  }
  EXPECT_GT(named, 0) << "a foot held still for half a second of walking leaves its targets";
}

// A clip below the network's 60 fps is solved on its own frames (the targets taken at its times), at
// rates that divide 60 and rates that do not: the result has the content's frames and meets the goals.
TEST(CleanupStylizedBelowTheNetworksRate, IsSolvedOnTheContentsOwnFrames) {
  const Motion zombie = readBvh(test::fixture("zombie.bvh"));
  for (const double fps : {30.0, 24.0}) {
    SCOPED_TRACE(std::to_string(fps) + " fps");
    const Motion content = sameFrameRate(zombie.fps(), fps) ? zombie : resampleMotion(zombie, fps);
    const JointMapping mapping = mapJoints(content.skeleton, content.source);
    const MotionFeatures features = extractFeatures(content, mapping);
    const style::StylizedClip stylized = style::Stylizer(networkLikeModel(features, 11, kDamage)).stylize(features, 1.0);
    ASSERT_GT(stylized.frameCount(), content.frameCount());  // the network's 60 fps
    const style::StylizedCleanup run = style::cleanUpStylizedClip(content, mapping, stylized);
    std::printf("[ figures  ] %.0f fps: skate %.3f cm/s, penetration %.3f cm, residual %.2f cm (max %.2f)\n", fps,
                run.cleaned.foot_skate_cm_s, run.cleaned.penetration_max_cm, run.cleaned.residual_mean_cm,
                run.cleaned.residual_max_cm);
    EXPECT_DOUBLE_EQ(run.fps, content.fps());
    EXPECT_EQ(run.report.frames, content.frameCount());
    EXPECT_EQ(run.contacts.rows(), content.frameCount());
    EXPECT_EQ(run.motion.frameCount(), content.frameCount());
    EXPECT_DOUBLE_EQ(run.motion.fps(), content.fps());
    EXPECT_GT(run.cleaned.contact_steps, 0);
    EXPECT_LE(run.cleaned.foot_skate_cm_s, 0.5);
    EXPECT_LE(run.cleaned.penetration_max_cm, 0.5);
    EXPECT_LE(run.cleaned.residual_mean_cm, 2.0);
  }
}

}  // namespace
}  // namespace motionstyle
