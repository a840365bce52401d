// The force the flow exerts on each side of the domain (FlowSolver::side_forces): what a wall, a
// barrier or a bed carries, e.g. the thrust of a landslide on a retaining wall.
#include <mpi.h>

#include <cmath>

#include "mesh/axis_views.hpp"
#include "mesh/obstacles.hpp"
#include "solver/cell_faces.hpp"
#include "solver/flow_solver.hpp"

namespace granflow {

// Each boundary face contributes the pressure on it and the viscous traction that the momentum
// equation applies there (momentum_equation.cpp), with the opposite sign: the side pushes the flow
// with exactly what the flow pushes it with.
//   - Pressure at a wall or slip face: p_P + rho_P g.(x_f - x_P), the pressure at which the face's
//     balanced force (-grad p + rho g) vanishes, as the wall faces of the momentum equation take it.
//     On a uniform mesh the face forces then sum exactly to the pressure on the sides plus the
//     weight, so at rest the sides carry the weight of what they hold.
//   - Viscous traction: the momentum equation's own terms, the implicit 2 mu_f (v_c - v_wall,c) / (h/2)
//     at a wall (normal component only at a slip side) with the quadratic wall gradient where the case
//     asks for it, and the lagged transpose part, which at a wall leaves mu_f (v_t - v_wall) / (h/2)
//     for the tangential component.
//   - At an atmosphere side: the boundary pressure the solver imposes and the lagged transpose part
//     of the viscous stress; the momentum carried through the side is not a force on it.
//   - On an obstacle (mesh/obstacles.hpp): each face between an open and a blocked cell, as a
//     static no-slip wall.
// The work the sides do on the flow per unit time is minus each face's force times the velocity on
// the face: a wall's or an inlet's own (held_velocity), at an atmosphere the face's normal velocity
// and the cell's tangential one. A static wall does none, an obstacle's included.
FlowSolver::WallForces FlowSolver::wall_forces() const {
  const auto& b = grid_.owned();
  const int dim = dimension_;
  const auto& g = settings_.gravity;
  const auto& num = settings_.numerics;
  const double stress_factor = num.transpose_stress ? 2.0 : 1.0;  // as in the momentum equation
  const ConstFieldArray p_array = local_read(grid_, *p_), rho_array = local_read(grid_, *rho_);
  const VolumeView p = p_array.volume(), rho = rho_array.volume();
  const AxisViews vel(grid_, vel_), face_mu(grid_, face_mu_), face_vel(grid_, face_);

  // (x, y, z) per side, in the order of Side, then the obstacles', then the sides' power.
  std::array<double, 22> force{};
  const BlockedView mask(grid_, blocked_);
  // The face of cell (i, j, k) on its side s, into f.
  auto add_face = [&](Side s, int i, int j, int k, const BoundaryCondition& bc, double* f) {
    if (is_blocked(mask.data(), i, j, k)) return;  // no flow there
    const FaceGeometry& fg = face_on(s);
    const int axis = fg.axis;
    const double sign = fg.sign;
    const double area = grid_.face_area(axis, i, j, k, sign);
    const double d_half = 0.5 * grid_.width(axis, index_along(axis, i, j, k));
    const double mu = on_face(face_mu.view, i, j, k, fg);
    // The lagged part of the viscous stress, on every kind of side (an open one included).
    if (num.transpose_stress)
      for (int c = 0; c < dim; ++c)
        if (c != axis) f[c] -= sign * mu * lagged_transpose_gradient(grid_, vel.view, i, j, k, fg, c) * area;
    if (bc.kind == BoundaryKind::atmosphere) {
      // The coupled solve's own boundary pressure where it held the face (coupled_step.cpp); else as
      // the segregated step takes it, from the present state.
      const auto& solved = solved_boundary_pressure_[static_cast<int>(s)];
      const size_t at = boundary_face_index(s, i, j, k);
      double pb = at < solved.size() ? solved[at] : std::nan("");
      if (std::isnan(pb)) pb = atmosphere_face_pressure(s, i, j, k, rho, vel.view, face_vel.view);
      f[axis] += pb * area * sign;
      return;
    }
    f[axis] += (p[k][j][i] + rho[k][j][i] * g[axis] * sign * d_half) * area * sign;
    // The implicit part, 2 mu (v_c - v_wall,c) / (h/2) (mu without the transpose stress), on every
    // component at a wall and on the normal one at a slip side, with the case's wall gradient.
    const auto held = held_velocity(bc, grid_, s, i, j, k);
    for (int c = 0; c < dim; ++c) {
      if (bc.kind == BoundaryKind::slip && c != axis) continue;  // no shear on a slip side
      const double wall = held[c];  // a wall's normal component is zero
      const double two_point = wall_gradient(grid_, vel.view[c], i, j, k, fg, wall, false);
      const double gradient = wall_gradient(grid_, vel.view[c], i, j, k, fg, wall, num.quadratic_wall_gradient);
      // stress_factor on the implicit two-point part, as assembled; the quadratic correction on top
      f[c] += stress_factor * mu * area * two_point + (c == axis ? stress_factor : 1.0) * mu * area * (gradient - two_point);
    }
  };
  // The face of cell (i, j, k) on side s, into the side's force, and its work rate into the power.
  double& power = force[21];
  auto add_side_face = [&](Side s, int i, int j, int k) {
    const auto& bc = boundary(settings_.boundaries, s);
    double* f = &force[3 * static_cast<int>(s)];
    const double before[3] = {f[0], f[1], f[2]};
    add_face(s, i, j, k, bc, f);
    if (is_blocked(mask.data(), i, j, k)) return;
    std::array<double, 3> on_side = held_velocity(bc, grid_, s, i, j, k);
    if (bc.kind == BoundaryKind::atmosphere) {
      for (int c = 0; c < dim; ++c) on_side[c] = vel.view[c][k][j][i];
      on_side[normal_axis(s)] = on_face(face_vel.view, i, j, k, face_on(s));
    }
    for (int c = 0; c < dim; ++c) power -= (f[c] - before[c]) * on_side[c];
  };
  // Each side's faces this rank holds, in the planar order of rows (west and east by row j, then south
  // and north by column i), layer by layer.
  const int n[3] = {grid_.nx(), grid_.ny(), grid_.nz()};
  for (int k = b.zs; k < b.ze(); ++k) {
    for (int j = b.ys; j < b.ye(); ++j)
      for (Side s : {Side::west, Side::east})
        if (grid_.owns_boundary(s))
          add_side_face(s, s == Side::west ? 0 : n[0] - 1, j, k);
    for (int i = b.xs; i < b.xe(); ++i)
      for (Side s : {Side::south, Side::north})
        if (grid_.owns_boundary(s))
          add_side_face(s, i, s == Side::south ? 0 : n[1] - 1, k);
  }
  for (Side s : {Side::front, Side::back})
    if (grid_.owns_boundary(s))
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          add_side_face(s, i, j, s == Side::front ? 0 : n[2] - 1);
  if (mask.data())
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i)
          for (const auto& fg : cell_faces(dim))
            if (is_blocked(mask.data(), i + fg.di, j + fg.dj, k + fg.dk)) add_face(fg.side, i, j, k, obstacle_wall, &force[18]);
  MPI_Allreduce(MPI_IN_PLACE, force.data(), int(force.size()), MPI_DOUBLE, MPI_SUM, grid_.comm());
  WallForces out;
  for (int s = 0; s < 6; ++s) out.sides[s] = {force[3 * s], force[3 * s + 1], force[3 * s + 2]};
  out.obstacle = {force[18], force[19], force[20]};
  out.power = force[21];
  return out;
}

std::array<std::array<double, 3>, 6> FlowSolver::side_forces() const { return wall_forces().sides; }

std::array<double, 3> FlowSolver::obstacle_force() const { return wall_forces().obstacle; }

}  // namespace granflow
