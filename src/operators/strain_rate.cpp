#include "operators/strain_rate.hpp"

#include <array>

namespace granflow {

// Central differences over the two neighbours along each axis.
rheology::StrainRate cell_strain_rate(const Grid& g, const double* const* u, const double* const* v, int i, int j) {
  const double hx = g.xc(i + 1) - g.xc(i - 1), hy = g.yc(j + 1) - g.yc(j - 1);
  const double dudx = (u[j][i + 1] - u[j][i - 1]) / hx, dudy = (u[j + 1][i] - u[j - 1][i]) / hy;
  const double dvdx = (v[j][i + 1] - v[j][i - 1]) / hx, dvdy = (v[j + 1][i] - v[j - 1][i]) / hy;
  // Axisymmetric: the hoop rate D_thth = u_r / r enters ||D|| and the Lode angle ([YS] Sec. 4).
  if (g.axisymmetric()) return rheology::axisymmetric_strain_rate(dudx, dvdy, 0.5 * (dudy + dvdx), u[j][i] / g.xc(i));
  return rheology::planar_strain_rate(dudx, dvdy, 0.5 * (dudy + dvdx));
}

namespace {

// Velocity gradient on a face, and the hoop rate where axisymmetric.
struct FaceGradient {
  double dudx, dvdx, dudy, dvdy, hoop;
};

FaceGradient face_gradient(const Grid& g, const double* const* u, const double* const* v, int axis, int i, int j) {
  const int in = i + (axis == 0), jn = j + (axis == 1);
  auto central_x = [&](const double* const* f, int ii, int jj) {
    return (f[jj][ii + 1] - f[jj][ii - 1]) / (g.xc(ii + 1) - g.xc(ii - 1));
  };
  auto central_y = [&](const double* const* f, int ii, int jj) {
    return (f[jj + 1][ii] - f[jj - 1][ii]) / (g.yc(jj + 1) - g.yc(jj - 1));
  };
  FaceGradient d{0.0, 0.0, 0.0, 0.0, 0.0};
  if (axis == 0) {
    const double h = g.xc(in) - g.xc(i);
    d.dudx = (u[j][in] - u[j][i]) / h;
    d.dvdx = (v[j][in] - v[j][i]) / h;
    d.dudy = 0.5 * (central_y(u, i, j) + central_y(u, in, j));
    d.dvdy = 0.5 * (central_y(v, i, j) + central_y(v, in, j));
    if (g.axisymmetric()) {
      const double r = g.xf(i);
      d.hoop = r > 0.0 ? 0.5 * (u[j][i] + u[j][in]) / r : d.dudx;  // u_r / r -> du_r/dr on the axis
    }
  } else {
    const double h = g.yc(jn) - g.yc(j);
    d.dudy = (u[jn][i] - u[j][i]) / h;
    d.dvdy = (v[jn][i] - v[j][i]) / h;
    d.dudx = 0.5 * (central_x(u, i, j) + central_x(u, i, jn));
    d.dvdx = 0.5 * (central_x(v, i, j) + central_x(v, i, jn));
    if (g.axisymmetric()) d.hoop = 0.5 * (u[j][i] + u[jn][i]) / g.xc(i);
  }
  return d;
}

rheology::StrainRate strain_rate_of(const Grid& g, const FaceGradient& d) {
  if (g.axisymmetric()) return rheology::axisymmetric_strain_rate(d.dudx, d.dvdy, 0.5 * (d.dudy + d.dvdx), d.hoop);
  return rheology::planar_strain_rate(d.dudx, d.dvdy, 0.5 * (d.dudy + d.dvdx));
}

}  // namespace

// Strain rate on the face between cell (i, j) and its neighbour at +1 along `axis` (either may be a
// ghost): the derivatives across the face from the two cells (compact), those along it as the mean
// of the two cells' central differences. This is the rate the face's viscous stress multiplies, so
// a plastic viscosity taken from it puts that stress on the yield surface. From the cells' central
// rates instead, in a layer whose velocity grows r-fold per cell the harmonic face mean transmits only
// 4 r / (1 + r)^2 of the yield stress (3/4 at r = 3): the layer slides below its strength.
rheology::StrainRate face_strain_rate(const Grid& g, const double* const* u, const double* const* v, int axis, int i,
                                      int j) {
  return strain_rate_of(g, face_gradient(g, u, v, axis, i, j));
}

// The flux's quadratic wall gradient (flow_solver.cpp) in the rate the wall face's viscosity is taken
// from: a plastic viscosity from the two-point rate times the quadratic gradient would put the wall's
// stress off the yield surface, by 4/3 for a plug sliding on the wall.
rheology::StrainRate quadratic_wall_strain_rate(const Grid& g, const double* const* u, const double* const* v, int axis,
                                                int i, int j, int sign, std::array<double, 2> wall_velocity,
                                                bool no_shear) {
  const int di = axis == 0 ? sign : 0, dj = axis == 1 ? sign : 0;
  // The wall face lies between the ghost and the cell on the low side, between the cell and the
  // ghost on the high side.
  const int il = sign < 0 ? i + di : i, jl = sign < 0 ? j + dj : j;
  FaceGradient d = face_gradient(g, u, v, axis, il, jl);
  const double h1 = axis == 0 ? g.dx(i) : g.dy(j);
  const double h2 = axis == 0 ? g.dx(i - di) : g.dy(j - dj);
  const double s1 = 0.5 * h1, s2 = h1 + 0.5 * h2;
  // Derivative along +axis of a component whose wall value is w, first two cells f1 and f2 inward.
  auto across = [&](double f1, double f2, double w) { return -sign * quadratic_wall_derivative(f1, f2, w, s1, s2); };
  const double du = across(u[j][i], u[j - dj][i - di], wall_velocity[0]);
  const double dv = across(v[j][i], v[j - dj][i - di], wall_velocity[1]);
  if (axis == 0) {
    if (g.axisymmetric() && g.xf(il) <= 0.0) d.hoop = du;  // on the axis u_r / r -> du_r/dr
    d.dudx = du;
    d.dvdx = no_shear ? 0.0 : dv;
  } else {
    d.dvdy = dv;
    d.dudy = no_shear ? 0.0 : du;
  }
  return strain_rate_of(g, d);
}

namespace {

using Index3 = std::array<int, 3>;

double value(const double* const* const* f, const Index3& p) { return f[p[2]][p[1]][p[0]]; }

// d f / d x_axis at the centre of cell p, central over its two neighbours along the axis.
double central(const Grid& g, const double* const* const* f, Index3 p, int axis) {
  const int n = p[axis];
  Index3 lo = p, hi = p;
  --lo[axis];
  ++hi[axis];
  return (value(f, hi) - value(f, lo)) / (g.centre(axis, n + 1) - g.centre(axis, n - 1));
}

// D = (G + G^T) / 2 of the velocity gradient G[c][d] = d v_c / d x_d ([YS] Eq. 4).
rheology::StrainRate symmetric_part(const double G[3][3]) {
  return {G[0][0], G[1][1], G[2][2], 0.5 * (G[0][1] + G[1][0]), 0.5 * (G[0][2] + G[2][0]), 0.5 * (G[1][2] + G[2][1])};
}

}  // namespace

rheology::StrainRate cell_strain_rate(const Grid& g, const VelocityArrays3& v, int i, int j, int k) {
  double G[3][3];
  for (int c = 0; c < 3; ++c)
    for (int d = 0; d < 3; ++d) G[c][d] = central(g, v[c], {i, j, k}, d);
  return symmetric_part(G);
}

namespace {
// The velocity gradient G[c][d] on the face between cell p and its neighbour at +1 along axis.
void face_gradient_3d(const Grid& g, const VelocityArrays3& v, int axis, const Index3& p, double G[3][3]) {
  Index3 q = p;
  ++q[axis];
  const double h = g.centre(axis, q[axis]) - g.centre(axis, p[axis]);
  for (int c = 0; c < 3; ++c)
    for (int d = 0; d < 3; ++d)
      G[c][d] = d == axis ? (value(v[c], q) - value(v[c], p)) / h : 0.5 * (central(g, v[c], p, d) + central(g, v[c], q, d));
}
}  // namespace

rheology::StrainRate face_strain_rate(const Grid& g, const VelocityArrays3& v, int axis, int i, int j, int k) {
  double G[3][3];
  face_gradient_3d(g, v, axis, {i, j, k}, G);
  return symmetric_part(G);
}

rheology::StrainRate quadratic_wall_strain_rate(const Grid& g, const VelocityArrays3& v, int axis, int i, int j, int k,
                                                int sign, std::array<double, 3> wall_velocity, bool no_shear) {
  const Index3 p{i, j, k};
  Index3 low = p, inner = p;  // the wall face lies after `low`; `inner` is the second cell from the wall
  if (sign < 0) --low[axis];
  inner[axis] -= sign;
  double G[3][3];
  face_gradient_3d(g, v, axis, low, G);
  const double h1 = g.width(axis, p[axis]), h2 = g.width(axis, inner[axis]);
  const double s1 = 0.5 * h1, s2 = h1 + 0.5 * h2;
  for (int c = 0; c < 3; ++c) {
    const double wall = wall_velocity[c];
    G[c][axis] = c != axis && no_shear
                     ? 0.0
                     : -sign * quadratic_wall_derivative(value(v[c], p), value(v[c], inner), wall, s1, s2);
  }
  return symmetric_part(G);
}

}  // namespace granflow
