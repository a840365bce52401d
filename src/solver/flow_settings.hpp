#pragma once
// Settings of the incompressible flow solver, filled from the case file.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "operators/convection_scheme.hpp"
#include "operators/face_interpolation.hpp"
#include "solver/boundary.hpp"
#include "solver/linear_solver.hpp"

namespace granflow {

// How the pressure step couples to momentum (see FlowSolver::cell_force).
enum class PressureCoupling { projection, piso, coupled };

struct NumericsSettings {
  PressureCoupling pressure_coupling = PressureCoupling::projection;
  ConvectionScheme convection = ConvectionScheme::quick;
  double blending = 0.7;        // central share of the blended scheme
  int outer_iterations = 3;     // PIMPLE outer iterations per step (properties updated in each)
  double outer_tolerance = 1e-5;  // stop the outer loop when the velocity changes less than this (relative)
  // Viscosity of a step's first outer iteration: from u^n (false), or the larger of that and the
  // viscosity from the velocity extrapolated to the end of the step (true, "look_ahead").
  bool look_ahead_viscosity = false;
  // Pressure in the yield stress of the outer iterations after the first: the last iterate's (false),
  // or the mean of the last two (true, "mean_of_last_two"), which cancels a two-iteration cycle of a
  // stiff cell's pressure and viscosity (docs/method.md). A converged step is the same either way.
  bool mean_viscosity_pressure = false;
  // Coupled solve only: the outer iterations after a step's first solved by Krylov iterations on the
  // first's factorisation (true, "first_factorisation"), or each by its own (false). The first's
  // Rhie-Chow mobilities are kept, so the continuity rows are the factorised ones and hold exactly
  // (LinearSolver::solve_by_last_factorisation); within a step the density does not change.
  bool reuse_first_factorisation = false;
  int krylov_iterations = 2;  // FGMRES iterations of each such later outer iteration
  // Coupled solve only: cells of air around the soil that the solve covers (0: the whole domain).
  // The region is rebuilt with this band when the soil comes closer than half of it to its edge.
  int air_band = 0;
  int pressure_correctors = 2;  // PISO pressure corrections per outer iteration
  bool momentum_predictor = true;
  bool transpose_stress = true;  // explicit div(mu grad(v)^T) term
  FaceViscosity face_viscosity = FaceViscosity::harmonic;
  // Velocity gradient at a wall: from the wall and the first cell (two_point, first order in the
  // flux, second in the solution), or quadratic through the wall and the first two cells, added as a
  // deferred correction (exact for parabolic profiles: Poiseuille flow is then exact).
  bool quadratic_wall_gradient = false;
  // Momentum moved with the mass the soil fraction's advection moves (true, "conservative"), or with
  // the cell's density times the face velocity (false, "advective"), which hands a cell that heavy
  // soil enters the velocity its light air had. Coupled solve only (the case file's default there);
  // needs a soil phase; a single fluid is the same either way.
  bool conservative_momentum = false;
  // Under the conservative transport, where the mixture's density at a cell's new fraction differs from
  // the mass the step's fluxes left there (the arctan mixture): the next step starts from the momentum
  // that keeps the kinetic energy it was carried with (true, "keep_kinetic_energy"), or at the carried
  // velocity (false, "keep_velocity"), which gains the jump's kinetic energy where soil spreads thin
  // (models/mixture/carried_momentum.hpp).
  bool density_jump_keeps_kinetic_energy = true;
};

struct FlowSettings {
  std::array<double, 3> gravity{0.0, 0.0, 0.0};  // z's is 0 on a planar mesh
  // With periodic x and gravity along x (a slope), the density of the ambient fluid whose weight along
  // x a mean pressure gradient carries, as the atmosphere's own hydrostatic pressure does on a real
  // slope: a periodic pressure cannot, and the air would otherwise fall along the slope without end.
  // The face force along x is then -dp/dx + (rho_f - ambient) g_x; 0 for a single fluid, which the
  // slope drives.
  double periodic_ambient_density = 0.0;
  BoundarySet boundaries{};
  NumericsSettings numerics{};
  LinearSolverSettings momentum_solver{"bcgs", "bjacobi", 1e-8, 1e-14, 1000};
  LinearSolverSettings pressure_solver{"cg", "hypre", 1e-10, 1e-14, 2000};
  // preonly applies its factorisation once whatever max_iterations says; the count is a Krylov
  // method's, for one chosen in the case or through PETSc's options.
  LinearSolverSettings coupled_solver{"preonly", "lu", 1e-10, 1e-14, 1000};
};

// Whether the velocity components share one momentum matrix in the segregated steps: not beside a slip
// wall (its condition differs by component), nor on the axis (the hoop stress is on the radial one's
// diagonal).
inline bool momentum_matrix_shared(const FlowSettings& s, bool axisymmetric, int dimension = 2) {
  if (axisymmetric) return false;
  for (Side side : sides_of_dimension(dimension))
    if (boundary(s.boundaries, side).kind == BoundaryKind::slip) return false;
  return true;
}

// The linear solvers a flow solver makes, by their PETSc options prefix: the coupled system's, or the
// segregated steps' momentum solvers (one where u and v share a matrix) and pressure solver.
inline std::vector<std::pair<std::string, LinearSolverSettings>> solvers_made(const FlowSettings& s,
                                                                             bool axisymmetric, int dimension = 2) {
  if (s.numerics.pressure_coupling == PressureCoupling::coupled) return {{"coupled", s.coupled_solver}};
  std::vector<std::pair<std::string, LinearSolverSettings>> made{{"momentum_x", s.momentum_solver}};
  if (!momentum_matrix_shared(s, axisymmetric, dimension)) {
    made.emplace_back("momentum_y", s.momentum_solver);
    if (dimension == 3) made.emplace_back("momentum_z", s.momentum_solver);
  }
  made.emplace_back("pressure", s.pressure_solver);
  return made;
}

}  // namespace granflow
