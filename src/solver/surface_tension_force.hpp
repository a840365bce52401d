#pragma once
// The surface tension of the soil-air interface as the flow solver's face source (FlowSolver::
// face_source): the curvature of a smoothed soil fraction, then sigma kappa_f (c_N - c_P) / d on each
// interior face (models/interface/surface_tension.hpp). The domain's wall sides hold the interface at
// the contact angle theta through the ghosts of the smoothed fraction; the other sides and obstacles'
// walls mirror it, so the interface meets them at a right angle.
#include <memory>

#include "mesh/field.hpp"
#include "mesh/grid.hpp"
#include "solver/boundary.hpp"
#include "solver/flow_solver.hpp"

namespace granflow {

class SurfaceTensionForce {
 public:
  // sigma: N/m, > 0; contact_angle_deg: theta at the wall sides, degrees in (0, 180) (90: the mirror);
  // blocked: the mask of blocked cells (obstacles), or null.
  SurfaceTensionForce(const Grid& grid, double sigma, double contact_angle_deg, const BoundarySet& boundaries,
                      const Field* blocked);

  // The face source of the flow from the soil fraction c (its ghosts current): fills
  // flow.face_source(), which the first call enables.
  void fill(const Field& soil_fraction, FlowSolver& flow);
  // The interface's energy at the last fill, sigma times its length (area on a mesh of layers, per
  // radian on an axisymmetric one): sigma times the integral of |grad(c~)| over the open cells, which
  // through a smoothed interface is its length. J per metre depth. Collective.
  double surface_energy() const;
  // The capillary time-step limit on this mesh for phases of these densities (s).
  double time_step_limit(double density_a, double density_b) const;

  // Passes of the 1-2-1 filter that smooth c before its normal is taken. Two spread the interface over
  // about five cells: a smooth enough normal for the curvature, yet local.
  static constexpr int smoothing_passes = 2;

 private:
  void smooth(const Field& from, Field& to) const;  // one pass; `to` with its ghosts
  void fill_ghosts(Field& f) const;                 // of the smoothed fraction: the contact angle, or the mirror
  void compute_curvature(const Field& smoothed);

  const Grid& grid_;
  double sigma_;
  double cot_theta_;  // cot of the contact angle; 0 for a right angle
  BoundarySet boundaries_;
  const Field* blocked_;
  std::unique_ptr<Field> smoothed_[2], curvature_, gradient_magnitude_;  // |grad c~| at the cell, kappa's weight
};

}  // namespace granflow
