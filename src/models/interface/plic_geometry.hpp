// Piecewise-linear interface calculation (PLIC) geometry on a single 2D cell.
//
// All geometry is done in the cell's own scaled coordinates X = (x - x_c)/dx, Y = (y - y_c)/dy,
// so every cell is the unit square [-0.5, 0.5]^2 whatever its aspect ratio. The interface in a
// cell is the line n.X * X + n.Y * Y = alpha and the soil occupies n.X * X + n.Y * Y <= alpha.
//
// Normal convention: the normal points OUT of the soil (from c = 1 towards c = 0), i.e. along
// -grad c, and is normalised with |nx| + |ny| = 1 (the form in which the Scardovelli & Zaleski
// inversion is simplest). A normal in scaled coordinates corresponds to the physical direction
// (nx/dx, ny/dy); see to_physical().
#pragma once

namespace granflow::interface {

// Interface normal in scaled cell coordinates, |nx| + |ny| = 1, pointing out of the soil.
// {0, 0} means "undefined" (a uniform neighbourhood); callers must treat that case.
struct Normal2 {
  double nx = 0.0;
  double ny = 0.0;
};

// 3x3 block of volume fractions around a cell, indexed c[j][i] with j = row (0 = south,
// 2 = north) and i = column (0 = west, 2 = east); the centre cell is c[1][1]. dx[i] and dy[j]
// are the widths of the three columns and three rows (graded meshes allowed).
struct Block3x3 {
  double c[3][3];
  double dx[3];
  double dy[3];
};

// Gathers the block around cell (i, j) from ghosted [j][i] arrays with global indices.
inline Block3x3 gather_block(const double* const* c, const double* dx, const double* dy, int i,
                             int j) {
  Block3x3 b;
  for (int r = 0; r < 3; ++r)
    for (int q = 0; q < 3; ++q) b.c[r][q] = c[j - 1 + r][i - 1 + q];
  for (int k = 0; k < 3; ++k) {
    b.dx[k] = dx[i - 1 + k];
    b.dy[k] = dy[j - 1 + k];
  }
  return b;
}

// The PLIC line of a mixed cell (0 < c < 1) at the centre of a block: MYC normal and the alpha that
// holds the cell's c. `found` is false where the block is too flat to orient (spread of c below
// 1e-8): MYC's normal is scale-invariant, so round-off noise in a uniform mixed region would
// otherwise be turned into an arbitrary sharp line. Callers then treat the cell as uniform, at c.
struct CellLine {
  bool found = false;
  Normal2 n;
  double alpha = 0.0;
};
// With rho > 0 (an axisymmetric cell, below) alpha holds c as the share of the radius-weighted area.
CellLine cell_line(const Block3x3& b, double rho = 0.0);

// Youngs' normal: -grad c averaged over the four corners of the centre cell. Exact for lines
// aligned with the grid axes or diagonals, first order otherwise.
Normal2 youngs_normal(const Block3x3& b);

// Mixed Youngs-Centred normal (Aulisa, Manservisi, Scardovelli & Zaleski 2007, J. Comput. Phys.
// 225:2301): the centred height-function normal in the direction where the interface is flatter,
// replaced by Youngs' when that one is steeper (larger minor/major ratio). On uniform meshes
// (any aspect ratio) it is exact for every straight line whose column heights (or row widths) are
// bracketed by the 3x3 block; on graded meshes the error for such lines is O(r - 1), r the width
// ratio of neighbouring cells. Heights are physical lengths, so grading is accounted for.
Normal2 myc_normal(const Block3x3& b);

// Converts a normal in scaled cell coordinates (cell widths dx, dy) into the same physical
// direction, again normalised with |nx| + |ny| = 1.
Normal2 to_physical(Normal2 n, double dx, double dy);

// Line constant alpha such that the region n.X*X + n.Y*Y <= alpha of the unit cell [-0.5,0.5]^2
// has area fraction c (Scardovelli & Zaleski 2000, J. Comput. Phys. 164:228, analytic inversion).
// n must satisfy |nx| + |ny| = 1; c is clamped to [0, 1].
double line_alpha(double c, Normal2 n);

// Area fraction of the unit cell lying on the soil side of the line (inverse of line_alpha).
double cell_fraction(Normal2 n, double alpha);

// Area fraction of the sub-rectangle [x0, x1] x [y0, y1] of the unit cell (x0 < x1, y0 < y1, all
// in [-0.5, 0.5]) lying on the soil side of the line; used for the flux polygon. The result is
// relative to the sub-rectangle's own area.
double rectangle_fraction(Normal2 n, double alpha, double x0, double x1, double y0, double y1);

// Length fraction of one side of the unit cell lying on the soil side of the line: the side normal
// to `axis` (0 = x, 1 = y) at X or Y = sign * 0.5 (sign = -1 or +1). A side the line only touches
// counts as soil if the soil lies along it (n.X * X + n.Y * Y <= alpha everywhere on it).
double side_fraction(Normal2 n, double alpha, int axis, int sign);

// Radius-weighted geometry of an axisymmetric cell (x = r). In the cell's scaled coordinates the
// radius is r = dx (rho + X), with rho = r_c / dx >= 0.5 (0.5 for a cell on the axis), and the
// cell's volume per radian is dx^2 dy times the integral of (rho + X) over the unit cell, rho. Its c is
// the soil's share of that volume, so the line holding c lies further out than the planar one where
// the soil is on the axis side: soil nearer the axis weighs less.
//
// Share of the radius-weighted area of [x0, x1] x [y0, y1] (in [-0.5, 0.5]^2) lying on the soil side
// of the line, relative to the sub-rectangle's own weighted area. rho >= 0.5.
double weighted_rectangle_fraction(Normal2 n, double alpha, double rho, double x0, double x1, double y0,
                                   double y1);

// Line constant alpha such that the soil side of the line holds the share c of the cell's
// radius-weighted area (the inverse of weighted_rectangle_fraction over the whole cell), to about 1e-16
// in the share. n as for line_alpha; c is clamped to [0, 1]; rho >= 0.5.
double weighted_line_alpha(double c, Normal2 n, double rho);

// Share of side (axis, sign) of an axisymmetric cell lying on the soil side of the line, the side's
// points weighted by their radius: for a side normal to y, the share of its area (the integral of r
// over it); a side normal to x lies at one radius, and its share is side_fraction's. rho >= 0.5.
double weighted_side_fraction(Normal2 n, double alpha, int axis, int sign, double rho);

// Area fraction of the unit square [0,1]^2 where mx*X + my*Y <= a (any signs, any magnitudes,
// not necessarily normalised). Exact, cancellation-free piecewise formula; building block of the
// functions above.
double unit_square_fraction(double mx, double my, double a);

}  // namespace granflow::interface
