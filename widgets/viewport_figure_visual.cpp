#include "viewport_figure_visual.h"

#include <vtkCellArray.h>
#include <vtkPointData.h>
#include <vtkProperty.h>
#include <vtkTransform.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace motionstyle::detail {
namespace {

std::array<double, 3> rgbOf(const QColor& color) {
  return {static_cast<double>(color.redF()), static_cast<double>(color.greenF()), static_cast<double>(color.blueF())};
}

void setColor(vtkProperty* property, const QColor& color, double scale = 1.0) {
  const auto rgb = rgbOf(color);
  property->SetColor(std::min(1.0, rgb[0] * scale), std::min(1.0, rgb[1] * scale), std::min(1.0, rgb[2] * scale));
}

void applySatinMaterial(vtkProperty* property) {
  property->SetInterpolationToPhong();
  property->SetAmbient(0.22);
  property->SetDiffuse(0.80);
  property->SetSpecular(0.28);
  property->SetSpecularPower(28.0);
  property->SetSpecularColor(1.0, 1.0, 1.0);
}

QColor mixWithWhite(const QColor& color, double amount) {
  const auto rgb = rgbOf(color);
  return QColor::fromRgbF(static_cast<float>(rgb[0] + (1.0 - rgb[0]) * amount),
                          static_cast<float>(rgb[1] + (1.0 - rgb[1]) * amount),
                          static_cast<float>(rgb[2] + (1.0 - rgb[2]) * amount));
}

// A new result for the same figure changes its height by a little: a glyph source keeps its radius
// then (within 2 %), so the glyph mappers do not rebuild their buffers at every live edit.
template <typename Source>
void setRadiusUnlessClose(Source& source, double radius) {
  if (std::abs(source->GetRadius() - radius) > 0.02 * radius) source->SetRadius(radius);
}

}  // namespace

vtkSmartPointer<vtkTransformPolyDataFilter> makeUnitBoneCylinder() {
  // vtkCylinderSource is centred on the origin along Y; the glyph mapper's DIRECTION mode turns the
  // glyph's X axis onto the bone, so rotate the cylinder to lie along X with unit length and radius.
  vtkNew<vtkCylinderSource> cylinder;
  cylinder->SetHeight(1.0);
  cylinder->SetRadius(1.0);
  cylinder->SetResolution(kBoneSides);
  cylinder->CappingOff();  // the joint spheres (wider than bones) cover the ends
  vtkNew<vtkTransform> to_x_axis;
  to_x_axis->RotateZ(-90.0);
  auto filter = vtkSmartPointer<vtkTransformPolyDataFilter>::New();
  filter->SetInputConnection(cylinder->GetOutputPort());
  filter->SetTransform(to_x_axis);
  return filter;
}

void ViewportScene::FigureVisual::connectPipeline(vtkAlgorithm* bone_glyph) {
  joints->SetPoints(joint_points);
  joint_mapper->SetInputData(joints);
  joint_mapper->SetSourceConnection(joint_sphere->GetOutputPort());
  joint_mapper->ScalingOff();
  joint_mapper->OrientOff();
  joint_actor->SetMapper(joint_mapper);
  applySatinMaterial(joint_actor->GetProperty());

  bone_directions->SetName("direction");
  bone_directions->SetNumberOfComponents(3);
  bone_scales->SetName("scale");
  bone_scales->SetNumberOfComponents(3);
  bones->SetPoints(bone_points);
  bones->GetPointData()->AddArray(bone_directions);
  bones->GetPointData()->AddArray(bone_scales);
  bone_mapper->SetInputData(bones);
  bone_mapper->SetSourceConnection(bone_glyph->GetOutputPort());
  bone_cylinder = vtkCylinderSource::SafeDownCast(bone_glyph->GetInputAlgorithm());
  bone_mapper->SetOrientationArray("direction");
  bone_mapper->SetOrientationModeToDirection();
  bone_mapper->SetScaleArray("scale");
  bone_mapper->SetScaleModeToScaleByVectorComponents();
  bone_mapper->ScalingOn();
  bone_actor->SetMapper(bone_mapper);
  applySatinMaterial(bone_actor->GetProperty());

  contact_disc->SetHeight(0.4);
  contact_scales->SetName("contact");
  contacts->SetPoints(contact_points);
  contacts->GetPointData()->AddArray(contact_scales);
  contact_mapper->SetInputData(contacts);
  contact_mapper->SetSourceConnection(contact_disc->GetOutputPort());
  contact_mapper->SetScaleArray("contact");
  contact_mapper->SetScaleModeToScaleByMagnitude();
  contact_mapper->ScalingOn();
  contact_mapper->OrientOff();
  contact_actor->SetMapper(contact_mapper);
  contact_actor->GetProperty()->SetAmbient(0.6);
  contact_actor->GetProperty()->SetDiffuse(0.5);

  trajectory_mapper->SetInputData(trajectory);
  trajectory_actor->SetMapper(trajectory_mapper);
  trajectory_actor->GetProperty()->SetLineWidth(2.0f);
  trajectory_actor->GetProperty()->LightingOff();
}

void ViewportScene::FigureVisual::fill(const FigureData& figure, double floor_height, bool trajectory_visible) {
  // One pass over the clip's positions (every result of a live edit comes through here).
  double lateral_squared = 0.0;
  double tallest = 1.0;
  const size_t joint_count = static_cast<size_t>(figure.jointCount());
  for (size_t frame = 0; frame < static_cast<size_t>(figure.frame_count); ++frame) {
    const double* p = figure.positions.data() + frame * joint_count * 3;
    double low = std::numeric_limits<double>::max();
    double high = std::numeric_limits<double>::lowest();
    for (size_t j = 0; j < joint_count; ++j) {
      const double dx = p[3 * j] - p[0], y = p[3 * j + 1], dz = p[3 * j + 2] - p[2];
      low = std::min(low, y);
      high = std::max(high, y);
      lateral_squared = std::max(lateral_squared, dx * dx + dz * dz);
    }
    tallest = std::max(tallest, high - low);
  }
  height = tallest;
  lateral_extent = std::sqrt(lateral_squared);
  const QColor color = figureColor(figure.role);

  setRadiusUnlessClose(joint_sphere, kJointRadiusPerHeight * height);
  joint_points->SetNumberOfPoints(figure.jointCount());
  setColor(joint_actor->GetProperty(), color, 0.82);

  bone_joints.clear();
  for (int j = 0; j < figure.jointCount(); ++j)
    if (figure.parents[static_cast<size_t>(j)] >= 0) bone_joints.push_back(j);
  const auto bone_count = static_cast<vtkIdType>(bone_joints.size());
  bone_points->SetNumberOfPoints(bone_count);
  bone_directions->SetNumberOfTuples(bone_count);
  bone_scales->SetNumberOfTuples(bone_count);
  setColor(bone_actor->GetProperty(), color);

  const auto contact_count = static_cast<vtkIdType>(figure.contact_joints.size());
  setRadiusUnlessClose(contact_disc, kContactRadiusPerHeight * height);
  contact_points->SetNumberOfPoints(contact_count);
  contact_scales->SetNumberOfTuples(contact_count);
  setColor(contact_actor->GetProperty(), mixWithWhite(color, 0.45));

  // The root's path on the floor: static for the clip, built once per figure.
  vtkNew<vtkPoints> path;
  vtkNew<vtkCellArray> line;
  line->InsertNextCell(figure.frame_count);
  for (int f = 0; f < figure.frame_count; ++f) {
    path->InsertNextPoint(figure.x(f, 0), floor_height + kTrajectoryLiftCm, figure.z(f, 0));
    line->InsertCellPoint(f);
  }
  trajectory->SetPoints(path);
  trajectory->SetLines(line);
  setColor(trajectory_actor->GetProperty(), mixWithWhite(color, 0.25));
  trajectory_actor->SetVisibility(trajectory_visible);
}

void ViewportScene::FigureVisual::setCoarse(bool coarse) {
  // vtkSetMacro: an unchanged value does not re-run the source or rebuild the glyph buffers.
  joint_sphere->SetThetaResolution(coarse ? kCoarseJointSphereSides : kJointSphereSides);
  joint_sphere->SetPhiResolution(coarse ? kCoarseJointSphereRings : kJointSphereRings);
  contact_disc->SetResolution(coarse ? kCoarseContactDiscSides : kContactDiscSides);
  if (bone_cylinder) bone_cylinder->SetResolution(coarse ? kCoarseBoneSides : kBoneSides);
}

}  // namespace motionstyle::detail
