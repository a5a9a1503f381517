#pragma once
// Camera moves for the viewport (INTERNAL header, VTK types). There is no QVTKInteractor here (VTK's
// Qt module is Qt5-only on Debian 12), so the widget turns Qt mouse/wheel deltas into these calls.
//
// Conventions: world Y is up and stays up (turntable orbit, like Maya/Blender); angles in DEGREES;
// screen deltas in device PIXELS, x to the right, y DOWN (Qt's convention); lengths in cm.

#include <array>

class vtkCamera;

namespace motionstyle::detail {

// Turns the camera about the focal point: azimuth about world Y, then elevation, which is clamped so
// the view never passes over a pole (|elevation| <= 88 degrees).
void orbitCamera(vtkCamera* camera, double azimuth_degrees, double elevation_degrees);

// Slides camera and focal point in the view plane so the point under the cursor follows the cursor.
void panCamera(vtkCamera* camera, double dx_pixels, double dy_pixels, int viewport_height_pixels);

// Moves towards (factor > 1) or away from (factor < 1) the focal point, keeping the distance within
// [min_distance, max_distance] cm.
void dollyCamera(vtkCamera* camera, double factor, double min_distance, double max_distance);

// Moves camera and focal point together by `delta` (cm, world).
void translateCamera(vtkCamera* camera, const std::array<double, 3>& delta);

// Looks at the box {xmin, xmax, ymin, ymax, zmin, zmax} from the front (+Z) turned by `azimuth`
// degrees about Y and raised by `elevation` degrees, at the distance where the box's bounding sphere
// fills the view for this aspect ratio (width / height).
void frameBox(vtkCamera* camera, const std::array<double, 6>& box, double azimuth_degrees,
              double elevation_degrees, double aspect);

// Backs the camera away from its focal point (never closer) until the box's bounding sphere, widened by
// its centre's distance from the focal point, fits the view: what the follow camera does when the
// figures spread further than the view shows.
void keepBoxInView(vtkCamera* camera, const std::array<double, 6>& box, double aspect);

}  // namespace motionstyle::detail
