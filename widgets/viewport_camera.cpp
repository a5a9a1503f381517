#include "viewport_camera.h"

#include <vtkCamera.h>
#include <vtkMath.h>

#include <algorithm>
#include <cmath>

namespace motionstyle::detail {
namespace {

constexpr double kMaxElevationDegrees = 88.0;

// Elevation of the camera above the focal point's horizontal plane, degrees.
double elevationOf(vtkCamera* camera) {
  double position[3];
  double focal[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  const double dx = position[0] - focal[0];
  const double dy = position[1] - focal[1];
  const double dz = position[2] - focal[2];
  return vtkMath::DegreesFromRadians(std::atan2(dy, std::hypot(dx, dz)));
}

}  // namespace

void orbitCamera(vtkCamera* camera, double azimuth_degrees, double elevation_degrees) {
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->Azimuth(azimuth_degrees);
  const double current = elevationOf(camera);
  const double target = std::clamp(current + elevation_degrees, -kMaxElevationDegrees, kMaxElevationDegrees);
  camera->Elevation(target - current);
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->OrthogonalizeViewUp();
}

void panCamera(vtkCamera* camera, double dx_pixels, double dy_pixels, int viewport_height_pixels) {
  if (viewport_height_pixels <= 0) return;
  // World length of one pixel at the focal distance.
  const double half_angle = vtkMath::RadiansFromDegrees(camera->GetViewAngle() / 2.0);
  const double per_pixel = 2.0 * camera->GetDistance() * std::tan(half_angle) / viewport_height_pixels;

  double up[3];
  double forward[3];
  double right[3];
  camera->GetViewUp(up);
  camera->GetDirectionOfProjection(forward);
  vtkMath::Cross(forward, up, right);
  vtkMath::Normalize(right);
  vtkMath::Cross(right, forward, up);
  vtkMath::Normalize(up);
  // Dragging right moves the scene right, i.e. the camera left; dragging down moves it up.
  std::array<double, 3> delta{};
  for (int a = 0; a < 3; ++a)
    delta[static_cast<size_t>(a)] = per_pixel * (-dx_pixels * right[a] + dy_pixels * up[a]);
  translateCamera(camera, delta);
}

void dollyCamera(vtkCamera* camera, double factor, double min_distance, double max_distance) {
  if (factor <= 0.0) return;
  const double distance = camera->GetDistance();
  const double target = std::clamp(distance / factor, min_distance, max_distance);
  camera->Dolly(distance / target);
}

void translateCamera(vtkCamera* camera, const std::array<double, 3>& delta) {
  double position[3];
  double focal[3];
  camera->GetPosition(position);
  camera->GetFocalPoint(focal);
  camera->SetFocalPoint(focal[0] + delta[0], focal[1] + delta[1], focal[2] + delta[2]);
  camera->SetPosition(position[0] + delta[0], position[1] + delta[1], position[2] + delta[2]);
}

namespace {

// The distance at which a sphere of `radius` around the focal point fills the narrower field of view.
double fillingDistance(vtkCamera* camera, double radius, double aspect, double margin) {
  const double vertical = vtkMath::RadiansFromDegrees(camera->GetViewAngle()) / 2.0;
  const double horizontal = std::atan(std::tan(vertical) * std::max(aspect, 0.1));
  return margin * radius / std::sin(std::min(vertical, horizontal));
}

double boxRadius(const std::array<double, 6>& box) {
  return std::max(1.0, 0.5 * std::sqrt((box[1] - box[0]) * (box[1] - box[0]) + (box[3] - box[2]) * (box[3] - box[2]) +
                                       (box[5] - box[4]) * (box[5] - box[4])));
}

}  // namespace

void keepBoxInView(vtkCamera* camera, const std::array<double, 6>& box, double aspect) {
  double focal[3];
  camera->GetFocalPoint(focal);
  const double off_centre = std::sqrt(std::pow(0.5 * (box[0] + box[1]) - focal[0], 2) +
                                      std::pow(0.5 * (box[2] + box[3]) - focal[1], 2) +
                                      std::pow(0.5 * (box[4] + box[5]) - focal[2], 2));
  const double needed = fillingDistance(camera, boxRadius(box) + off_centre, aspect, 1.1);
  const double distance = camera->GetDistance();
  if (distance < needed) camera->Dolly(distance / needed);
}

void frameBox(vtkCamera* camera, const std::array<double, 6>& box, double azimuth_degrees,
              double elevation_degrees, double aspect) {
  const double centre[3] = {0.5 * (box[0] + box[1]), 0.5 * (box[2] + box[3]), 0.5 * (box[4] + box[5])};
  // The narrower of the vertical and horizontal fields of view decides the distance.
  const double distance = fillingDistance(camera, boxRadius(box), aspect, 1.3);

  const double azimuth = vtkMath::RadiansFromDegrees(azimuth_degrees);
  const double elevation = vtkMath::RadiansFromDegrees(elevation_degrees);
  camera->SetFocalPoint(centre[0], centre[1], centre[2]);
  camera->SetPosition(centre[0] + distance * std::cos(elevation) * std::sin(azimuth),
                      centre[1] + distance * std::sin(elevation),
                      centre[2] + distance * std::cos(elevation) * std::cos(azimuth));
  camera->SetViewUp(0.0, 1.0, 0.0);
  camera->OrthogonalizeViewUp();
}

}  // namespace motionstyle::detail
