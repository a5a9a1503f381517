#include "viewport_floor.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>

namespace motionstyle::detail {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Where the horizon usually sits in the backdrop's gradient (0 bottom, 1 top) for the default camera
// (12 degrees down, 30 degree field of view): the floor fades to that colour so it meets the sky
// without a seam.
constexpr double kHorizonBlend = 0.9;
// The flat apron around the checker reaches this many checker radii, close to the true horizon.
constexpr double kApronRadii = 25.0;
constexpr int kApronSegments = 48;
constexpr double kLightTile[3] = {0.60, 0.61, 0.63};
constexpr double kDarkTile[3] = {0.50, 0.515, 0.54};

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

void fillFloorMesh(vtkPolyData* mesh, const std::array<double, 3>& centre, double tile, int half_tiles) {
  const double centre_x = centre[0];
  const double floor_height = centre[1];
  const double centre_z = centre[2];
  const double radius = half_tiles * tile;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> quads;
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetNumberOfComponents(3);
  colors->SetName("floor");
  // Opaque, fading into the backdrop's colour near the horizon: a translucent floor would send VTK
  // through its order-independent translucency pass, several full-screen passes per frame.
  double horizon[3];
  for (int c = 0; c < 3; ++c) horizon[c] = kBackdropBottom[c] + kHorizonBlend * (kBackdropTop[c] - kBackdropBottom[c]);
  for (int ix = -half_tiles; ix < half_tiles; ++ix) {
    for (int iz = -half_tiles; iz < half_tiles; ++iz) {
      const double* rgb = ((ix + iz) % 2 == 0) ? kLightTile : kDarkTile;
      vtkIdType ids[4];
      const double corners[4][2] = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
      for (int c = 0; c < 4; ++c) {
        const double x = centre_x + (ix + corners[c][0]) * tile;
        const double z = centre_z + (iz + corners[c][1]) * tile;
        ids[c] = points->InsertNextPoint(x, floor_height, z);
        const double distance = std::hypot(x - centre_x, z - centre_z);
        const double fade = smoothstep(0.35 * radius, 0.95 * radius, distance);
        unsigned char shade[3];
        for (int k = 0; k < 3; ++k)
          shade[k] = static_cast<unsigned char>(std::lround(255.0 * (rgb[k] + (horizon[k] - rgb[k]) * fade)));
        colors->InsertNextTypedTuple(shade);
      }
      quads->InsertNextCell(4, ids);
    }
  }
  // A flat apron in the horizon colour from the checker's rim to near the horizon: the floor's edge
  // then sits where the backdrop already has that colour.
  const unsigned char apron[3] = {static_cast<unsigned char>(std::lround(255.0 * horizon[0])),
                                  static_cast<unsigned char>(std::lround(255.0 * horizon[1])),
                                  static_cast<unsigned char>(std::lround(255.0 * horizon[2]))};
  for (int i = 0; i < kApronSegments; ++i) {
    vtkIdType ids[4];
    const double angles[2] = {2.0 * kPi * i / kApronSegments, 2.0 * kPi * (i + 1) / kApronSegments};
    const double radii[4] = {radius * 0.999, radius * kApronRadii, radius * kApronRadii, radius * 0.999};
    const double* corner_angles[4] = {&angles[0], &angles[0], &angles[1], &angles[1]};
    for (int c = 0; c < 4; ++c) {
      // The checker is a square: its inner rim is the inscribed circle, its corners stay on top.
      ids[c] = points->InsertNextPoint(centre_x + radii[c] * std::cos(*corner_angles[c]), floor_height - 0.05,
                                       centre_z + radii[c] * std::sin(*corner_angles[c]));
      colors->InsertNextTypedTuple(apron);
    }
    quads->InsertNextCell(4, ids);
  }
  mesh->SetPoints(points);
  mesh->SetPolys(quads);
  mesh->GetPointData()->SetScalars(colors);
  mesh->Modified();
}

}  // namespace motionstyle::detail
