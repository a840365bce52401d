// Operator-split geometric (PLIC) advection of the soil fraction c on a 2D Cartesian (possibly
// graded) mesh, with the dilatation correction of Weymouth & Yue (2010, J. Comput. Phys.
// 229:2853) that makes the split scheme exactly conservative for a discretely divergence-free
// velocity and bounded for Courant numbers below 1/2 per sweep.
//
// Data layout (matches a PETSc DMDA local array, DM_BOUNDARY_GHOSTED, DMDA_STENCIL_BOX, width 2):
//   - 2D arrays are `double**` indexed [j][i] with GLOBAL cell indices; ghost cells exist for
//     i in [xs-2, xs+xm+1] and j in [ys-2, ys+ym+1], including outside the physical domain.
//   - Face velocities use the east/north convention: ux[j][i] is the x-velocity on the face between
//     cells i and i+1 (the west boundary face is ux[j][-1]); uy[j][i] is the y-velocity on the
//     face between rows j and j+1.
//   - dx[i], dy[j] are cell widths indexed globally, valid for ghost indices too.
//
// One time step (the caller's job, see the advection tests' SerialVofField, tests/unit/interface, for a serial reference driver):
//   1. fill ghosts of c (exchange + boundary conditions), including the corner ghosts;
//   2. dilatation_indicator(c, owned, cc)  -- once per step, held fixed over both sweeps;
//   3. vof_sweep(first axis, ...) into c_tmp; fill ghosts of c_tmp;
//   4. vof_sweep(second axis, ...) back into c; alternate the axis order every step.
#pragma once

#include "mesh/cell_box.hpp"

namespace granflow::interface {

// Owned cells [xs, xs+xm) x [ys, ys+ym) in global indices.
using granflow::CellBox;

// Radius weights of an axisymmetric (r-z, x = r) mesh, ghost-offset like dx: face[i] is the radius of
// cell i's east face, centre[i] that of its centre. Fluxes through x-faces are multiplied by the face
// radius and the update divided by the centre radius (the cell volume is r_c dr dz per radian), which
// keeps sum(c r_c dr dz) conserved. c is the soil's share of the cell's volume, so the donor's line is
// placed to hold c of the radius-weighted area, the flux is the radius-weighted soil in the swept strip,
// and an x-strip's width is that of the face's swept volume r_f u dt (wider than u dt by the outer
// face, narrower by the inner): the soil a strip carries is what it takes from its cell, and the sweep
// stays bounded as the planar one does (plic_geometry.hpp, weighted_*). Both null: planar.
struct RadialWeights {
  const double* face = nullptr;
  const double* centre = nullptr;
};

// The domain's cells, nx x ny, for a sweep to treat the cells beyond it as boundary ghosts: soil coming
// in through a side is a plain donor at the ghost's value (an atmosphere's inflow fraction), with no
// interface line fitted across the side, and a cell next to a side fits its line as if the soil went
// on unchanged beyond it (so a layer leaves through an open side as it is). nx = 0: the ghosts are
// read as cells (a periodic or reference driver's). periodic_x: the ghosts beyond the west and east
// sides are the other end's cells (read as cells), those beyond south and north boundary ghosts.
struct DomainCells {
  int nx = 0, ny = 0;
  bool periodic_x = false;
};

// One directional sweep (axis 0 = x, 1 = y) of Weymouth & Yue's scheme:
//   c_new = c + (F_low - F_high)/h + cc * (u_high - u_low) dt/h,
// with F the volume (per unit face area) of the upwind cell's PLIC polygon swept through a face
// in dt. Writes c_new on owned cells only; c_new must not alias c.
// Reads c on owned cells plus two ghost layers along `axis` and one across it (corners included),
// face_velocity on the faces bounding owned cells along `axis`, and cc on owned cells.
// Requires max_sweep_courant(axis, ...) < 0.5 for boundedness. With radial weights the x-sweep
// reads c_new = c + (r_low F_low - r_high F_high)/(r_c h) + cc (r_high u_high - r_low u_low) dt/(r_c h);
// the y-sweep is unchanged (its faces and cells share the radius r_c).
// With `face_soil` (non-null, laid out like face_velocity), F of every face the sweep computes (those
// bounding owned cells along `axis`, the low ghost face included) is added to it: the soil volume per
// unit face area that crossed it, so that the momentum can move with the same mass.
void vof_sweep(int axis, double dt, const double* const* c, const double* const* face_velocity,
               const double* const* cc, const double* dx, const double* dy,
               CellBox owned, double** c_new, RadialWeights radial = {}, double** face_soil = nullptr,
               DomainCells domain = {});

// Soil volume (per unit depth, per radian with radial weights) that the sweep of `axis` carries out
// of the domain through the boundary faces of the owned cells; negative for inflow. The same face
// fluxes as vof_sweep given the same `domain`, so that the soil in the domain plus the outflow of such
// sweeps is conserved. Along a periodic x there are no boundary faces: only the y sweep's count.
double boundary_outflow(int axis, double dt, const double* const* c, const double* const* face_velocity,
                        const double* dx, const double* dy, CellBox owned, DomainCells domain, RadialWeights radial = {});

// Soil volume (per unit depth) that the x sweep carries through face (i, j), between cells i and i + 1,
// positive along x: the F vof_sweep takes there, times the face's height.
double face_soil_volume_x(int i, int j, double dt, const double* const* c, const double* const* face_velocity,
                          const double* dx, const double* dy, DomainCells domain);

// cc = 1 where c > 0.5, else 0, on owned cells. Evaluate once per time step, before the first
// sweep. Any cc array holding 0/1 values works (cc > 0.5 selects the correction).
void dilatation_indicator(const double* const* c, CellBox owned, double** cc);

// Largest |u| dt / h over the faces bounding owned cells along `axis`, with h the smaller of the
// two adjacent cell widths (with radial weights, |u| dt r_f / (h r_c), the larger over the two
// cells: next to the axis a face at r = dr bounds a cell of centre dr/2). Local to this rank:
// reduce with MPI_MAX in parallel.
// With `region` (non-null), only faces with a region cell on either side count (region read on the
// owned cells and one ghost layer along `axis`); see soil_region below.
double max_sweep_courant(int axis, double dt, const double* const* face_velocity,
                         const double* dx, const double* dy, CellBox owned,
                         RadialWeights radial = {}, const double* const* region = nullptr);

// region_out = 1 on the owned cells with |in| > `floor` anywhere in their 3 x 3 box, else 0 (reads
// one ghost layer of `in`, corners included; floor 0 means any non-zero value). Applied to c and
// then n - 1 times to its own result (ghosts refreshed in between), it marks the cells within n
// cells of any soil.
// Why it bounds the sweeps: a face carries soil in a sweep only if its upwind cell holds soil, and a
// sweep at Courant number below 1 spreads soil by at most one cell along its axis, so in n sub-steps
// (2n sweeps) every upwind cell with soil lies within n cells of the soil at the start. Faces
// outside that region carry nothing, whatever their velocity, and need not limit the step: air far
// from the soil may move fast.
void soil_region(const double* const* in, CellBox owned, double** region_out, double floor = 0.0);

// Soil of at most this share of a cell, of either sign, is round-off: what a geometric sweep leaves
// where its strip grazes the interface (1e-20 to 1e-16), present on one rank layout and exactly 0 on
// another. The soil phase clears it after each advection (SoilPhase::clear_round_off_soil), so that
// "any soil" is the same region on every layout.
inline constexpr double round_off_soil = 1e-15;

}  // namespace granflow::interface
