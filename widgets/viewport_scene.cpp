#include "viewport_scene.h"

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkCylinderSource.h>
#include <vtkDoubleArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkLight.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>
#include <vtkTransform.h>
#include <vtkTransformPolyDataFilter.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "viewport_floor.h"

namespace motionstyle::detail {
namespace {

// Sizes relative to the character's height, so a 30 cm toy rig and a 2 m giant look alike.
constexpr double kJointRadiusPerHeight = 0.019;
constexpr double kBoneRadiusPerHeight = 0.012;
constexpr double kContactRadiusPerHeight = 0.045;
// Small lifts above the floor so markers and paths never z-fight with it.
constexpr double kTrajectoryLiftCm = 0.4;
constexpr double kContactLiftCm = 0.2;

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

// A tile edge that reads well: 1, 2 or 5 times a power of ten centimetres.
double niceLength(double approximate) {
  const double decade = std::pow(10.0, std::floor(std::log10(std::max(approximate, 1e-3))));
  for (const double step : {1.0, 2.0, 5.0, 10.0}) {
    if (step * decade >= approximate * 0.75) return step * decade;
  }
  return 10.0 * decade;
}


}  // namespace

struct ViewportScene::FigureVisual {
  double height = 170.0;
  double lateral_extent = 40.0;  // max horizontal reach of any joint from the root, cm
  // Placement: drawn = R_y(yaw) (p - pivot) + lane, with pivot the first frame's root on the floor
  // plane (actor origin), yaw about the vertical (actor orientation) and lane where it starts.
  Vec3 pivot{};
  double yaw_degrees = 0.0;
  Vec3 lane{};
  std::vector<int> bone_joints;  // joints with a parent: one bone each, parent -> joint

  vtkNew<vtkSphereSource> joint_sphere;
  vtkNew<vtkPoints> joint_points;
  vtkNew<vtkPolyData> joints;
  vtkNew<vtkGlyph3DMapper> joint_mapper;
  vtkNew<vtkActor> joint_actor;

  vtkNew<vtkPoints> bone_points;  // bone midpoints
  vtkNew<vtkDoubleArray> bone_directions;
  vtkNew<vtkDoubleArray> bone_scales;  // (length, radius, radius) of the unit X-axis cylinder
  vtkNew<vtkPolyData> bones;
  vtkNew<vtkGlyph3DMapper> bone_mapper;
  vtkNew<vtkActor> bone_actor;

  vtkNew<vtkCylinderSource> contact_disc;
  vtkNew<vtkPoints> contact_points;
  vtkNew<vtkDoubleArray> contact_scales;  // 1 in contact, 0 hides the disc
  vtkNew<vtkPolyData> contacts;
  vtkNew<vtkGlyph3DMapper> contact_mapper;
  vtkNew<vtkActor> contact_actor;

  vtkNew<vtkPolyData> trajectory;
  vtkNew<vtkPolyDataMapper> trajectory_mapper;
  vtkNew<vtkActor> trajectory_actor;

  void addTo(vtkRenderer* renderer) const {
    for (vtkActor* actor : actors()) renderer->AddActor(actor);
  }
  void removeFrom(vtkRenderer* renderer) const {
    for (vtkActor* actor : actors()) renderer->RemoveActor(actor);
  }
  std::array<vtkActor*, 4> actors() const {
    return {joint_actor.Get(), bone_actor.Get(), contact_actor.Get(), trajectory_actor.Get()};
  }
  void place(const Vec3& first_root, double yaw, const Vec3& start) {
    pivot = first_root;
    yaw_degrees = yaw;
    lane = start;
    for (vtkActor* actor : actors()) {
      actor->SetOrigin(pivot[0], pivot[1], pivot[2]);
      actor->SetOrientation(0.0, yaw_degrees, 0.0);
      actor->SetPosition(lane[0] - pivot[0], lane[1] - pivot[1], lane[2] - pivot[2]);
    }
  }
  Vec3 drawn(double x, double y, double z) const {
    const double a = vtkMath::RadiansFromDegrees(yaw_degrees);
    const double dx = x - pivot[0];
    const double dz = z - pivot[2];
    // vtkProp3D's RotateY: x' = x cos a + z sin a, z' = -x sin a + z cos a.
    return {lane[0] + dx * std::cos(a) + dz * std::sin(a), y, lane[2] - dx * std::sin(a) + dz * std::cos(a)};
  }
};

struct ViewportScene::Floor {
  vtkNew<vtkPolyData> mesh;
  vtkNew<vtkPolyDataMapper> mapper;
  vtkNew<vtkActor> actor;
};

namespace {

vtkSmartPointer<vtkTransformPolyDataFilter> makeUnitBoneCylinder() {
  // vtkCylinderSource is centred on the origin along Y; the glyph mapper's DIRECTION mode turns the
  // glyph's X axis onto the bone, so rotate the cylinder to lie along X with unit length and radius.
  vtkNew<vtkCylinderSource> cylinder;
  cylinder->SetHeight(1.0);
  cylinder->SetRadius(1.0);
  cylinder->SetResolution(14);
  cylinder->CappingOff();  // the joint spheres (wider than bones) cover the ends
  vtkNew<vtkTransform> to_x_axis;
  to_x_axis->RotateZ(-90.0);
  auto filter = vtkSmartPointer<vtkTransformPolyDataFilter>::New();
  filter->SetInputConnection(cylinder->GetOutputPort());
  filter->SetTransform(to_x_axis);
  return filter;
}

}  // namespace

ViewportScene::ViewportScene() : renderer_(vtkSmartPointer<vtkRenderer>::New()), floor_(std::make_unique<Floor>()) {
  // Studio look: a cool gradient backdrop and two lights that follow the camera: a warm key from the
  // upper right and a cool, soft headlight fill. (A full light kit costs twice the per-pixel lighting,
  // which matters under software GL, and reads no better on bones.)
  renderer_->GradientBackgroundOn();
  renderer_->SetBackground(kBackdropBottom[0], kBackdropBottom[1], kBackdropBottom[2]);
  renderer_->SetBackground2(kBackdropTop[0], kBackdropTop[1], kBackdropTop[2]);
  renderer_->UseFXAAOn();
  renderer_->RemoveAllLights();
  vtkNew<vtkLight> key;
  key->SetLightTypeToCameraLight();
  key->SetPosition(0.9, 1.1, 1.0);  // camera space: right, up, towards the viewer
  key->SetFocalPoint(0.0, 0.0, 0.0);
  key->SetColor(1.0, 0.97, 0.92);
  key->SetIntensity(0.85);
  renderer_->AddLight(key);
  vtkNew<vtkLight> fill;
  fill->SetLightTypeToHeadlight();
  fill->SetColor(0.85, 0.9, 1.0);
  fill->SetIntensity(0.35);
  renderer_->AddLight(fill);

  floor_->mapper->SetInputData(floor_->mesh);
  floor_->mapper->SetScalarModeToUsePointData();
  floor_->mapper->SetColorModeToDirectScalars();
  floor_->actor->SetMapper(floor_->mapper);
  // The floor's shading is baked into its colours: unlit, it costs the least per pixel.
  floor_->actor->GetProperty()->LightingOff();
  floor_->actor->PickableOff();
  renderer_->AddActor(floor_->actor);
  buildFloor();
}

ViewportScene::~ViewportScene() = default;

vtkRenderer* ViewportScene::renderer() const { return renderer_; }

int ViewportScene::frameCount() const {
  int frames = 0;
  for (const FigureData& figure : figures_) frames = std::max(frames, figure.frame_count);
  return frames;
}

void ViewportScene::setFigures(std::vector<FigureData> figures) {
  for (const auto& visual : visuals_) visual->removeFrom(renderer_);
  visuals_.clear();
  figures_ = std::move(figures);
  frame_ = 0;

  floor_height_ = 0.0;
  for (const FigureData& figure : figures_) {
    for (int f = 0; f < figure.frame_count; ++f)
      for (int j = 0; j < figure.jointCount(); ++j) floor_height_ = std::min(floor_height_, figure.y(f, j));
  }

  const auto bone_cylinder = makeUnitBoneCylinder();
  for (const FigureData& figure : figures_) {
    auto visual = std::make_unique<FigureVisual>();
    FigureVisual& v = *visual;
    double lateral = 0.0;
    double tallest = 1.0;
    for (int f = 0; f < figure.frame_count; ++f) {
      double low = std::numeric_limits<double>::max();
      double high = std::numeric_limits<double>::lowest();
      for (int j = 0; j < figure.jointCount(); ++j) {
        low = std::min(low, figure.y(f, j));
        high = std::max(high, figure.y(f, j));
        lateral = std::max(lateral, std::hypot(figure.x(f, j) - figure.x(f, 0), figure.z(f, j) - figure.z(f, 0)));
      }
      tallest = std::max(tallest, high - low);
    }
    v.height = tallest;
    v.lateral_extent = lateral;
    const QColor color = figureColor(figure.role);

    v.joint_sphere->SetRadius(kJointRadiusPerHeight * v.height);
    v.joint_sphere->SetThetaResolution(14);
    v.joint_sphere->SetPhiResolution(10);
    v.joint_points->SetNumberOfPoints(figure.jointCount());
    v.joints->SetPoints(v.joint_points);
    v.joint_mapper->SetInputData(v.joints);
    v.joint_mapper->SetSourceConnection(v.joint_sphere->GetOutputPort());
    v.joint_mapper->ScalingOff();
    v.joint_mapper->OrientOff();
    v.joint_actor->SetMapper(v.joint_mapper);
    applySatinMaterial(v.joint_actor->GetProperty());
    setColor(v.joint_actor->GetProperty(), color, 0.82);

    for (int j = 0; j < figure.jointCount(); ++j)
      if (figure.parents[static_cast<size_t>(j)] >= 0) v.bone_joints.push_back(j);
    const auto bones = static_cast<vtkIdType>(v.bone_joints.size());
    v.bone_points->SetNumberOfPoints(bones);
    v.bone_directions->SetName("direction");
    v.bone_directions->SetNumberOfComponents(3);
    v.bone_directions->SetNumberOfTuples(bones);
    v.bone_scales->SetName("scale");
    v.bone_scales->SetNumberOfComponents(3);
    v.bone_scales->SetNumberOfTuples(bones);
    v.bones->SetPoints(v.bone_points);
    v.bones->GetPointData()->AddArray(v.bone_directions);
    v.bones->GetPointData()->AddArray(v.bone_scales);
    v.bone_mapper->SetInputData(v.bones);
    v.bone_mapper->SetSourceConnection(bone_cylinder->GetOutputPort());
    v.bone_mapper->SetOrientationArray("direction");
    v.bone_mapper->SetOrientationModeToDirection();
    v.bone_mapper->SetScaleArray("scale");
    v.bone_mapper->SetScaleModeToScaleByVectorComponents();
    v.bone_mapper->ScalingOn();
    v.bone_actor->SetMapper(v.bone_mapper);
    applySatinMaterial(v.bone_actor->GetProperty());
    setColor(v.bone_actor->GetProperty(), color);

    const auto contact_count = static_cast<vtkIdType>(figure.contact_joints.size());
    v.contact_disc->SetRadius(kContactRadiusPerHeight * v.height);
    v.contact_disc->SetHeight(0.4);
    v.contact_disc->SetResolution(32);
    v.contact_points->SetNumberOfPoints(contact_count);
    v.contact_scales->SetName("contact");
    v.contact_scales->SetNumberOfTuples(contact_count);
    v.contacts->SetPoints(v.contact_points);
    v.contacts->GetPointData()->AddArray(v.contact_scales);
    v.contact_mapper->SetInputData(v.contacts);
    v.contact_mapper->SetSourceConnection(v.contact_disc->GetOutputPort());
    v.contact_mapper->SetScaleArray("contact");
    v.contact_mapper->SetScaleModeToScaleByMagnitude();
    v.contact_mapper->ScalingOn();
    v.contact_mapper->OrientOff();
    v.contact_actor->SetMapper(v.contact_mapper);
    v.contact_actor->GetProperty()->SetAmbient(0.6);
    v.contact_actor->GetProperty()->SetDiffuse(0.5);
    setColor(v.contact_actor->GetProperty(), mixWithWhite(color, 0.45));

    // The root's path on the floor: static for the clip, built once.
    vtkNew<vtkPoints> path;
    vtkNew<vtkCellArray> line;
    line->InsertNextCell(figure.frame_count);
    for (int f = 0; f < figure.frame_count; ++f) {
      path->InsertNextPoint(figure.x(f, 0), floor_height_ + kTrajectoryLiftCm, figure.z(f, 0));
      line->InsertCellPoint(f);
    }
    v.trajectory->SetPoints(path);
    v.trajectory->SetLines(line);
    v.trajectory_mapper->SetInputData(v.trajectory);
    v.trajectory_actor->SetMapper(v.trajectory_mapper);
    v.trajectory_actor->GetProperty()->SetLineWidth(2.0f);
    v.trajectory_actor->GetProperty()->LightingOff();
    setColor(v.trajectory_actor->GetProperty(), mixWithWhite(color, 0.25));
    v.trajectory_actor->SetVisibility(trajectories_visible_);

    visual->addTo(renderer_);
    visuals_.push_back(std::move(visual));
  }
  placeFigures();
  setFrame(0);
}

void ViewportScene::setLayout(SceneLayout layout) {
  if (layout == layout_) return;
  layout_ = layout;
  placeFigures();
}

void ViewportScene::setAntialiasing(bool on) { renderer_->SetUseFXAA(on); }
bool ViewportScene::antialiasing() const { return renderer_->GetUseFXAA(); }

void ViewportScene::setTrajectoriesVisible(bool visible) {
  trajectories_visible_ = visible;
  for (const auto& visual : visuals_) visual->trajectory_actor->SetVisibility(visible);
}

namespace {

// The root's travel on the floor plane from the first to the last frame, and whether it is a walk
// (more than half a character height) rather than motion on the spot.
struct Travel {
  double x = 0.0, z = 0.0;
  bool walks = false;
};

Travel travelOf(const FigureData& figure, double height) {
  const int last = figure.frame_count - 1;
  Travel travel{figure.x(last, 0) - figure.x(0, 0), figure.z(last, 0) - figure.z(0, 0), false};
  travel.walks = std::hypot(travel.x, travel.z) > 0.5 * height;
  return travel;
}

double headingDegrees(const Travel& travel) { return vtkMath::DegreesFromRadians(std::atan2(travel.x, travel.z)); }

}  // namespace

void ViewportScene::placeFigures() {
  // Side by side: every figure walks in its own lane along the content's (the first figure's) direction
  // of travel, turned about its first root position, so that clips recorded facing other ways do not
  // drift apart; lanes are spaced by the widest reach plus a gap, across that direction, centred on the
  // origin. Overlay: every clip starts on the origin as recorded.
  double spacing = 0.0;
  for (const auto& visual : visuals_)
    spacing = std::max(spacing, 2.0 * visual->lateral_extent + 0.35 * visual->height);
  spacing = std::max(spacing, 0.6 * characterHeight());
  const double count = static_cast<double>(visuals_.size());
  const Travel lead = figures_.empty() ? Travel{} : travelOf(figures_.front(), visuals_.front()->height);
  // Across the lead's travel (+X when it walks along +Z, as the old layout), else along X.
  const double length = std::hypot(lead.x, lead.z);
  const double across_x = lead.walks ? lead.z / length : 1.0;
  const double across_z = lead.walks ? -lead.x / length : 0.0;
  for (size_t i = 0; i < visuals_.size(); ++i) {
    const FigureData& figure = figures_[i];
    const bool side_by_side = layout_ == SceneLayout::SideBySide;
    const double sideways = side_by_side ? (static_cast<double>(i) - (count - 1.0) / 2.0) * spacing : 0.0;
    const Travel own = travelOf(figure, visuals_[i]->height);
    const double yaw = side_by_side && lead.walks && own.walks ? headingDegrees(lead) - headingDegrees(own) : 0.0;
    visuals_[i]->place({figure.x(0, 0), 0.0, figure.z(0, 0)}, yaw, {sideways * across_x, 0.0, sideways * across_z});
  }
  buildFloor();
}

void ViewportScene::setFrame(int frame) {
  frame_ = std::max(0, frame);
  for (size_t i = 0; i < visuals_.size(); ++i) poseFigure(i);
}

void ViewportScene::poseFigure(size_t index) {
  const FigureData& figure = figures_[index];
  FigureVisual& v = *visuals_[index];
  const int f = std::min(frame_, figure.frame_count - 1);
  const double bone_radius = kBoneRadiusPerHeight * v.height;

  for (int j = 0; j < figure.jointCount(); ++j) v.joint_points->SetPoint(j, figure.x(f, j), figure.y(f, j), figure.z(f, j));
  v.joint_points->Modified();

  for (size_t b = 0; b < v.bone_joints.size(); ++b) {
    const int joint = v.bone_joints[b];
    const int parent = figure.parents[static_cast<size_t>(joint)];
    const double child_pos[3] = {figure.x(f, joint), figure.y(f, joint), figure.z(f, joint)};
    const double parent_pos[3] = {figure.x(f, parent), figure.y(f, parent), figure.z(f, parent)};
    double direction[3] = {child_pos[0] - parent_pos[0], child_pos[1] - parent_pos[1], child_pos[2] - parent_pos[2]};
    const double length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
    if (length < 1e-9) {
      // A zero-length bone (CMU rigs have some): keep a valid direction, draw nothing.
      direction[0] = 1.0;
      direction[1] = direction[2] = 0.0;
    }
    const auto id = static_cast<vtkIdType>(b);
    v.bone_points->SetPoint(id, 0.5 * (child_pos[0] + parent_pos[0]), 0.5 * (child_pos[1] + parent_pos[1]),
                            0.5 * (child_pos[2] + parent_pos[2]));
    v.bone_directions->SetTuple(id, direction);
    const double scale[3] = {length, length < 1e-9 ? 0.0 : bone_radius, length < 1e-9 ? 0.0 : bone_radius};
    v.bone_scales->SetTuple(id, scale);
  }
  v.bone_points->Modified();
  v.bone_directions->Modified();
  v.bone_scales->Modified();

  for (size_t k = 0; k < figure.contact_joints.size(); ++k) {
    const int joint = figure.contact_joints[k];
    const auto id = static_cast<vtkIdType>(k);
    v.contact_points->SetPoint(id, figure.x(f, joint), floor_height_ + kContactLiftCm, figure.z(f, joint));
    v.contact_scales->SetValue(id, figure.inContact(f, static_cast<int>(k)) ? 1.0 : 0.0);
  }
  v.contact_points->Modified();
  v.contact_scales->Modified();

  v.joints->Modified();
  v.bones->Modified();
  v.contacts->Modified();
}

Vec3 ViewportScene::drawnJoint(int figure, int joint, int frame) const {
  const FigureData& data = figures_[static_cast<size_t>(figure)];
  const int f = std::clamp(frame, 0, data.frame_count - 1);
  return visuals_[static_cast<size_t>(figure)]->drawn(data.x(f, joint), data.y(f, joint), data.z(f, joint));
}

Vec3 ViewportScene::anchor(int frame) const {
  Vec3 sum{};
  for (size_t i = 0; i < figures_.size(); ++i) {
    const Vec3 root = drawnJoint(static_cast<int>(i), 0, frame);
    for (int a = 0; a < 3; ++a) sum[static_cast<size_t>(a)] += root[static_cast<size_t>(a)];
  }
  const double count = std::max<double>(1.0, static_cast<double>(figures_.size()));
  return {sum[0] / count, sum[1] / count, sum[2] / count};
}

std::array<double, 6> ViewportScene::bounds(int frame) const {
  if (figures_.empty()) return {-100.0, 100.0, 0.0, 200.0, -100.0, 100.0};
  std::array<double, 6> box{};
  for (size_t a = 0; a < 3; ++a) {
    box[2 * a] = std::numeric_limits<double>::max();
    box[2 * a + 1] = std::numeric_limits<double>::lowest();
  }
  for (size_t i = 0; i < figures_.size(); ++i) {
    const int first = frame < 0 ? 0 : frame;
    const int last = frame < 0 ? figures_[i].frame_count - 1 : frame;
    for (int f = first; f <= last; ++f) {
      for (int j = 0; j < figures_[i].jointCount(); ++j) {
        const Vec3 p = drawnJoint(static_cast<int>(i), j, f);
        for (size_t a = 0; a < 3; ++a) {
          box[2 * a] = std::min(box[2 * a], p[a]);
          box[2 * a + 1] = std::max(box[2 * a + 1], p[a]);
        }
      }
    }
  }
  return box;
}

double ViewportScene::characterHeight() const {
  double height = 0.0;
  for (const auto& visual : visuals_) height = std::max(height, visual->height);
  return height > 0.0 ? height : 170.0;
}

void ViewportScene::buildFloor() {
  // Covers every figure's whole path plus a margin; tiles snap to a world grid so the checker does
  // not swim when it is rebuilt.
  const double height = characterHeight();
  const auto box = bounds(-1);
  const double tile = niceLength(height / 3.4);
  const double centre_x = std::round(0.5 * (box[0] + box[1]) / tile) * tile;
  const double centre_z = std::round(0.5 * (box[4] + box[5]) / tile) * tile;
  const double reach = std::max({0.5 * (box[1] - box[0]), 0.5 * (box[5] - box[4]), 0.0});
  const int half_tiles = std::clamp(static_cast<int>(std::ceil((reach + 3.0 * height) / tile)), 4, 60);
  fillFloorMesh(floor_->mesh, {centre_x, floor_height_, centre_z}, tile, half_tiles);
}

}  // namespace motionstyle::detail
