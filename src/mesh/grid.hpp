#pragma once
// Cartesian cell-centred grid on a PETSc DMDA.
//
// Every field lives on one DMDA with DM_BOUNDARY_GHOSTED sides and a box stencil of width 2, so local
// arrays carry two layers of ghost cells also outside the physical domain (indices -2, -1 and n, n+1);
// boundary conditions fill those. With periodic x (GridSpec::periodic_x) the x sides are
// DM_BOUNDARY_PERIODIC: the exchange fills those ghosts with the other end's cells, and the
// matrices' stencils wrap. Matrices use a second DMDA with the same parallel layout and a
// star stencil (5 points in 2D, 7 in 3D), so they are preallocated for exactly the pattern the operators use.
//
// Coordinates are held per axis (cell widths and centres, ghosts included), so graded spacing is a
// change of constructor only.
//
// The DMDAs are three-dimensional. A planar or axisymmetric mesh is one layer of cells along z
// (nz = 1), whose z sides have no ghosts, so its arrays are [0][j][i] and hold what a 2D DMDA's would;
// its ranks are laid out as PETSc lays out a 2D DMDA. Its areas and volumes are per metre of depth
// (per radian in r-z).
#include <petscdmda.h>

#include <array>
#include <cassert>
#include <span>
#include <stdexcept>
#include <vector>

#include "mesh/cell_box.hpp"
#include "mesh/petsc_handle.hpp"

namespace granflow {

// The sides of the box: west and east along x, south and north along y (the vertical), front and back
// along z, which a mesh of several layers has.
enum class Side { west = 0, east = 1, south = 2, north = 3, front = 4, back = 5 };
inline constexpr std::array<Side, 4> planar_sides{Side::west, Side::east, Side::south, Side::north};
inline constexpr std::array<Side, 6> box_sides{Side::west, Side::east, Side::south, Side::north, Side::front, Side::back};
// The sides a mesh of this dimension has (2: the planar four; 3: all six).
inline std::span<const Side> sides_of_dimension(int dimension) {
  return dimension == 3 ? std::span<const Side>(box_sides) : std::span<const Side>(planar_sides);
}
const char* side_name(Side s);
// The axis a side is normal to (0 = x, 1 = y, 2 = z).
inline int normal_axis(Side s) { return static_cast<int>(s) / 2; }
// Outward unit normal component of a side along an axis.
inline double outward_normal(Side s, int axis) {
  if (axis != normal_axis(s)) return 0.0;
  return static_cast<int>(s) % 2 == 0 ? -1.0 : 1.0;
}
// A side at the low end of its axis (west, south, front).
inline bool is_low_side(Side s) { return static_cast<int>(s) % 2 == 0; }
// The side a boundary face lies on, from its axis and its sign (-1 low, +1 high).
inline Side side_of(int axis, int sign) { return static_cast<Side>(2 * axis + (sign < 0 ? 0 : 1)); }

struct GridSpec {
  // Cells along x, y and z; y is the vertical of the shipped cases, in 2D and 3D alike. With one cell
  // along z the mesh is planar (or axisymmetric) and the z entries of lower, upper and grading are
  // not read: the depth is one metre.
  std::array<int, 3> cells{0, 0, 1};
  std::array<double, 3> lower{0.0, 0.0, 0.0};
  std::array<double, 3> upper{1.0, 1.0, 1.0};
  // Ratio of the last to the first cell width per axis (1 = uniform); geometric progression.
  std::array<double, 3> grading{1.0, 1.0, 1.0};
  // Axisymmetric (r-z): x is the radius r >= 0, y the axial coordinate z. Areas and volumes are per
  // radian: a face at radius r has area r dz, a cell volume r_c dr dz.
  bool axisymmetric = false;
  // The west and east sides joined (an infinite strip, e.g. a uniform flow down a slope): the cell
  // beyond the east side is the first cell, and ghosts along x are the other end's cells.
  bool periodic_x = false;
  // 2 for one layer along z (planar or axisymmetric), 3 for a mesh of layers.
  int dimension() const { return cells[2] > 1 ? 3 : 2; }
};

// The mesh cannot be laid out as asked (too many ranks for its cells); thrown on every rank alike.
struct GridError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Grid {
 public:
  static constexpr int ghost_width = 2;

  Grid(MPI_Comm comm, const GridSpec& spec);
  ~Grid();
  Grid(const Grid&) = delete;
  Grid& operator=(const Grid&) = delete;

  MPI_Comm comm() const { return comm_; }
  DM field_dm() const { return field_dm_; }    // ghosted, box stencil width 2
  DM matrix_dm() const { return matrix_dm_; }  // star stencil width 1, same layout
  // The x sides of a matrix's DMDA: periodic ones wrap its stencil, others end it.
  DMBoundaryType matrix_x_sides() const { return spec_.periodic_x ? DM_BOUNDARY_PERIODIC : DM_BOUNDARY_NONE; }
  int nx() const { return spec_.cells[0]; }
  int ny() const { return spec_.cells[1]; }
  int nz() const { return spec_.cells[2]; }
  // 2 for a planar or axisymmetric mesh (one layer along z), 3 otherwise.
  int dimension() const { return spec_.dimension(); }
  long cell_count() const { return long(nx()) * ny() * nz(); }
  const GridSpec& spec() const { return spec_; }
  const CellBox& owned() const { return owned_; }
  // The cells of the local (ghosted) arrays: the owned block and ghost_width cells around it, along z
  // too on a mesh of layers (a planar mesh's one layer has no z ghosts).
  CellBox with_ghosts() const {
    const bool layers = dimension() == 3;
    return {owned_.xs - ghost_width, owned_.ys - ghost_width, owned_.xm + 2 * ghost_width, owned_.ym + 2 * ghost_width,
            layers ? owned_.zs - ghost_width : 0, layers ? owned_.zm + 2 * ghost_width : 1};
  }

  // Per-axis geometry, valid for ghost indices -2 .. n+1.
  double dx(int i) const { return width_[0][i + ghost_width]; }
  double dy(int j) const { return width_[1][j + ghost_width]; }
  double xc(int i) const { return centre_[0][i + ghost_width]; }
  double yc(int j) const { return centre_[1][j + ghost_width]; }
  double dz(int k) const { return width_[2][k + ghost_width]; }  // 1 on a planar mesh
  double zc(int k) const { return centre_[2][k + ghost_width]; }
  // The same along any axis (0 = x, 1 = y, 2 = z), for kernels that loop over axes.
  double width(int axis, int index) const { return width_[axis][index + ghost_width]; }
  double centre(int axis, int index) const { return centre_[axis][index + ghost_width]; }
  // Face coordinate between cells i and i+1 (east face of cell i).
  double xf(int i) const { return xc(i) + 0.5 * dx(i); }
  double yf(int j) const { return yc(j) + 0.5 * dy(j); }
  double zf(int k) const { return zc(k) + 0.5 * dz(k); }
  bool axisymmetric() const { return spec_.axisymmetric; }
  // Radius weight of cell i's centre and of its east face (1 in planar geometry).
  double radius_c(int i) const { return spec_.axisymmetric ? xc(i) : 1.0; }
  double radius_f(int i) const { return spec_.axisymmetric ? xf(i) : 1.0; }
  // Volume of cell (i, j) of a planar or axisymmetric mesh (per metre of depth, per radian).
  double volume(int i, int j) const {
    assert(dimension() == 2);
    return dx(i) * dy(j) * radius_c(i);
  }
  // Volume of cell (i, j, k) of a mesh of any dimension: a planar or axisymmetric mesh's depth is 1,
  // so it is volume(i, j) to the bit.
  double volume(int i, int j, int k) const { return dx(i) * dy(j) * dz(k) * radius_c(i); }
  // Area of the face of cell (i, j) of a planar or axisymmetric mesh normal to `axis` (0 or 1) on the
  // high (sign > 0) or low side.
  double face_area(int axis, int i, int j, double sign) const {
    assert(dimension() == 2 && axis < 2);
    return axis == 0 ? dy(j) * radius_f(sign > 0 ? i : i - 1) : dx(i) * radius_c(i);
  }
  // Area of the face of cell (i, j, k) normal to `axis` on its high (sign > 0) or low side, on a mesh
  // of any dimension; on one layer it is face_area(axis, i, j, sign) to the bit.
  double face_area(int axis, int i, int j, int k, double sign) const {
    if (axis == 0) return dy(j) * dz(k) * radius_f(sign > 0 ? i : i - 1);
    return axis == 1 ? dx(i) * dz(k) * radius_c(i) : dx(i) * dy(j);
  }
  // Raw pointers offset so that p[-2] is the first ghost; for kernels working on plain arrays.
  const double* dx_data() const { return width_[0].data() + ghost_width; }
  const double* dy_data() const { return width_[1].data() + ghost_width; }
  const double* dz_data() const { return width_[2].data() + ghost_width; }
  // Radii of the x-faces (p[i] = r of cell i's east face) and of the cell centres, ghost-offset like
  // dx_data(); nullptr in planar geometry, so kernels can skip the weights altogether.
  const double* radius_face_data() const { return spec_.axisymmetric ? radius_face_.data() + ghost_width : nullptr; }
  const double* radius_centre_data() const { return spec_.axisymmetric ? centre_[0].data() + ghost_width : nullptr; }
  double min_spacing() const;
  bool periodic_x() const { return spec_.periodic_x; }
  // Whether side s is a boundary of the domain (not joined to the opposite side). The front and back
  // of a planar mesh are not: it is one layer, a metre deep, without ghosts along z.
  bool bounded(Side s) const {
    if (s == Side::front || s == Side::back) return dimension() == 3;
    return !(spec_.periodic_x && (s == Side::west || s == Side::east));
  }
  // Whether (i, j) lies beyond a boundary: a ghost that a boundary condition fills. A ghost across a
  // periodic side is a cell of the other end, not outside.
  bool outside(int i, int j) const {
    return j < 0 || j >= ny() || (!spec_.periodic_x && (i < 0 || i >= nx()));
  }
  bool outside(int i, int j, int k) const { return k < 0 || k >= nz() || outside(i, j); }
  // Whether this rank's cells touch side s and it is a boundary: its ghosts beyond s are the rank's to fill.
  bool owns_boundary(Side s) const {
    if (!bounded(s)) return false;
    switch (s) {
      case Side::west: return owned_.xs == 0;
      case Side::east: return owned_.xe() == nx();
      case Side::south: return owned_.ys == 0;
      case Side::north: return owned_.ye() == ny();
      case Side::front: return owned_.zs == 0;
      case Side::back: return owned_.ze() == nz();
    }
    return false;
  }

 private:
  MPI_Comm comm_;
  GridSpec spec_;
  OwnedDm field_dm_;
  OwnedDm matrix_dm_;
  CellBox owned_;
  std::array<std::vector<double>, 3> width_, centre_;
  std::vector<double> radius_face_;  // x-face coordinates, east face of each (ghost) column
};

}  // namespace granflow
