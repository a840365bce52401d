// Operator-split geometric (PLIC) advection of the soil fraction c on a 3D Cartesian (possibly graded)
// mesh: the three-dimensional counterpart of vof_advection.hpp, with the same scheme (Weymouth & Yue
// 2010, J. Comput. Phys. 229:2853: exactly conservative for a discretely divergence-free velocity,
// bounded for Courant numbers below 1/2 per sweep) and the same conventions, one axis more:
//   - arrays are `double***` indexed [k][j][i] with global cell indices and two ghost layers, as a
//     PETSc DMDA's local array (DM_BOUNDARY_GHOSTED, DMDA_STENCIL_BOX, width 2);
//   - face velocities of axis a at [k][j][i] are on the face between the cell and its neighbour at +1
//     along a (the low boundary face at index -1 along a);
//   - dx, dy, dz are cell widths indexed globally, valid for ghost indices too.
// The plane in a mixed cell takes the mixed Youngs-centred normal (plic_geometry_3d.hpp), as in 2D.
//
// One time step: fill the ghosts of c (corners included); dilatation_indicator once; then three sweeps,
// each into the other array, ghosts refilled after each; the order of the axes permuted from step to
// step (x y z, y z x, z x y) so that none always goes first.
#pragma once

#include "mesh/cell_box.hpp"

namespace granflow::interface {

// Ghost-offset cell widths along x, y and z.
struct CellWidths3 {
  const double* dx = nullptr;
  const double* dy = nullptr;
  const double* dz = nullptr;
  const double* along(int axis) const { return axis == 0 ? dx : (axis == 1 ? dy : dz); }
};

// The domain's cells, for a sweep to treat the cells beyond it as boundary ghosts (soil coming in
// is a plain donor at the ghost's value; a cell next to a side fits its plane as if the soil went on
// unchanged beyond it). nx = 0: the ghosts are read as cells (a reference driver's). periodic_x: the
// ghosts beyond the west and east sides are the other end's cells (read as cells), as in 2D.
struct DomainCells3 {
  int nx = 0, ny = 0, nz = 0;
  bool periodic_x = false;
};

// One directional sweep (axis 0, 1 or 2):
//   c_new = c + (F_low - F_high)/h + cc (u_high - u_low) dt/h,
// with F the volume per unit face area of the upwind cell's soil swept through a face in dt. Writes
// c_new on the owned cells only (it must not alias c). Reads c on the owned cells and two ghost
// layers (one across the axis, corners included), the face velocities on the faces bounding the owned
// cells along the axis, and cc on the owned cells. With `face_soil` (non-null, laid out like the face
// velocities), F of every face the sweep computes (the low ghost face included) is added to it: the
// soil volume per unit face area that crossed it, so that momentum can move with the same mass.
void vof_sweep(int axis, double dt, const double* const* const* c, const double* const* const* face_velocity,
               const double* const* const* cc, CellWidths3 widths, CellBox owned, double*** c_new,
               DomainCells3 domain = {}, double*** face_soil = nullptr);

// Soil volume that the sweep of `axis` carries out of the domain through the boundary faces of the
// owned cells (negative for inflow): the same face fluxes as vof_sweep given the same domain, so that
// the soil in the domain plus the outflow of such sweeps is conserved. Needs domain.nx > 0. Along a
// periodic x there are no boundary faces.
double boundary_outflow(int axis, double dt, const double* const* const* c, const double* const* const* face_velocity,
                        CellWidths3 widths, CellBox owned, DomainCells3 domain);

// Soil volume that the x sweep carries through face (i, j, k), between cells i and i + 1, positive
// along x: the F vof_sweep takes there, times the face's area (a periodic strip's join, for its budget).
double face_soil_volume_x(int i, int j, int k, double dt, const double* const* const* c,
                          const double* const* const* face_velocity, CellWidths3 widths, DomainCells3 domain);

// cc = 1 where c > 0.5, else 0, on the owned cells; once per step, before the first sweep.
void dilatation_indicator(const double* const* const* c, CellBox owned, double*** cc);

// Largest |u| dt / h over the faces bounding the owned cells along the axis, h the smaller of the two
// cells' widths. Local to this rank.
double max_sweep_courant(int axis, double dt, const double* const* const* face_velocity, CellWidths3 widths,
                         CellBox owned);

// region_out = 1 on the owned cells with |in| > `floor` anywhere in their 3 x 3 x 3 box, else 0: the
// 3D soil_region of vof_advection.hpp, which says why n passes bound n sub-steps' sweeps.
void soil_region(const double* const* const* in, CellBox owned, double*** region_out, double floor = 0.0);

}  // namespace granflow::interface
