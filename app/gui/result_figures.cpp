#include "result_figures.h"

#include <stdexcept>

#include "mapping/canonical_joints.h"
#include "motion/kinematics.h"
#include "motion/resample.h"

namespace motionstyle {
namespace {

const JointMapping& mappingOf(const LoadedClip& content) {
  if (!content.mapping) throw std::invalid_argument("result figures: the content clip " + content.name.toStdString() + " is not mapped");
  return *content.mapping;
}

}  // namespace

FigureData cleanedOutputFigure(const style::StylizeCleanupResult& result, const LoadedClip& content, const QString& name,
                               double display_fps) {
  const JointMapping& mapping = mappingOf(content);
  const Motion& cleaned = result.cleaned;  // at the content's rate
  std::vector<int> parents;
  parents.reserve(static_cast<size_t>(cleaned.skeleton.jointCount()));
  for (const Joint& joint : cleaned.skeleton.joints) parents.push_back(joint.parent);
  // The job's world positions (style::StylizeCleanupResult); a result made without them gets its own.
  const bool computed = result.cleaned_world_positions.rows() == cleaned.frameCount() &&
                        result.cleaned_world_positions.cols() == 3 * cleaned.skeleton.jointCount();
  const Eigen::MatrixXd own = computed ? Eigen::MatrixXd() : worldPositions(cleaned);
  const Eigen::MatrixXd& world = computed ? result.cleaned_world_positions : own;
  const BodySubtree body = bodySubtree(parents, mapping[CanonicalJoint::Hips]);
  FigureData figure =
      sameFrameRate(cleaned.fps(), display_fps)
          ? figureInDisplaySpace(name, FigureRole::Output, parents, body, world, content.display_space)
          : figureInDisplaySpace(name, FigureRole::Output, parents, body, rowsAtRate(world, cleaned.fps(), display_fps),
                                 content.display_space);
  setBodyContacts(figure, body, contactJoints(mapping), resampleRowsNearest(result.contacts, 1.0 / result.cleanup_fps, display_fps));
  return figure;
}

FigureData rawOutputFigure(const style::StylizeCleanupResult& result, const LoadedClip& content, const QString& name,
                           double display_fps) {
  mappingOf(content);
  const style::StylizedClip& raw = result.stylized;  // canonical joints, the content's file space
  const std::vector<int> parents(kCanonicalParent.begin(), kCanonicalParent.end());
  FigureData figure = figureFromPositions(
      name, FigureRole::RawOutput, parents,
      content.display_space.toDisplay(rowsAtRate(raw.world_positions, raw.fps, display_fps)));
  const Eigen::MatrixXi content_contacts = (raw.contacts.transpose().array() > 0.5).cast<int>().matrix();
  setFigureContacts(figure, canonicalContactJoints(), resampleRowsNearest(content_contacts, 1.0 / raw.fps, display_fps));
  return figure;
}

}  // namespace motionstyle
