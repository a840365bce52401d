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
// The face of a cell that lies on side s of the domain when the cell is next to it.
constexpr const FaceGeometry& face_on(Side s) {
  for (const auto& f : box_faces)
    if (f.side == s) return f;
  return box_faces[0];  // unreachable: every side is listed
}

// The value on face fg of cell (i, j) of a face field held as x and y faces in FlowSolver's layout:
// [j][i] of the x faces is the cell's east face and [j][i - 1] its west one; the y faces likewise in j.
inline double on_face(const double* const* x_faces, const double* const* y_faces, int i, int j,
                      const FaceGeometry& fg) {
  if (fg.axis == 0) return x_faces[j][fg.sign > 0 ? i : i - 1];
  return y_faces[fg.sign > 0 ? j : j - 1][i];
}

// The lagged part of the viscous stress on face fg of cell (i, j) for the component c tangential to
// it, over mu: (d v_n / d x_c) - (d v_c / d n), the remainder of Jasak & Weller (2000) after the
// implicit 2 mu grad(v_c) (momentum_equation.cpp). vel holds both components as local arrays;
// boundary faces read the ghosts, which encode the boundary condition.
inline double lagged_transpose_gradient(const Grid& g, const double* const* const vel[2], int i, int j,
                                        const FaceGeometry& fg, int c) {
  const int in = i + fg.di, jn = j + fg.dj;
  const double* const* qn = vel[fg.axis];  // normal component, differentiated along c
  const double* const* qc = vel[c];        // component c, differentiated along the normal
  double tangential;
  if (c == 0)  // d v_n / dx at a north/south face
    tangential = 0.5 * ((qn[j][i + 1] - qn[j][i - 1]) / (g.xc(i + 1) - g.xc(i - 1)) +
                        (qn[jn][i + 1] - qn[jn][i - 1]) / (g.xc(i + 1) - g.xc(i - 1)));
  else  // d v_n / dy at an east/west face
    tangential = 0.5 * ((qn[j + 1][i] - qn[j - 1][i]) / (g.yc(j + 1) - g.yc(j - 1)) +
                        (qn[j + 1][in] - qn[j - 1][in]) / (g.yc(j + 1) - g.yc(j - 1)));
  const double dn = fg.axis == 0 ? g.xc(in) - g.xc(i) : g.yc(jn) - g.yc(j);
  const double normal = (qc[jn][in] - qc[j][i]) / dn;
  return tangential - normal;
}

// The wall-normal derivative of a velocity component q at the wall face fg of cell (i, j), whose
// value at the wall is `wall`: the two-point (q_1 - wall) / (h/2), or the quadratic through the wall
// and the first two centres (numerics.wall_gradient = "quadratic", operators/strain_rate.hpp).
// Its magnitude, not its sign along the normal: the wall's traction on the cell is -mu times it.
inline double wall_gradient(const Grid& g, const double* const* q, int i, int j, const FaceGeometry& fg, double wall,
                            bool quadratic) {
  const double h1 = fg.axis == 0 ? g.dx(i) : g.dy(j);
  const double u1 = q[j][i];
  if (!quadratic) return (u1 - wall) / (0.5 * h1);
  const double h2 = fg.axis == 0 ? g.dx(i - fg.di) : g.dy(j - fg.dj);
  return quadratic_wall_derivative(u1, q[j - fg.dj][i - fg.di], wall, 0.5 * h1, h1 + 0.5 * h2);
}

}  // namespace granflow
