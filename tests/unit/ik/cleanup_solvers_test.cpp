// The kinematic-tree solver against its references: the cost it minimises is the Ceres functors' cost,
// its gradient is the cost's (central differences), a frame solved by both ends at the same cost, and
// a whole clip cleaned by both has the same quality. Then the chunking: the thread count never changes
// the result, and chunks join where a single sweep would have been.
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <utility>
#include <stdexcept>

#include <atomic>

#include "bvh/bvh_reader.h"
#include "common/errors.h"
#include "features/foot_contacts.h"
#include "ik/cleanup.h"
#include "ik/cleanup_frame_solver.h"
#include "ik/cleanup_window_solver.h"
#include "ik/cost_functors.h"
#include "ik/metrics.h"
#include "ik_test_support.h"
#include "mapping/joint_mapping.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

using ik_detail::FrameData;
using ik_detail::FrameRef;

Eigen::Quaterniond randomTurn(std::mt19937& rng, double radians) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::Vector3d axis = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(radians * std::abs(normal(rng)), axis));
}

// One frame of the CMU fixture with targets, locks and floor all active, and two previous frames.
class FrameProblem : public ::testing::Test {
 protected:
  void SetUp() override {
    clip = readBvh(test::fixture("cmu_131_01.bvh"));
    mapping = mapJoints(clip.skeleton, clip.source);
    model = ik_detail::buildCleanupModel(clip.skeleton, mapping.joints);
    poses = localPoses(clip);
    const Eigen::MatrixXd world = worldPositions(clip);
    const int frame = 40;
    std::mt19937 rng(3);
    std::normal_distribution<double> normal(0.0, 1.0);
    ik_detail::treeSegmentsAt(model, clip.skeleton, poses, frame, data.tree);
    for (size_t c = 0; c < kCanonicalJointCount; ++c)
      data.targets[c] = world.block<1, 3>(frame, 3 * mapping.joints[c]).transpose() +
                        Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    for (size_t i = 0; i < kContactCount; ++i) {
      data.lock_positions[i] = data.targets[static_cast<size_t>(index(kContactJoint[i]))] + Eigen::Vector3d(1.0, 0.0, 2.0);
      data.lock_weights[i] = i == 2 ? 0.0 : 10.0 * static_cast<double>(i + 1);
    }
    const int unknowns = model.unknownCount();
    data.prior_rotations.resize(static_cast<size_t>(unknowns));
    for (int u = 0; u < unknowns; ++u) {
      const int joint = model.unknown_joints[static_cast<size_t>(u)];
      data.prior_rotations[static_cast<size_t>(u)] = poses.rotation(frame, joint);
      for (int k = 0; k < 3; ++k)
        rotations[k].push_back(poses.rotation(frame - 2 + k, joint) * randomTurn(rng, 0.1));
    }
    data.smoothness_scale = 1.0;
    for (int k = 0; k < 3; ++k) roots[k] = poses.translation(frame - 2 + k, 0) + Eigen::Vector3d(normal(rng), 0.5, normal(rng));
    // A floor above the ankles' height, so that the floor term is active for some contact joints.
    constants.floor_height = world(frame, 3 * mapping.joints[static_cast<size_t>(index(CanonicalJoint::LeftAnkle))] + 1) + 0.5;
    constants.cm_per_unit = 2.54;
  }

  FrameRef ref(int k) const { return {&roots[k], rotations[k].data()}; }

  // The start pose (frame f) moved by `step` along solver coordinate i: [P; d_0; ...], a rotation step
  // turning on the right, as the solver's own steps do.
  std::pair<Eigen::Vector3d, std::vector<Eigen::Quaterniond>> perturbed(int i, double step) const {
    Eigen::Vector3d root = roots[2];
    std::vector<Eigen::Quaterniond> q = rotations[2];
    if (i < 3) {
      root[i] += step;
    } else {
      Eigen::Quaterniond& turned = q[static_cast<size_t>(i / 3 - 1)];
      turned = turned * Eigen::Quaterniond(Eigen::AngleAxisd(step, Eigen::Vector3d::Unit(i % 3)));
    }
    return {root, q};
  }

  // The Ceres window solver of one frame, loaded with this frame at the start pose.
  std::unique_ptr<ik_detail::WindowSolver> ceresAtStart() const {
    auto ceres = ik_detail::makeCeresWindowSolver(model, options, constants, 1);
    ceres->frame(0) = data;
    ceres->setPrevious(ref(0), ref(1));
    ceres->setStart(0, roots[2], rotations[2].data());
    return ceres;
  }

  Motion clip;
  JointMapping mapping;
  ik_detail::CleanupModel model;
  LocalPoses poses;
  FrameData data;
  ik_detail::ProblemConstants constants;
  CleanupOptions options;
  std::array<Eigen::Vector3d, 3> roots;
  std::array<std::vector<Eigen::Quaterniond>, 3> rotations;  // frames f-2, f-1, f (the start)
};

void expectSameCosts(const CleanupTermCosts& a, const CleanupTermCosts& b) {
  const double tolerance = 1e-10 * std::max(1.0, a.total());
  EXPECT_NEAR(a.position, b.position, tolerance);
  EXPECT_NEAR(a.contact, b.contact, tolerance);
  EXPECT_NEAR(a.floor, b.floor, tolerance);
  EXPECT_NEAR(a.smoothness, b.smoothness, tolerance);
  EXPECT_NEAR(a.prior, b.prior, tolerance);
}

TEST(CleanupSolverOptions, RejectsWindowsForTheTreeSolverAndBadChunks) {
  CleanupOptions options;
  options.window_frames = 3;
  EXPECT_THROW(options.validate(), std::invalid_argument);
  options.solver = CleanupSolver::Ceres;
  EXPECT_NO_THROW(options.validate());
  for (auto set : {+[](CleanupOptions& o) { o.chunk_frames = 0; }, +[](CleanupOptions& o) { o.chunk_lead_in = -1; },
                   +[](CleanupOptions& o) { o.threads = -1; }}) {
    CleanupOptions bad;
    set(bad);
    EXPECT_THROW(bad.validate(), std::invalid_argument);
  }
}

TEST_F(FrameProblem, CostIsTheCeresFunctorsCost) {
  ik_detail::FrameSolver tree(model, options, constants);
  CleanupTermCosts reference;
  ceresAtStart()->addCosts(0, reference);
  const CleanupTermCosts ours = tree.costs(data, ref(0), ref(1), roots[2], rotations[2].data());
  ASSERT_GT(ours.floor, 0.0) << "the floor term must be active for this check";
  ASSERT_GT(ours.contact, 0.0);
  expectSameCosts(ours, reference);
}

TEST_F(FrameProblem, GradientMatchesCentralDifferences) {
  ik_detail::FrameSolver tree(model, options, constants);
  const Eigen::VectorXd gradient = tree.gradient(data, ref(0), ref(1), roots[2], rotations[2].data());
  const int unknowns = model.unknownCount();
  ASSERT_EQ(gradient.size(), 3 * (unknowns + 1));
  const double h = 1e-6;
  for (int i = 0; i < gradient.size(); ++i) {
    double sides[2];
    for (int side = 0; side < 2; ++side) {
      const auto [root, q] = perturbed(i, side == 0 ? h : -h);
      sides[side] = tree.costs(data, ref(0), ref(1), root, q.data()).total();
    }
    const double numeric = (sides[0] - sides[1]) / (2.0 * h);
    EXPECT_NEAR(gradient[i], numeric, 1e-4 * std::max(1.0, std::abs(numeric))) << "coordinate " << i;
  }
}

// Where every residual is 0 the cost's Hessian is J'J, so differences of the gradient check J'J. The
// positions come from the Ceres functors' own forward kinematics (an independent implementation).
TEST_F(FrameProblem, NormalMatrixMatchesDifferencesOfTheGradientAtAZeroResidual) {
  for (size_t c = 0; c < kCanonicalJointCount; ++c) {
    std::vector<std::array<double, 4>> blocks;
    std::vector<const double*> parameters = {roots[2].data()};
    for (int pivot : model.chains[c].pivots) {
      const Eigen::Quaterniond& q = rotations[2][static_cast<size_t>(pivot)];
      blocks.push_back({q.w(), q.x(), q.y(), q.z()});
    }
    for (const auto& block : blocks) parameters.push_back(block.data());
    ik_detail::canonicalJointPosition(model, data, static_cast<int>(c), parameters.data(), data.targets[c].data());
  }
  for (size_t i = 0; i < kContactCount; ++i) data.lock_positions[i] = data.targets[static_cast<size_t>(index(kContactJoint[i]))];
  data.prior_rotations = rotations[2];
  constants.floor_height = -1e6;
  const FrameRef pose = ref(2);

  ik_detail::FrameSolver tree(model, options, constants);
  ASSERT_LT(tree.costs(data, pose, pose, roots[2], rotations[2].data()).total(), 1e-18);
  const Eigen::MatrixXd normal = tree.normalMatrix(data, pose, pose, roots[2], rotations[2].data());
  const double h = 1e-6;
  Eigen::MatrixXd numeric(normal.rows(), normal.cols());
  for (int j = 0; j < normal.cols(); ++j) {
    Eigen::VectorXd sides[2];
    for (int side = 0; side < 2; ++side) {
      const auto [root, q] = perturbed(j, side == 0 ? h : -h);
      sides[side] = tree.gradient(data, pose, pose, root, q.data());
    }
    numeric.col(j) = (sides[0] - sides[1]) / (2.0 * h);
  }
  const double scale = normal.cwiseAbs().maxCoeff();
  EXPECT_LT((normal - numeric).cwiseAbs().maxCoeff(), 1e-5 * scale);
  EXPECT_LT((normal - normal.transpose()).cwiseAbs().maxCoeff(), 1e-9 * scale);
}

TEST_F(FrameProblem, SolvedFrameReachesCeresCost) {
  ik_detail::FrameSolver tree(model, options, constants);
  Eigen::Vector3d root = roots[2];
  std::vector<Eigen::Quaterniond> q = rotations[2];
  const double start = tree.costs(data, ref(0), ref(1), root, q.data()).total();
  const ik_detail::FrameSolveResult ours = tree.solve(data, ref(0), ref(1), root, q.data());

  auto ceres = ceresAtStart();
  const ik_detail::WindowSolveStats ceres_stats = ceres->solve(60.0);
  CleanupTermCosts reference;
  ceres->addCosts(0, reference);

  EXPECT_LT(ours.costs.total(), 0.5 * start);
  EXPECT_LE(ours.costs.total(), reference.total() * (1.0 + 1e-4)) << "Ceres found a lower cost";
  EXPECT_LE(ours.iterations, ceres_stats.iterations + 2) << "Ceres: " << ceres_stats.iterations << ", cost " << reference.total() << " ours " << ours.costs.total();
  expectSameCosts(ours.costs, tree.costs(data, ref(0), ref(1), root, q.data()));  // reported = returned pose
}

// The whole clip: damaged targets on the CMU fixture, cleaned by both solvers.
class CleanupSolvers : public ::testing::Test {
 protected:
  void SetUp() override {
    clip = readBvh(test::fixture("cmu_131_01.bvh"));
    mapping = mapJoints(clip.skeleton, clip.source);
    const Eigen::MatrixXd world = worldPositions(clip);
    const std::array<int, kContactCount> feet = contactJoints(mapping);
    floor = estimateFloorHeight(world, feet, up);
    contacts = detectContacts(world, feet, up, floor, clip.fps(), restPoseBodyHeight(clip.skeleton, up));
    targets = test::damageTargets(test::canonicalPositions(world, mapping), contacts, clip.fps(), cm, up, {});
  }

  Motion clean(const CleanupOptions& options, CleanupReport* report = nullptr) const {
    return cleanupMotion(CleanupInput{clip, mapping, targets, contacts, up, floor, cm}, options, report);
  }

  ClipMetrics metricsOf(const Motion& result) const {
    return test::cleanedClipMetrics(worldPositions(result), clip, mapping, contacts, targets, up, floor, cm);
  }

  Motion clip;
  JointMapping mapping;
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  double cm = 2.54 / 0.45;  // the CMU unit (cleanup_real_clip_test.cpp)
  double floor = 0.0;
  Eigen::MatrixXi contacts;
  Eigen::MatrixXd targets;
};

TEST_F(CleanupSolvers, TreeAndCeresGiveTheSameQuality) {
  CleanupOptions tree_options, ceres_options;
  ceres_options.solver = CleanupSolver::Ceres;
  CleanupReport tree_report, ceres_report;
  const ClipMetrics tree = metricsOf(clean(tree_options, &tree_report));
  const ClipMetrics ceres = metricsOf(clean(ceres_options, &ceres_report));
  EXPECT_NEAR(tree.foot_skate_cm_s, ceres.foot_skate_cm_s, 0.01 + 0.1 * ceres.foot_skate_cm_s);
  EXPECT_NEAR(tree.residual_mean_cm, ceres.residual_mean_cm, 0.02 * ceres.residual_mean_cm);
  EXPECT_LE(tree.penetration_max_cm, ceres.penetration_max_cm + 0.05);
  EXPECT_LE(tree_report.final_costs.total(), ceres_report.final_costs.total() * 1.01);
  EXPECT_LT(tree.bone_error_max_cm, 1e-9);
}

TEST_F(CleanupSolvers, ThreadCountNeverChangesTheResult) {
  CleanupOptions one, many;
  one.chunk_frames = many.chunk_frames = 50;
  one.threads = 1;
  many.threads = 3;
  const Motion a = clean(one), b = clean(many);
  EXPECT_EQ(a.values, b.values);
}

// A live edit's clip (a few hundred frames) comes in four chunks, so that one core can take the next
// while the other is preempted; a clip too short for four chunks of three lead-ins gets as many as fit,
// and a long clip chunks of about chunk_frames.
TEST_F(CleanupSolvers, ShortClipsComeInFourChunksWhereEachIsThreeLeadInsLong) {
  const auto chunksOf = [&](int frames, const CleanupOptions& options) {
    Motion part = clip;
    part.values = clip.values.topRows(frames);
    CleanupReport report;
    cleanupMotion(CleanupInput{part, mapping, targets.topRows(frames), contacts.topRows(frames), up, floor, cm},
                  options, &report);
    return report.chunks;
  };
  const CleanupOptions defaults;  // chunk_frames 480, lead-in 40
  EXPECT_EQ(chunksOf(clip.frameCount(), defaults), 4);  // 720 frames: four, not round(720 / 480) = 2
  EXPECT_EQ(chunksOf(300, defaults), 2);                // 300 / (3 x 40): two
  EXPECT_EQ(chunksOf(200, defaults), 1);                // under six lead-ins: one sweep
  CleanupOptions short_chunks;
  short_chunks.chunk_frames = 100;
  EXPECT_EQ(chunksOf(clip.frameCount(), short_chunks), 7);  // round(720 / 100)
}

TEST_F(CleanupSolvers, ChunksJoinWhereOneSweepWouldBe) {
  CleanupOptions chunked, whole;
  chunked.chunk_frames = 50;
  whole.chunk_frames = clip.frameCount();
  const Eigen::MatrixXd a = worldPositions(clean(chunked)), b = worldPositions(clean(whole));
  EXPECT_LT((a - b).cwiseAbs().maxCoeff() * cm, 0.1) << "cm";  // under a millimetre anywhere
}

}  // namespace
}  // namespace motionstyle

namespace motionstyle {
namespace {

TEST_F(CleanupSolvers, MemoryReusesWhatDidNotChangeAndMatchesAFullSolve) {
  CleanupOptions options;
  options.chunk_frames = 120;
  CleanupMemory memory;
  CleanupReport first, again;
  const Motion a = cleanupMotion(CleanupInput{clip, mapping, targets, contacts, up, floor, cm}, options, &first,
                                 {nullptr, &memory});
  EXPECT_EQ(first.chunks_reused, 0);
  const Motion b = cleanupMotion(CleanupInput{clip, mapping, targets, contacts, up, floor, cm}, options, &again,
                                 {nullptr, &memory});
  EXPECT_EQ(again.chunks_reused, again.chunks);
  EXPECT_EQ(again.solves, 0);
  EXPECT_EQ(a.values, b.values);
  EXPECT_DOUBLE_EQ(again.final_costs.total(), first.final_costs.total());

  // One target moved late in the clip: only the chunks that read that frame are solved again, and the
  // result is what a clean-up without memory gives (within the solver's tolerance).
  Eigen::MatrixXd edited = targets;
  const int frame = clip.frameCount() - 30;
  edited.block<1, 3>(frame, 3 * index(CanonicalJoint::LeftWrist)) += Eigen::RowVector3d(3.0, 0.0, 0.0) / cm;
  CleanupReport partial;
  const Motion c = cleanupMotion(CleanupInput{clip, mapping, edited, contacts, up, floor, cm}, options, &partial,
                                 {nullptr, &memory});
  EXPECT_EQ(partial.chunks_reused, partial.chunks - 1);
  EXPECT_EQ(partial.chunks_warm, 1);
  const Motion full = cleanupMotion(CleanupInput{clip, mapping, edited, contacts, up, floor, cm}, options, nullptr);
  EXPECT_LT((worldPositions(c) - worldPositions(full)).cwiseAbs().maxCoeff() * cm, 0.05);
  EXPECT_EQ(c.values.topRows(frame - 120 - options.chunk_lead_in), full.values.topRows(frame - 120 - options.chunk_lead_in));
}

// Every target moved by 2 cm along the floor (a strength step moves every frame a little, and
// neighbouring frames alike): the solution moves with them, and from the frame before's new solution
// each frame starts almost where it ends: 1.04 iterations a frame here, where starting every frame
// from its own last solution (the memory's first scheme) took 2.0 and no memory 3.2.
TEST_F(CleanupSolvers, AWarmSolveCarriesTheFrameBeforesCorrection) {
  CleanupOptions options;
  options.chunk_frames = 120;
  CleanupMemory memory;
  CleanupReport cold, warm;
  cleanupMotion(CleanupInput{clip, mapping, targets, contacts, up, floor, cm}, options, &cold, {nullptr, &memory});
  Eigen::MatrixXd moved = targets;
  for (Eigen::Index joint = 0; joint < moved.cols() / 3; ++joint)
    moved.col(3 * joint).array() += 2.0 / cm;  // x: along the floor (up is y)
  const Motion again = cleanupMotion(CleanupInput{clip, mapping, moved, contacts, up, floor, cm}, options, &warm,
                                     {nullptr, &memory});
  EXPECT_EQ(warm.chunks_warm, warm.chunks);
  EXPECT_LT(static_cast<double>(warm.total_iterations) / warm.solves, 1.5);
  EXPECT_GT(static_cast<double>(cold.total_iterations) / cold.solves, 2.5);
  const Motion full = cleanupMotion(CleanupInput{clip, mapping, moved, contacts, up, floor, cm}, options, nullptr);
  // The solver's tolerance: 2 mm at the clavicles' prior of 10 per rad (under 1 mm at 20).
  EXPECT_LT((worldPositions(again) - worldPositions(full)).cwiseAbs().maxCoeff() * cm, 0.25);
}

TEST_F(CleanupSolvers, ACleanupWithMemoryOfAnotherClipSolvesEverything) {
  CleanupOptions options;
  options.chunk_frames = 120;
  CleanupMemory memory;
  cleanupMotion(CleanupInput{clip, mapping, targets, contacts, up, floor, cm}, options, nullptr, {nullptr, &memory});
  Motion other = clip;
  other.values.col(10).array() += 1.0;  // another clip of the same length and rig
  CleanupReport report;
  const Motion with_memory = cleanupMotion(CleanupInput{other, mapping, targets, contacts, up, floor, cm}, options,
                                           &report, {nullptr, &memory});
  EXPECT_EQ(report.chunks_reused, 0);
  EXPECT_EQ(report.chunks_warm, 0);
  EXPECT_EQ(with_memory.values, cleanupMotion(CleanupInput{other, mapping, targets, contacts, up, floor, cm}, options,
                                              nullptr).values);
}

// A cancelled clean-up (a live edit dropping a job that has only just started) keeps what the memory
// held: the next solve of the same inputs reuses every chunk, exactly.
TEST_F(CleanupSolvers, CancelStopsTheSolveAndKeepsTheMemoryWhole) {
  CleanupMemory memory;
  CleanupReport first;
  const Motion solved = cleanupMotion(CleanupInput{clip, mapping, targets, contacts, up, floor, cm}, {}, &first,
                                      {nullptr, &memory});
  ASSERT_GT(first.chunks, 1);
  std::atomic<bool> cancel{true};
  Eigen::MatrixXd moved = targets;
  moved.array() += 0.5;
  EXPECT_THROW(cleanupMotion(CleanupInput{clip, mapping, moved, contacts, up, floor, cm}, {}, nullptr,
                             {&cancel, &memory}),
               OperationCancelled);
  CleanupReport again;
  const Motion reused = cleanupMotion(CleanupInput{clip, mapping, targets, contacts, up, floor, cm}, {}, &again,
                                      {nullptr, &memory});
  EXPECT_EQ(again.chunks_reused, again.chunks);
  EXPECT_EQ(reused.values, solved.values);
}

}  // namespace
}  // namespace motionstyle
