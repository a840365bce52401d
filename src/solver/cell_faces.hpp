#pragma once
// The faces of a cell as the finite-volume loops of the flow solver visit them.
#include <span>

#include "mesh/grid.hpp"
#include "operators/strain_rate.hpp"

namespace granflow {

// Geometry of one face of a cell.
struct FaceGeometry {
  Side side;
  int axis;        // normal axis of the face
  double sign;     // +1 for the east/north/back face, -1 for west/south/front
  int di, dj, dk;  // offset to the neighbour across the face
};
// A cell's faces: east, west, north, south, then back and front on a mesh of layers. The 2D kernels
// visit the first four (faces_of_cell), in this order.
inline constexpr FaceGeometry box_faces[6] = {
    {Side::east, 0, +1.0, +1, 0, 0},  {Side::west, 0, -1.0, -1, 0, 0},  {Side::north, 1, +1.0, 0, +1, 0},
    {Side::south, 1, -1.0, 0, -1, 0}, {Side::back, 2, +1.0, 0, 0, +1}, {Side::front, 2, -1.0, 0, 0, -1},
};
inline constexpr std::span<const FaceGeometry, 4> faces_of_cell{box_faces, 4};
// The faces of a cell of a mesh of this dimension.
inline std::span<const FaceGeometry> cell_faces(int dimension) {
  return {box_faces, std::size_t(dimension == 3 ? 6 : 4)};
}
// The face of a cell on the `sign` side along `axis`.
constexpr const FaceGeometry& face_along(int axis, int sign) { return box_faces[2 * axis + (sign < 0)]; }
// The face of a cell that lies on side s of the domain when the cell is next to it.
constexpr const FaceGeometry& face_on(Side s) {
  for (const auto& f : box_faces)
    if (f.side == s) return f;
  return box_faces[0];  // unreachable: every side is listed
}

// The index of cell (i, j, k) along `axis`.
inline int index_along(int axis, int i, int j, int k) { return axis == 0 ? i : (axis == 1 ? j : k); }

// The value on face fg of cell (i, j, k) of a face field held per axis in FlowSolver's layout:
// [k][j][i] of faces[a] is the cell's high face along a, and the entry at -1 along a its low one.
inline double on_face(const VolumeView faces[], int i, int j, int k, const FaceGeometry& fg) {
  const bool low = fg.sign < 0;
  return faces[fg.axis][k - (low && fg.axis == 2)][j - (low && fg.axis == 1)][i - (low && fg.axis == 0)];
}
// The same for a planar mesh's x and y faces, [j][i].
inline double on_face(const double* const* x_faces, const double* const* y_faces, int i, int j,
                      const FaceGeometry& fg) {
  if (fg.axis == 0) return x_faces[j][fg.sign > 0 ? i : i - 1];
  return y_faces[fg.sign > 0 ? j : j - 1][i];
}

// The lagged part of the viscous stress on face fg of cell (i, j, k) for the component c tangential
// to it, over mu: (d v_n / d x_c) - (d v_c / d n), the remainder of Jasak & Weller (2000) after the
// implicit 2 mu grad(v_c) (momentum_equation.cpp). vel holds the components as local arrays;
// boundary faces read the ghosts, which encode the boundary condition.
inline double lagged_transpose_gradient(const Grid& g, const VolumeView vel[], int i, int j, int k,
                                        const FaceGeometry& fg, int c) {
  const int in = i + fg.di, jn = j + fg.dj, kn = k + fg.dk;
  const VolumeView qn = vel[fg.axis];  // normal component, differentiated along c
  const VolumeView qc = vel[c];        // component c, differentiated along the normal
  // d v_n / d x_c, the mean of the central differences in the two cells.
  const int ci = c == 0, cj = c == 1, ck = c == 2;
  const int along = index_along(c, i, j, k);
  const double span = g.centre(c, along + 1) - g.centre(c, along - 1);
  const double tangential = 0.5 * ((at(qn, i + ci, j + cj, k + ck) - at(qn, i - ci, j - cj, k - ck)) / span +
                                   (at(qn, in + ci, jn + cj, kn + ck) - at(qn, in - ci, jn - cj, kn - ck)) / span);
  const double dn = g.centre(fg.axis, index_along(fg.axis, in, jn, kn)) - g.centre(fg.axis, index_along(fg.axis, i, j, k));
  const double normal = (at(qc, in, jn, kn) - at(qc, i, j, k)) / dn;
  return tangential - normal;
}
inline double lagged_transpose_gradient(const Grid& g, const double* const* const vel[2], int i, int j,
                                        const FaceGeometry& fg, int c) {
  const PlaneAsVolume u(vel[0]), v(vel[1]);
  const VolumeView volumes[2] = {u, v};
  return lagged_transpose_gradient(g, volumes, i, j, 0, fg, c);
}

// The wall-normal derivative of a velocity component q at the wall face fg of cell (i, j, k), whose
// value at the wall is `wall`: the two-point (q_1 - wall) / (h/2), or the quadratic through the wall
// and the first two centres (numerics.wall_gradient = "quadratic", operators/strain_rate.hpp).
// Its magnitude, not its sign along the normal: the wall's traction on the cell is -mu times it.
inline double wall_gradient(const Grid& g, VolumeView q, int i, int j, int k, const FaceGeometry& fg, double wall,
                            bool quadratic) {
  const int along = index_along(fg.axis, i, j, k), step = fg.sign > 0 ? 1 : -1;
  const double h1 = g.width(fg.axis, along);
  const double u1 = at(q, i, j, k);
  if (!quadratic) return (u1 - wall) / (0.5 * h1);
  const double h2 = g.width(fg.axis, along - step);
  return quadratic_wall_derivative(u1, at(q, i - fg.di, j - fg.dj, k - fg.dk), wall, 0.5 * h1, h1 + 0.5 * h2);
}
inline double wall_gradient(const Grid& g, const double* const* q, int i, int j, const FaceGeometry& fg, double wall,
                            bool quadratic) {
  return wall_gradient(g, PlaneAsVolume(q), i, j, 0, fg, wall, quadratic);
}

}  // namespace granflow
