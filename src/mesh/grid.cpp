#include "mesh/grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace granflow {

const char* side_name(Side s) {
  switch (s) {
    case Side::west: return "west";
    case Side::east: return "east";
    case Side::south: return "south";
    case Side::north: return "north";
    case Side::front: return "front";
    case Side::back: return "back";
  }
  return "?";
}

namespace {
// Cell widths of a geometric progression whose last/first ratio is `grading`; ghosts mirror the
// boundary cells so that ghost centres sit at mirror images of the first interior centres.
// With `periodic` the ghosts are the other end's cells, shifted by the domain's length.
void axis_geometry(int n, double lo, double hi, double grading, bool periodic, std::vector<double>& width,
                   std::vector<double>& centre) {
  const int g = Grid::ghost_width;
  width.assign(n + 2 * g, 0.0);
  centre.assign(n + 2 * g, 0.0);
  const double r = (n > 1) ? std::pow(grading, 1.0 / (n - 1)) : 1.0;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += std::pow(r, i);
  const double first = (hi - lo) / sum;
  double x = lo;
  for (int i = 0; i < n; ++i) {
    width[i + g] = first * std::pow(r, i);
    centre[i + g] = x + 0.5 * width[i + g];
    x += width[i + g];
  }
  if (periodic) {
    for (int k = 1; k <= g; ++k) {
      width[g - k] = width[g + n - k];
      centre[g - k] = centre[g + n - k] - (hi - lo);
      width[g + n - 1 + k] = width[g + k - 1];
      centre[g + n - 1 + k] = centre[g + k - 1] + (hi - lo);
    }
    return;
  }
  for (int k = 1; k <= g; ++k) {
    width[g - k] = width[g + k - 1];
    centre[g - k] = lo - (centre[g + k - 1] - lo);
    width[g + n - 1 + k] = width[g + n - k];
    centre[g + n - 1 + k] = hi + (hi - centre[g + n - k]);
  }
}
}  // namespace

namespace {
bool fits(long cells_along, long parts) {
  return parts == 1 || (cells_along >= parts && cells_along / parts >= Grid::ghost_width);
}

// How many ranks share each axis. One layer along z: PETSc's own split of a 2D DMDA (DMSetUp_DA_2D,
// PETSC_DECIDE), the squarest m x n = size with m along the longer axis, so that a planar mesh is laid
// out as it was on a 2D DMDA. More layers: of the splits m x n x p = size whose ranks hold the ghost
// layers, the one with the least area between ranks. Too many ranks for the cells is the user's to
// fix, not a PETSc error trace (which one rank alone may meet while the others wait); each width must
// hold the ghost layers unless the axis is not split.
std::array<int, 3> ranks_per_axis(MPI_Comm comm, std::array<int, 3> cells) {
  int size;
  MPI_Comm_size(comm, &size);
  const long M = cells[0], N = cells[1], P = cells[2];
  auto too_many = [&] {
    return GridError(fmt::format("mesh.cells: {} cells cannot be shared by {} rank{} (each needs at least {} cells "
                                 "along each axis it is split along); use fewer ranks or more cells",
                                 P == 1 ? fmt::format("{} x {}", M, N) : fmt::format("{} x {} x {}", M, N, P), size,
                                 size == 1 ? "" : "s", Grid::ghost_width));
  };
  if (P == 1) {
    long m = std::max(1L, long(0.5 + std::sqrt(double(M) * size / double(N))));
    while (size % m != 0) --m;  // stops at 1 at the latest
    long n = size / m;
    if (M > N && m < n) std::swap(m, n);
    if (!fits(M, m) || !fits(N, n)) throw too_many();
    return {int(m), int(n), 1};
  }
  std::array<int, 3> best{0, 0, 0};
  double best_area = 0.0;
  for (int m = 1; m <= size; ++m)
    for (int n = 1; m * n <= size; ++n) {
      if (size % (m * n) != 0) continue;
      const int p = size / (m * n);
      if (!fits(M, m) || !fits(N, n) || !fits(P, p)) continue;
      const double area = double(m - 1) * N * P + double(n - 1) * M * P + double(p - 1) * M * N;
      if (best[0] == 0 || area < best_area) best = {m, n, p}, best_area = area;
    }
  if (best[0] == 0) throw too_many();
  return best;
}
}  // namespace

Grid::Grid(MPI_Comm comm, const GridSpec& spec) : comm_(comm), spec_(spec) {
  if (spec.cells[0] < 1 || spec.cells[1] < 1 || spec.cells[2] < 1)
    throw std::invalid_argument("grid needs at least one cell per axis");
  if (spec.cells[2] > 1 && spec.axisymmetric) throw std::invalid_argument("an axisymmetric grid has one layer along z");
  if (spec.cells[2] > 1 && !(spec.upper[2] > spec.lower[2] && spec.grading[2] > 0.0))
    throw std::invalid_argument("a grid of several layers needs upper[2] > lower[2] and a positive grading[2]");
  if (spec.cells[2] == 1) spec_.lower[2] = 0.0, spec_.upper[2] = 1.0, spec_.grading[2] = 1.0;  // a metre's depth
  const auto [m, n, p] = ranks_per_axis(comm, spec.cells);
  const DMBoundaryType x_sides = spec.periodic_x ? DM_BOUNDARY_PERIODIC : DM_BOUNDARY_GHOSTED;
  // One layer: no ghosts along z, so that the arrays are those of a 2D DMDA.
  const DMBoundaryType z_sides = spec.cells[2] == 1 ? DM_BOUNDARY_NONE : DM_BOUNDARY_GHOSTED;
  PetscCallAbort(comm, DMDACreate3d(comm, x_sides, DM_BOUNDARY_GHOSTED, z_sides, DMDA_STENCIL_BOX, spec.cells[0],
                                    spec.cells[1], spec.cells[2], m, n, p, 1, ghost_width, nullptr, nullptr, nullptr,
                                    field_dm_.put()));
  PetscCallAbort(comm, DMSetUp(field_dm_));
  const PetscInt *lx, *ly, *lz;
  PetscCallAbort(comm, DMDAGetOwnershipRanges(field_dm_, &lx, &ly, &lz));
  PetscCallAbort(comm, DMDACreate3d(comm, matrix_x_sides(), DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_STAR,
                                    spec.cells[0], spec.cells[1], spec.cells[2], m, n, p, 1, 1, lx, ly, lz,
                                    matrix_dm_.put()));
  PetscCallAbort(comm, DMSetUp(matrix_dm_));
  PetscInt xs, ys, zs, xm, ym, zm;
  PetscCallAbort(comm, DMDAGetCorners(field_dm_, &xs, &ys, &zs, &xm, &ym, &zm));
  owned_ = CellBox{int(xs), int(ys), int(xm), int(ym), int(zs), int(zm)};
  for (int a = 0; a < 3; ++a)
    axis_geometry(spec_.cells[a], spec_.lower[a], spec_.upper[a], spec_.grading[a], a == 0 && spec.periodic_x,
                  width_[a], centre_[a]);
  radius_face_.resize(width_[0].size());
  for (size_t k = 0; k < width_[0].size(); ++k) radius_face_[k] = centre_[0][k] + 0.5 * width_[0][k];
}

Grid::~Grid() = default;

double Grid::min_spacing() const {
  double h = 1e300;
  for (int a = 0; a < dimension(); ++a)
    for (int i = 0; i < spec_.cells[a]; ++i) h = std::min(h, width_[a][i + ghost_width]);
  return h;
}

}  // namespace granflow
