#pragma once
// The viewport's floor and backdrop colours (INTERNAL header, VTK types).
//
// The floor is a checker of `tile` cm squares, 2 * half_tiles on a side, centred on `centre` (cm,
// world, Y-up; centre[1] is the floor height), whose tiles fade into the backdrop's horizon colour
// towards the rim, surrounded by a flat apron in that colour reaching nearly to the horizon, so the
// stage has no visible edge. It is OPAQUE and unlit on purpose: a translucent fade would send VTK
// through its order-independent translucency passes, and lighting it would cost per-pixel work for
// nothing (both matter under software OpenGL). Vertices are per tile, so every tile keeps its own
// flat colour while the fade is interpolated.

#include <array>

class vtkPolyData;

namespace motionstyle::detail {

inline constexpr double kBackdropBottom[3] = {0.20, 0.215, 0.235};
inline constexpr double kBackdropTop[3] = {0.44, 0.47, 0.52};

// Replaces `mesh`'s points, quads and RGB point colours.
void fillFloorMesh(vtkPolyData* mesh, const std::array<double, 3>& centre, double tile, int half_tiles);

}  // namespace motionstyle::detail
