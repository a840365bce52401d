// Piecewise-linear interface calculation (PLIC) geometry on a single 3D cell: the plane that holds a
// cell's soil fraction, and the soil that parts of the cell hold under it. The three-dimensional
// counterpart of plic_geometry.hpp, with the same conventions:
//
// All geometry is done in the cell's own scaled coordinates X = (x - x_c)/dx, Y = (y - y_c)/dy,
// Z = (z - z_c)/dz, so every cell is the unit cube [-0.5, 0.5]^3. The interface is the plane
// n.X X + n.Y Y + n.Z Z = alpha, the soil occupies n.X <= alpha, and the normal points out of the
// soil (along -grad c), normalised with |nx| + |ny| + |nz| = 1.
#pragma once

#include <array>

namespace granflow::interface {

// Interface normal in scaled cell coordinates, |nx| + |ny| + |nz| = 1, pointing out of the soil.
// {0, 0, 0} means "undefined" (a uniform neighbourhood); callers must treat that case.
struct Normal3 {
  double nx = 0.0;
  double ny = 0.0;
  double nz = 0.0;
};

// Volume fraction of the unit cube [0,1]^3 where mx X + my Y + mz Z <= a (any signs, any magnitudes,
// not necessarily normalised): Scardovelli & Zaleski (2000, J. Comput. Phys. 164:228, Eq. 12 and the
// branches after it), each branch written without cancellation, so that a nearly axis-aligned plane
// (a tiny coefficient) keeps full relative accuracy. Building block of the functions below.
double unit_cube_fraction(double mx, double my, double mz, double a);

// Volume fraction of the cell on the soil side of the plane.
double cube_fraction(Normal3 n, double alpha);

// Plane constant alpha such that the soil side of the plane holds the volume fraction c of the
// cell: Scardovelli & Zaleski's analytic inversion (a cube root, a square root or a cubic's
// trigonometric root), polished by Newton's method on unit_cube_fraction, so that
// cube_fraction(n, plane_alpha(c, n)) is c to round-off (a few 1e-15). c is clamped to [0, 1]; n as above.
double plane_alpha(double c, Normal3 n);

// Volume fraction of the box [lower, upper] (inside the unit cube, lower < upper along each axis)
// on the soil side of the plane, relative to the box's own volume: the soil a flux volume carries.
double box_fraction(Normal3 n, double alpha, const std::array<double, 3>& lower, const std::array<double, 3>& upper);

// Area fraction of one face of the cell on the soil side of the plane: the face normal to `axis`
// (0 = x, 1 = y, 2 = z) at sign * 0.5 (sign = -1 or +1).
double face_fraction(Normal3 n, double alpha, int axis, int sign);

// 3 x 3 x 3 block of volume fractions around a cell, c[k][j][i] with k along z, j along y and i along
// x (0 = low side, 2 = high side); the centre cell is c[1][1][1]. dx, dy, dz are the widths of the
// block's three columns, rows and layers (graded meshes allowed).
struct Block3x3x3 {
  double c[3][3][3];
  double dx[3];
  double dy[3];
  double dz[3];
};

// Youngs' normal: -grad c at the eight corners of the centre cell, each from the eight cells that
// share the corner, averaged, in the centre cell's scaled coordinates. Exact for planes aligned with
// the grid's axes, face diagonals and body diagonals on a uniform mesh; first order otherwise.
Normal3 youngs_normal(const Block3x3x3& b);

// Mixed Youngs-centred normal in 3D (Aulisa, Manservisi, Scardovelli & Zaleski 2007, J. Comput. Phys.
// 225:2301; Basilisk's mycs has the same choice): the centred height-function normal along each
// axis (the column sums of the block along the axis, differenced across it), the one most aligned
// with its own axis of the three, replaced by Youngs' when that one's is more aligned still. Exact
// on a uniform mesh for every plane whose heights along one of the axes the block brackets. Heights
// are physical lengths, so graded cells are allowed; there the error for such planes is of the order
// of the grading (Youngs' may be taken), as in 2D.
Normal3 myc_normal(const Block3x3x3& b);

// Converts a normal in scaled cell coordinates (cell widths dx, dy, dz) into the same physical
// direction, again normalised with |nx| + |ny| + |nz| = 1.
Normal3 to_physical(Normal3 n, double dx, double dy, double dz);

}  // namespace granflow::interface
