// The force the flow exerts on each side of the domain (FlowSolver::side_forces): what a wall, a
// barrier or a bed carries, e.g. the thrust of a landslide on a retaining wall.
#include <mpi.h>

#include <cmath>

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
std::array<double, 10> FlowSolver::wall_force_sums() const {
  const auto& b = grid_.owned();
  const int nx = grid_.nx(), ny = grid_.ny();
  const auto& g = settings_.gravity;
  const auto& num = settings_.numerics;
  const double stress_factor = num.transpose_stress ? 2.0 : 1.0;  // as in the momentum equation
  ConstFieldArray p = local_read(grid_, *p_), rho = local_read(grid_, *rho_);
  ConstFieldArray u = local_read(grid_, *vel_[0]), v = local_read(grid_, *vel_[1]);
  ConstFieldArray fmx = local_read(grid_, *face_mu_[0]), fmy = local_read(grid_, *face_mu_[1]);
  ConstFieldArray fvx = local_read(grid_, *face_[0]), fvy = local_read(grid_, *face_[1]);
  const double* const* vel[2] = {u.data(), v.data()};

  std::array<double, 10> force{};  // (x, y) per side, in the order of Side, then the obstacles'
  const BlockedView mask(grid_, blocked_);
  // The face of cell (i, j) on its side s, into f.
  auto add_face = [&](Side s, int i, int j, const BoundaryCondition& bc, double* f) {
    if (is_blocked(mask.data(), i, j)) return;  // no flow there
    const FaceGeometry& fg = face_on(s);
    const int axis = fg.axis;
    const double sign = fg.sign;
    const double area = grid_.face_area(axis, i, j, sign);
    const double d_half = 0.5 * (axis == 0 ? grid_.dx(i) : grid_.dy(j));
    const double mu = axis == 0 ? fmx[j][sign > 0 ? i : i - 1] : fmy[sign > 0 ? j : j - 1][i];
    // The lagged part of the viscous stress, on every kind of side (an open one included).
    if (num.transpose_stress)
      for (int c = 0; c < 2; ++c)
        if (c != axis) f[c] -= sign * mu * lagged_transpose_gradient(grid_, vel, i, j, fg, c) * area;
    if (bc.kind == BoundaryKind::atmosphere) {
      // The coupled solve's own boundary pressure where it held the face (coupled_step.cpp); else as
      // the segregated step takes it, from the present state.
      const auto& solved = solved_boundary_pressure_[static_cast<int>(s)];
      const size_t along = size_t(axis == 0 ? j : i);
      double pb = along < solved.size() ? solved[along] : std::nan("");
      if (std::isnan(pb)) pb = atmosphere_face_pressure(s, i, j, rho.data(), u.data(), v.data(), fvx.data(), fvy.data());
      f[axis] += pb * area * sign;
      return;
    }
    f[axis] += (p[j][i] + rho[j][i] * g[axis] * sign * d_half) * area * sign;
    // The implicit part, 2 mu (v_c - v_wall,c) / (h/2) (mu without the transpose stress), on both
    // components at a wall and on the normal one at a slip side, with the case's wall gradient.
    for (int c = 0; c < 2; ++c) {
      if (bc.kind == BoundaryKind::slip && c != axis) continue;  // no shear on a slip side
      const double wall = c == axis ? 0.0 : bc.wall_velocity[c];
      const double two_point = wall_gradient(grid_, vel[c], i, j, fg, wall, false);
      const double gradient = wall_gradient(grid_, vel[c], i, j, fg, wall, num.quadratic_wall_gradient);
      // stress_factor on the implicit two-point part, as assembled; the quadratic correction on top
      f[c] += stress_factor * mu * area * two_point + (c == axis ? stress_factor : 1.0) * mu * area * (gradient - two_point);
    }
  };
  auto on_side = [&](Side s) { return &force[2 * static_cast<int>(s)]; };
  for (int j = b.ys; j < b.ye(); ++j) {
    if (grid_.owns_boundary(Side::west)) add_face(Side::west, 0, j, boundary(settings_.boundaries, Side::west), on_side(Side::west));
    if (grid_.owns_boundary(Side::east)) add_face(Side::east, nx - 1, j, boundary(settings_.boundaries, Side::east), on_side(Side::east));
  }
  for (int i = b.xs; i < b.xe(); ++i) {
    if (b.ys == 0) add_face(Side::south, i, 0, boundary(settings_.boundaries, Side::south), on_side(Side::south));
    if (b.ye() == ny) add_face(Side::north, i, ny - 1, boundary(settings_.boundaries, Side::north), on_side(Side::north));
  }
  if (mask.data())
    for (int j = b.ys; j < b.ye(); ++j)
      for (int i = b.xs; i < b.xe(); ++i)
        for (const auto& fg : faces_of_cell)
          if (is_blocked(mask.data(), i + fg.di, j + fg.dj)) add_face(fg.side, i, j, obstacle_wall, &force[8]);
  MPI_Allreduce(MPI_IN_PLACE, force.data(), 10, MPI_DOUBLE, MPI_SUM, grid_.comm());
  return force;
}

FlowSolver::WallForces FlowSolver::wall_forces() const {
  const auto force = wall_force_sums();
  WallForces out;
  for (int s = 0; s < 4; ++s) out.sides[s] = {force[2 * s], force[2 * s + 1]};
  out.obstacle = {force[8], force[9]};
  return out;
}

std::array<std::array<double, 2>, 4> FlowSolver::side_forces() const { return wall_forces().sides; }

std::array<double, 2> FlowSolver::obstacle_force() const { return wall_forces().obstacle; }

}  // namespace granflow
