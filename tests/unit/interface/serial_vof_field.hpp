// Single-block serial driver for the split PLIC advection (vof_sweep): owns c, the face velocities
// and the scratch arrays in the DMDA-like ghosted layout, applies simple boundary conditions and
// performs complete time steps. Used by the advection unit tests (it is theirs, not the library's), and as the reference for
// what the parallel solver must do around each sweep.
#pragma once

#include <functional>
#include <vector>

#include "models/interface/ghosted_array2.hpp"
#include "models/interface/vof_advection.hpp"

namespace granflow::interface {

// How ghost cells of c are filled.
enum class VofBoundary {
  ZeroGradient,  // copy of the nearest owned cell (corners included)
  Empty,         // c = 0 outside the domain
  Periodic,      // wrap-around in both directions
};

class SerialVofField {
 public:
  static constexpr int kGhosts = 2;

  // Uniform mesh of mx x my cells covering [x0, x0 + lx] x [y0, y0 + ly].
  SerialVofField(int mx, int my, double lx, double ly, double x0 = 0.0, double y0 = 0.0);
  // Graded mesh given by the owned cell widths; ghost widths mirror the boundary cells (so
  // VofBoundary::Periodic is only consistent when the end cells have matching widths).
  SerialVofField(const std::vector<double>& dx, const std::vector<double>& dy, double x0 = 0.0,
                 double y0 = 0.0);

  int mx() const { return mx_; }
  int my() const { return my_; }
  CellBox owned() const { return {0, 0, mx_, my_}; }

  // Geometry with global (ghost-capable) indices, i in [-2, mx+2).
  const double* dx() const { return dx_.data() + kGhosts; }
  const double* dy() const { return dy_.data() + kGhosts; }
  double x_face(int i) const { return xf_[i + kGhosts]; }  // west face of cell i, i <= mx+2
  double y_face(int j) const { return yf_[j + kGhosts]; }  // south face of row j, j <= my+2
  double x_centre(int i) const { return 0.5 * (x_face(i) + x_face(i + 1)); }
  double y_centre(int j) const { return 0.5 * (y_face(j) + y_face(j + 1)); }

  GhostedArray2& c() { return c_; }
  const GhostedArray2& c() const { return c_; }
  GhostedArray2& ux() { return ux_; }  // ux(i, j): x-velocity on the face between i and i+1
  GhostedArray2& uy() { return uy_; }  // uy(i, j): y-velocity on the face between j and j+1

  void set_boundary(VofBoundary bc) { bc_ = bc; }
  // Axisymmetric (x = r >= 0, y = z): radius-weighted x-fluxes and volumes; the stream function of
  // set_velocity_from_stream_function is then Stokes's (r u_r = dpsi/dz, r u_z = -dpsi/dr).
  void set_axisymmetric(bool on);
  RadialWeights radial() const;  // the sweeps' radius weights (none when planar)
  void fill_ghosts() { fill_ghosts(c_); }

  // Face velocities u = dpsi/dy, v = -dpsi/dx from psi sampled at cell corners: the discrete
  // divergence then telescopes to zero (to round-off), as Weymouth & Yue's conservation needs.
  void set_velocity_from_stream_function(const std::function<double(double, double)>& psi);

  // Largest per-sweep Courant number over both axes for time step dt.
  double max_courant(double dt) const;

  // One time step: ghosts, dilatation indicator, two sweeps (x then y on even steps, y then x on
  // odd steps), ghosts refilled between the sweeps.
  void step(double dt);
  long steps_taken() const { return steps_; }
  // c after the first sweep of the last step (with ghosts), e.g. to check intermediate bounds.
  const GhostedArray2& intermediate() const { return tmp_; }

  // Carries `count` soil materials with the soil (material_transport.hpp): material(k) is the share of
  // each cell's soil that is material k, set by the caller before the first step.
  void track_materials(int count);
  GhostedArray2& material(int k) { return materials_[k]; }
  const GhostedArray2& material(int k) const { return materials_[k]; }
  double material_volume(int k) const;  // sum of c m_k * cell volume over owned cells
  // Soils of their own densities (after track_materials; the base's first, then material k's): each
  // step then adds the soil's mass through each face (per unit face area, material_sweep's
  // face_density times F) to soil_mass_through(axis), which the caller zeroes.
  void set_material_densities(std::vector<double> densities);
  GhostedArray2& soil_mass_through(int axis) { return mass_through_[axis]; }

  double total_volume() const;  // sum of c * cell area (times r_c when axisymmetric) over owned cells
  double min_fraction() const;
  double max_fraction() const;

 private:
  void fill_ghosts(GhostedArray2& a) const;

  int mx_, my_;
  std::vector<double> dx_, dy_, xf_, yf_;
  GhostedArray2 c_, tmp_, cc_, ux_, uy_;
  VofBoundary bc_ = VofBoundary::ZeroGradient;
  std::vector<double> r_face_, r_centre_;  // empty in planar geometry
  std::vector<GhostedArray2> materials_, material_start_, material_tmp_;
  GhostedArray2 face_soil_;  // one sweep's soil volume per unit face area, with materials only
  std::vector<double> densities_;
  GhostedArray2 face_density_, mass_through_[2];
  void sweep(int axis, double dt, const GhostedArray2& from, GhostedArray2& to, std::vector<GhostedArray2>& m_from,
             std::vector<GhostedArray2>& m_to);
  double volume(int i, int j) const;
  long steps_ = 0;
};

}  // namespace granflow::interface
