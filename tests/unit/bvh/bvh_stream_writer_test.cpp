// BVH stream writer: refusals first (a bad skeleton, bad blocks, a frame count that does not match the
// header), then that any split into blocks gives formatBvh's bytes.

#include <gtest/gtest.h>

#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "bvh/bvh_reader.h"
#include "bvh/bvh_writer.h"
#include "bvh_test_clips.h"
#include "test_paths.h"

namespace motionstyle {
namespace {

using test::kTinyBvh;

// The text written for `motion` in blocks of `block_frames` rows (the last block may be shorter).
std::string writtenInBlocks(const Motion& motion, Eigen::Index block_frames) {
  std::ostringstream out;
  BvhStreamWriter writer(out, motion.skeleton, motion.frameCount(), motion.frame_time);
  for (Eigen::Index first = 0; first < motion.values.rows(); first += block_frames)
    writer.writeFrames(motion.values.middleRows(first, std::min(block_frames, motion.values.rows() - first)));
  writer.finish();
  return out.str();
}

// A skeleton whose file order is not depth-first: root, A, B, A1 (child of A), A1's End Site.
Motion notDepthFirst() {
  Motion motion;
  motion.frame_time = 0.02;
  auto joint = [](std::string name, int parent, bool end_site) {
    Joint j;
    j.name = std::move(name);
    j.parent = parent;
    j.end_site = end_site;
    j.offset = Eigen::Vector3d(parent + 1.0, 0.5, 0.0);
    if (!end_site) j.channels = {ChannelType::Zrotation, ChannelType::Xrotation, ChannelType::Yrotation};
    return j;
  };
  motion.skeleton.joints = {joint("root", -1, false), joint("A", 0, false), joint("B", 0, false), joint("A1", 1, false),
                            joint("A1_End", 3, true)};
  motion.values.resize(7, 12);
  for (int f = 0; f < 7; ++f)
    for (int c = 0; c < 12; ++c) motion.values(f, c) = 100.0 * f + c + 1.0 / (c + 3.0);
  return motion;
}

TEST(BvhStreamWriterInvalid, FinishWithTooFewFramesThrows) {
  const Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  std::ostringstream out;
  BvhStreamWriter writer(out, motion.skeleton, 2, motion.frame_time);
  writer.writeFrames(motion.values.topRows(1));
  EXPECT_THROW(writer.finish(), std::invalid_argument);
  EXPECT_EQ(writer.framesWritten(), 1);
  writer.writeFrames(motion.values.bottomRows(1));
  EXPECT_NO_THROW(writer.finish());
}

TEST(BvhStreamWriterInvalid, BadBlocksThrowAndWriteNothing) {
  const Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  std::ostringstream out;
  BvhStreamWriter writer(out, motion.skeleton, 2, motion.frame_time);
  const std::string header = out.str();
  EXPECT_EQ(header, kTinyBvh.substr(0, kTinyBvh.find("1 2 3")));

  MatrixRowMajor narrow = motion.values.leftCols(8);
  EXPECT_THROW(writer.writeFrames(narrow), std::invalid_argument);  // a wrong column count
  MatrixRowMajor with_nan = motion.values;
  with_nan(1, 4) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(writer.writeFrames(with_nan), std::invalid_argument);
  MatrixRowMajor three(3, 9);
  three.setZero();
  EXPECT_THROW(writer.writeFrames(three), std::invalid_argument);  // beyond the 2 frames announced
  EXPECT_EQ(out.str(), header);
  EXPECT_EQ(writer.framesWritten(), 0);

  writer.writeFrames(motion.values);
  EXPECT_THROW(writer.writeFrames(motion.values.topRows(1)), std::invalid_argument);
  writer.finish();
  EXPECT_EQ(out.str(), kTinyBvh);
}

TEST(BvhStreamWriterInvalid, UnwritableHeaderThrowsAndWritesNothing) {
  const Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  std::ostringstream out;
  Skeleton partial = motion.skeleton;
  partial.joints[1].channels.pop_back();
  EXPECT_THROW(BvhStreamWriter(out, partial, 2, motion.frame_time), std::invalid_argument);
  Skeleton bad_name = motion.skeleton;
  bad_name.joints[1].name = "Spine\nMOTION";
  EXPECT_THROW(BvhStreamWriter(out, bad_name, 2, motion.frame_time), std::invalid_argument);
  Skeleton orphan = motion.skeleton;
  orphan.joints[1].parent = 5;
  EXPECT_THROW(BvhStreamWriter(out, orphan, 2, motion.frame_time), std::invalid_argument);
  EXPECT_THROW(BvhStreamWriter(out, motion.skeleton, -1, motion.frame_time), std::invalid_argument);
  EXPECT_THROW(BvhStreamWriter(out, motion.skeleton, 2, 0.0), std::invalid_argument);
  EXPECT_THROW(BvhStreamWriter(out, motion.skeleton, 2, std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_EQ(out.str(), "");
}

TEST(BvhStreamWriter, AnyBlockSplitGivesFormatBvhBytes) {
  const Motion clips[] = {parseBvh(kTinyBvh, "tiny.bvh"), readBvh(test::fixture("cmu_131_01.bvh")),
                          readBvh(test::fixture("zombie.bvh")), notDepthFirst()};
  for (const Motion& motion : clips) {
    const std::string expected = formatBvh(motion);
    for (Eigen::Index block : {Eigen::Index{1}, Eigen::Index{3}, std::max<Eigen::Index>(motion.values.rows(), 1)})
      EXPECT_EQ(writtenInBlocks(motion, block), expected) << motion.source << ", blocks of " << block << " frames";
  }
}

TEST(BvhStreamWriter, HeaderOnlyForZeroFrames) {
  Motion motion = parseBvh(kTinyBvh, "tiny.bvh");
  motion.values.resize(0, 9);
  std::ostringstream out;
  BvhStreamWriter writer(out, motion.skeleton, 0, motion.frame_time);
  writer.finish();
  EXPECT_EQ(out.str(), formatBvh(motion));
  EXPECT_EQ(parseBvh(out.str(), "rest.bvh").frameCount(), 0);
}

}  // namespace
}  // namespace motionstyle
