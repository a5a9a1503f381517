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
  FigureData figure = figureFromPositions(
      name, FigureRole::Output, parents,
      rowsAtRate(content.display_space.toDisplay(worldPositions(cleaned)), cleaned.fps(), display_fps));
  setFigureContacts(figure, contactJoints(mapping),
                    resampleRowsNearest(result.contacts, 1.0 / result.cleanup_fps, display_fps));
  return keepBodySubtree(figure, mapping[CanonicalJoint::Hips]);
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
