// Soil materials carried with the soil: each material's share m of a cell's soil moves with the soil
// volume that the geometric VoF sweep moved through each face (vof_sweep's face_soil), so that a
// material goes where its soil goes, its volume is conserved as c's is, and its share stays in [0, 1].
// Same data layouts as vof_advection.hpp and vof_advection_3d.hpp.
#pragma once

#include "models/interface/vof_advection.hpp"
#include "models/interface/vof_advection_3d.hpp"

namespace granflow::interface {

inline constexpr int max_materials = 16;  // the base's included

// A cell with less soil than this has no shares that mean anything: they are q / c of round-off.
inline constexpr double no_soil = 1e-9;

// One directional sweep, after vof_sweep of the same axis took c to c_new and recorded F, the soil
// volume per unit face area that crossed each face in this sweep (face_soil, zeroed before it). For
// each of `count` materials (m[k]: its share of each cell's soil; the base material, not stored, holds
// the rest), with q = c m its volume fraction,
//   q_new = q + (F_low m_low - F_high m_high)/h + cc m0 (u_high - u_low) dt/h,   m_new = q_new / c_new.
// The shares a face carries are the donor's (upwind cell's), corrected towards the acceptor's by a
// limited slope (superbee, a TVD face value), the base's likewise, then scaled to add up to 1: the soil
// through a face is shared out whole. cc and m0 (the shares at the start of the step)
// are held over both sweeps, so that the dilatation terms of a divergence-free velocity cancel over
// the step as they do for c, and sum(q V) is conserved to round-off. A cell the soil leaves
// (c_new <= 0) keeps its shares; round-off in a sliver is clipped to [0, 1]. Radial weights as in
// vof_sweep. Reads c and m on owned cells and two ghost layers along `axis`, F on the faces bounding
// owned cells along it. count < max_materials.
//
// With `density` (count + 1 entries: the base's, then the stored materials'), also sets face_density on
// each face bounding owned cells along the axis that carried soil: the density of the soil it carried,
// sum_k rho_k s_k over the face's shares s_k. F face_density is then the soil's mass through the face,
// which the materials' volumes moved: a mixture of soils of several densities conserves its mass.
void material_sweep(int axis, double dt, const double* const* c, const double* const* c_new, int count,
                    const double* const* const* m, const double* const* const* m0, const double* const* face_velocity,
                    const double* const* face_soil, const double* const* cc, const double* dx, const double* dy,
                    CellBox owned, double** const* m_new, RadialWeights radial = {}, const double* density = nullptr,
                    double** face_density = nullptr);

// The same on a mesh of layers (arrays [k][j][i], axis 0, 1 or 2), after the 3D vof_sweep of the same
// axis recorded face_soil: the same face shares and the same update, cell by cell, as the planar sweep
// (a layer-independent field is swept as the planar one is, layer by layer).
void material_sweep_3d(int axis, double dt, const double* const* const* c, const double* const* const* c_new,
                       int count, const double* const* const* const* m, const double* const* const* const* m0,
                       const double* const* const* face_velocity, const double* const* const* face_soil,
                       const double* const* const* cc, CellWidths3 widths, CellBox owned, double*** const* m_new,
                       const double* density = nullptr, double*** face_density = nullptr);

}  // namespace granflow::interface
