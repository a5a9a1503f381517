#include "viewport_scene.h"

#include <vtkActor.h>
#include <vtkLight.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkTransformPolyDataFilter.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "viewport_figure_visual.h"
#include "viewport_floor.h"

namespace motionstyle::detail {
namespace {

// A tile edge that reads well: 1, 2 or 5 times a power of ten centimetres.
double niceLength(double approximate) {
  const double decade = std::pow(10.0, std::floor(std::log10(std::max(approximate, 1e-3))));
  for (const double step : {1.0, 2.0, 5.0, 10.0}) {
    if (step * decade >= approximate * 0.75) return step * decade;
  }
  return 10.0 * decade;
}

}  // namespace

struct ViewportScene::Floor {
  vtkNew<vtkPolyData> mesh;
  vtkNew<vtkPolyDataMapper> mapper;
  vtkNew<vtkActor> actor;
  // What the mesh was filled for (centre x, height, centre z, tile, half tiles), once it was: an
  // unchanged floor is not refilled, so its buffers are not rebuilt at every live result.
  std::optional<std::array<double, 5>> filled_for;
};

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


namespace {

// Same joints, hierarchy and contact joints: a figure's VTK pipeline can be refilled for the other.
bool sameSkeleton(const FigureData& a, const FigureData& b) {
  return a.parents == b.parents && a.contact_joints == b.contact_joints;
}

}  // namespace

void ViewportScene::setFigures(std::vector<FigureData> figures) {
  // A figure whose skeleton is unchanged (a new result for the same clip: every live edit) keeps its
  // VTK pipeline and buffers and is only refilled; the others are built anew.
  std::vector<std::unique_ptr<FigureVisual>> previous = std::move(visuals_);
  const std::vector<FigureData> previous_figures = std::move(figures_);
  visuals_.clear();
  figures_ = std::move(figures);
  frame_ = 0;

  floor_height_ = 0.0;
  for (const FigureData& figure : figures_)  // every joint's height, every frame: the y of each triple
    for (size_t i = 1; i < figure.positions.size(); i += 3) floor_height_ = std::min(floor_height_, figure.positions[i]);

  vtkSmartPointer<vtkTransformPolyDataFilter> bone_cylinder;
  for (size_t i = 0; i < figures_.size(); ++i) {
    std::unique_ptr<FigureVisual> visual;
    if (i < previous.size() && previous[i] && sameSkeleton(previous_figures[i], figures_[i])) {
      visual = std::move(previous[i]);
    } else {
      if (!bone_cylinder) bone_cylinder = makeUnitBoneCylinder();
      visual = std::make_unique<FigureVisual>();
      visual->connectPipeline(bone_cylinder);
      visual->addTo(renderer_);
    }
    visual->fill(figures_[i], floor_height_, trajectories_visible_);
    visual->setCoarse(coarse_glyphs_);
    visuals_.push_back(std::move(visual));
  }
  for (const auto& visual : previous)
    if (visual) visual->removeFrom(renderer_);
  placeFigures();
  setFrame(0);
}

void ViewportScene::setLayout(SceneLayout layout) {
  if (layout == layout_) return;
  layout_ = layout;
  placeFigures();
}

void ViewportScene::setCoarseGlyphs(bool coarse) {
  coarse_glyphs_ = coarse;
  for (const auto& visual : visuals_) visual->setCoarse(coarse);
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
    const FigureData& figure = figures_[i];
    const FigureVisual& visual = *visuals_[i];
    const int first = frame < 0 ? 0 : std::clamp(frame, 0, figure.frame_count - 1);
    const int last = frame < 0 ? figure.frame_count - 1 : first;
    const size_t begin = static_cast<size_t>(first) * static_cast<size_t>(figure.jointCount()) * 3;
    const size_t end = static_cast<size_t>(last + 1) * static_cast<size_t>(figure.jointCount()) * 3;
    for (size_t k = begin; k < end; k += 3) {  // a whole clip's joints at every result: no per-joint lookup
      const Vec3 p = visual.drawn(figure.positions[k], figure.positions[k + 1], figure.positions[k + 2]);
      for (size_t a = 0; a < 3; ++a) {
        box[2 * a] = std::min(box[2 * a], p[a]);
        box[2 * a + 1] = std::max(box[2 * a + 1], p[a]);
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
  const std::array<double, 5> wanted = {centre_x, floor_height_, centre_z, tile, static_cast<double>(half_tiles)};
  if (floor_->filled_for != wanted) {
    fillFloorMesh(floor_->mesh, {centre_x, floor_height_, centre_z}, tile, half_tiles);
    floor_->filled_for = wanted;
  }
  // Everything drawn lies in the floor's square and the figures' whole-clip box grown by a joint's
  // radius (and above the floor by a character's height when there are no figures).
  std::array<double, 6> drawn{};
  floor_->mesh->GetBounds(drawn.data());
  const double margin = 0.1 * height;
  for (size_t a = 0; a < 3; ++a) {
    drawn[2 * a] = std::min(drawn[2 * a], box[2 * a] - margin);
    drawn[2 * a + 1] = std::max(drawn[2 * a + 1], box[2 * a + 1] + margin);
  }
  drawn_bounds_ = drawn;
}

}  // namespace motionstyle::detail
