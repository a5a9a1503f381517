#pragma once
// One figure's VTK pipeline in the viewport (INTERNAL header: VTK types; viewport_scene.cpp only):
// instanced joint spheres, instanced bone cylinders (parent -> joint), contact discs on the floor and
// the root's path. connectPipeline() wires it once; fill() sizes and colours it for a figure, so that a
// new figure with the same skeleton (every live edit's result) reuses the pipeline and its buffers.

#include <vtkActor.h>
#include <vtkCylinderSource.h>
#include <vtkDoubleArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkTransformPolyDataFilter.h>

#include <array>
#include <cmath>
#include <vector>

#include "viewport_scene.h"

namespace motionstyle::detail {

// Sizes relative to the character's height, so a 30 cm toy rig and a 2 m giant look alike.
inline constexpr double kJointRadiusPerHeight = 0.019;
inline constexpr double kBoneRadiusPerHeight = 0.012;
inline constexpr double kContactRadiusPerHeight = 0.045;
// Tessellation: fine, and coarse while results follow the hand (setCoarse). 8 x 6 spheres read as
// round at the reduced resolution and halve a software render's vertex work.
inline constexpr int kJointSphereSides = 14, kJointSphereRings = 10, kBoneSides = 14, kContactDiscSides = 32;
inline constexpr int kCoarseJointSphereSides = 8, kCoarseJointSphereRings = 6, kCoarseBoneSides = 8,
                     kCoarseContactDiscSides = 16;
// Small lifts above the floor so markers and paths never z-fight with it.
inline constexpr double kTrajectoryLiftCm = 0.4;
inline constexpr double kContactLiftCm = 0.2;

struct ViewportScene::FigureVisual {
  double height = 170.0;
  double lateral_extent = 40.0;  // max horizontal reach of any joint from the root, cm
  // Placement: drawn = R_y(yaw) (p - pivot) + lane, with pivot the first frame's root on the floor
  // plane (actor origin), yaw about the vertical (actor orientation) and lane where it starts.
  Vec3 pivot{};
  double yaw_degrees = 0.0;
  double yaw_cos = 1.0, yaw_sin = 0.0;  // of yaw_degrees, set by place(): drawn() runs per joint and frame
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
  vtkCylinderSource* bone_cylinder = nullptr;  // the scene's unit bone, behind the shared glyph filter
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

  // Once per visual: sources, data sets, mappers and actors wired together, materials set.
  void connectPipeline(vtkAlgorithm* bone_glyph);
  // For each figure shown: sizes, colours, glyph counts and the floor path (the pose: poseFigure).
  void fill(const FigureData& figure, double floor_height, bool trajectory_visible);
  // The glyphs' tessellation: fine, or coarse while results follow the user's hand. The bone cylinder
  // is the scene's, shared by its figures.
  void setCoarse(bool coarse);

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
    yaw_cos = std::cos(vtkMath::RadiansFromDegrees(yaw));
    yaw_sin = std::sin(vtkMath::RadiansFromDegrees(yaw));
    lane = start;
    for (vtkActor* actor : actors()) {
      actor->SetOrigin(pivot[0], pivot[1], pivot[2]);
      actor->SetOrientation(0.0, yaw_degrees, 0.0);
      actor->SetPosition(lane[0] - pivot[0], lane[1] - pivot[1], lane[2] - pivot[2]);
    }
  }
  Vec3 drawn(double x, double y, double z) const {
    const double dx = x - pivot[0];
    const double dz = z - pivot[2];
    // vtkProp3D's RotateY: x' = x cos a + z sin a, z' = -x sin a + z cos a.
    return {lane[0] + dx * yaw_cos + dz * yaw_sin, y, lane[2] - dx * yaw_sin + dz * yaw_cos};
  }
};

// A unit cylinder along +X (length 1, radius 1, open ends): the bone glyph.
vtkSmartPointer<vtkTransformPolyDataFilter> makeUnitBoneCylinder();

}  // namespace motionstyle::detail
