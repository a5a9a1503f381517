#include "style/stylized_cleanup.h"

#include <cmath>
#include <stdexcept>

#include "features/foot_contacts.h"
#include "motion/kinematics.h"
#include "motion/resample.h"

namespace motionstyle::style {
namespace {

bool sameRate(double a, double b) { return std::abs(a - b) <= 1e-6 * b; }

Eigen::MatrixXi contactsPerFrame(const Eigen::MatrixXd& contacts) {
  return (contacts.transpose().array() > 0.5).cast<int>().matrix();
}

}  // namespace

double fileFloorHeight(const FeatureAnchor& anchor) {
  // Reference cm -> canonical cm -> file units; the up axis is the same line in both spaces.
  return anchor.floor_height / anchor.scale / anchor.convention.cm_per_unit;
}

StylizedCleanup cleanUpStylizedClip(const Motion& content, const JointMapping& mapping, const StylizedClip& stylized,
                                    const CleanupOptions& options, double output_fps) {
  const Motion at_rate = sameRate(content.fps(), stylized.fps) ? content : resampleMotion(content, stylized.fps);
  if (at_rate.frameCount() != stylized.frameCount())
    throw std::invalid_argument("cleanUpStylizedClip: the stylized clip has " + std::to_string(stylized.frameCount()) +
                                " frames, its content " + std::to_string(at_rate.frameCount()) + " at the same rate");
  const FeatureAnchor& anchor = stylized.anchor;
  const Eigen::Vector3d up = anchor.convention.fileUp();
  const double floor = fileFloorHeight(anchor);
  // Locks: the content's contacts OR those detected on the output. The content's labels are what the
  // network was trained to respect (the foot loss), frame for frame (the networks keep the clip's
  // timing), and they judge the raw output. Detection on the raw output alone misses most of them:
  // its feet slide at 70-100 cm/s where the content is planted, above any speed threshold (measured
  // on a held-back Bandai run with three style networks: 0-6 contact frames of 159, vs 15-35 per
  // foot joint in the content), so the clean-up locked almost nothing and the cleaned feet still slid
  // at 60-90 cm/s there. Contacts found on the output as well keep any stance a style lengthens.
  const Eigen::MatrixXi content_contacts = contactsPerFrame(stylized.contacts);
  const Eigen::MatrixXi contacts =
      content_contacts.cwiseMax(detectContacts(stylized.world_positions, canonicalContactJoints(), up, floor,
                                               stylized.fps, restPoseBodyHeight(content.skeleton, up)));

  StylizedCleanup result;
  result.contacts = contacts;
  const CleanupInput input(at_rate, mapping, stylized.world_positions, contacts, up, floor,
                           anchor.convention.cm_per_unit);
  Motion cleaned = cleanupMotion(input, options, &result.report);

  // Raw output: canonical joints only, judged against the content's own canonical bone lengths.
  const Eigen::MatrixXd content_world = worldPositions(at_rate);
  MetricsInput raw(stylized.world_positions, identityCanonicalJoints(), canonicalBones(content_world, mapping));
  raw.contacts = content_contacts;
  raw.up = up;
  raw.floor_height = floor;
  raw.cm_per_unit = anchor.convention.cm_per_unit;
  raw.fps = stylized.fps;
  result.raw = computeMetrics(raw);

  const Eigen::MatrixXd cleaned_world = worldPositions(cleaned);
  MetricsInput after(cleaned_world, mapping.joints, skeletonBones(cleaned.skeleton));
  after.contacts = contacts;
  after.targets = stylized.world_positions;
  after.up = up;
  after.floor_height = floor;
  after.cm_per_unit = anchor.convention.cm_per_unit;
  after.fps = stylized.fps;
  result.cleaned = computeMetrics(after);

  const double target_fps = output_fps > 0.0 ? output_fps : content.fps();
  result.motion = sameRate(cleaned.fps(), target_fps) ? std::move(cleaned) : resampleMotion(cleaned, target_fps);
  result.motion.source = content.source;
  return result;
}

}  // namespace motionstyle::style
