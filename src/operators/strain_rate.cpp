#include "operators/strain_rate.hpp"

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

// Strain rate on the face between cell (i, j) and its neighbour at +1 along `axis` (either may be a
// ghost): the derivatives across the face from the two cells (compact), those along it as the mean
// of the two cells' central differences. This is the rate the face's viscous stress multiplies, so
// a plastic viscosity taken from it puts that stress on the yield surface. From the cells' central
// rates instead, in a layer whose velocity grows r-fold per cell the harmonic face mean transmits only
// 4 r / (1 + r)^2 of the yield stress (3/4 at r = 3): the layer slides below its strength.
rheology::StrainRate face_strain_rate(const Grid& g, const double* const* u, const double* const* v, int axis, int i,
                                      int j) {
  const int in = i + (axis == 0), jn = j + (axis == 1);
  auto central_x = [&](const double* const* f, int ii, int jj) {
    return (f[jj][ii + 1] - f[jj][ii - 1]) / (g.xc(ii + 1) - g.xc(ii - 1));
  };
  auto central_y = [&](const double* const* f, int ii, int jj) {
    return (f[jj + 1][ii] - f[jj - 1][ii]) / (g.yc(jj + 1) - g.yc(jj - 1));
  };
  double dudx, dvdx, dudy, dvdy, hoop = 0.0;
  if (axis == 0) {
    const double h = g.xc(in) - g.xc(i);
    dudx = (u[j][in] - u[j][i]) / h;
    dvdx = (v[j][in] - v[j][i]) / h;
    dudy = 0.5 * (central_y(u, i, j) + central_y(u, in, j));
    dvdy = 0.5 * (central_y(v, i, j) + central_y(v, in, j));
    if (g.axisymmetric()) {
      const double r = g.xf(i);
      hoop = r > 0.0 ? 0.5 * (u[j][i] + u[j][in]) / r : dudx;  // u_r / r -> du_r/dr on the axis
    }
  } else {
    const double h = g.yc(jn) - g.yc(j);
    dudy = (u[jn][i] - u[j][i]) / h;
    dvdy = (v[jn][i] - v[j][i]) / h;
    dudx = 0.5 * (central_x(u, i, j) + central_x(u, i, jn));
    dvdx = 0.5 * (central_x(v, i, j) + central_x(v, i, jn));
    if (g.axisymmetric()) hoop = 0.5 * (u[j][i] + u[jn][i]) / g.xc(i);
  }
  if (g.axisymmetric()) return rheology::axisymmetric_strain_rate(dudx, dvdy, 0.5 * (dudy + dvdx), hoop);
  return rheology::planar_strain_rate(dudx, dvdy, 0.5 * (dudy + dvdx));
}

}  // namespace granflow
