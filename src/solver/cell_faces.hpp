#pragma once
// The four faces of a cell (i, j) as the finite-volume loops of the flow solver visit them.
#include "mesh/grid.hpp"

namespace granflow {

// Geometry of one face of cell (i, j) in 2D planar coordinates (unit depth).
struct FaceGeometry {
  Side side;
  int axis;      // normal axis of the face
  double sign;   // +1 for the east/north face, -1 for west/south
  int di, dj;    // offset to the neighbour across the face
};
inline constexpr FaceGeometry faces_of_cell[4] = {
    {Side::east, 0, +1.0, +1, 0},
    {Side::west, 0, -1.0, -1, 0},
    {Side::north, 1, +1.0, 0, +1},
    {Side::south, 1, -1.0, 0, -1},
};

}  // namespace granflow
