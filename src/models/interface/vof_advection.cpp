#include "models/interface/vof_advection.hpp"

#include <algorithm>
#include <cmath>

#include "mesh/largest.hpp"
#include "models/interface/plic_geometry.hpp"

namespace granflow::interface {

namespace {

// Width, relative to the cell's, of the strip beside a face of an axisymmetric cell whose volume is
// the face's swept volume r_f |u| dt: relative width sigma = |u| dt / dx at the face's radius, rho =
// r_c / dx. The strip by the outer face lies at smaller radii, so it is wider than sigma; by the
// inner face, narrower. The roots are taken in the form free of cancellation.
inline double weighted_strip_width(double rho, bool to_high, double sigma) {
  if (to_high) {
    const double rf = rho + 0.5;  // s (rf - s/2) = rf sigma
    return 2.0 * rf * sigma / (rf + std::sqrt(std::max(rf * rf - 2.0 * rf * sigma, 0.0)));
  }
  const double rf = rho - 0.5;  // s (rf + s/2) = rf sigma
  return rf > 0.0 ? 2.0 * rf * sigma / (rf + std::sqrt(rf * rf + 2.0 * rf * sigma)) : 0.0;
}

// Soil fraction of the strip of relative width s next to the face the flow leaves through, in the
// upwind cell (i, j). `to_high` is true when that face is the cell's east/north face. With rho > 0
// (an axisymmetric cell, rho = r_c / dx) the line and the fraction are the radius-weighted ones, and
// an x-strip's width is that of the face's swept volume, so that the soil the strip carries is the
// soil it takes from the cell: no cell gives away more than it holds.
inline double swept_fraction(const double* const* c, const double* dx, const double* dy, int i,
                             int j, int axis, bool to_high, double s, DomainCells domain, double rho) {
  const double cu = c[j][i];
  // Pure cells (the vast majority) need no reconstruction, and give exact 0/1 fluxes.
  if (cu <= 0.0) return 0.0;
  if (cu >= 1.0) return 1.0;
  auto outside = [&](int ii, int jj) {
    return jj < 0 || jj >= domain.ny || (!domain.periodic_x && (ii < 0 || ii >= domain.nx));
  };
  if (domain.nx > 0 && outside(i, j)) return cu;  // a boundary ghost: the mixture coming in, uniform
  Block3x3 block = gather_block(c, dx, dy, i, j);
  if (domain.nx > 0) {
    for (int r = 0; r < 3; ++r)
      for (int q = 0; q < 3; ++q)
        if (outside(i - 1 + q, j - 1 + r))
          block.c[r][q] = c[std::clamp(j - 1 + r, 0, domain.ny - 1)]
                           [domain.periodic_x ? i - 1 + q : std::clamp(i - 1 + q, 0, domain.nx - 1)];
  }
  // A flat neighbourhood has no orientation (a line would amplify round-off to O(1) within one
  // sweep), so take the line parallel to the flow (donor cell).
  const bool weighted = rho >= 0.5;  // a ghost across the axis (rho < 0) is never a donor: u = 0 there
  const CellLine line = cell_line(block, weighted ? rho : 0.0);
  if (!line.found) return cu;
  if (weighted && axis == 0) s = weighted_strip_width(rho, to_high, s);
  if (!(s > 0.0)) return cu;
  s = std::min(s, 1.0);
  const double lo = to_high ? 0.5 - s : -0.5;
  const double hi = to_high ? 0.5 : -0.5 + s;
  if (weighted)
    return axis == 0 ? weighted_rectangle_fraction(line.n, line.alpha, rho, lo, hi, -0.5, 0.5)
                     : weighted_rectangle_fraction(line.n, line.alpha, rho, -0.5, 0.5, lo, hi);
  return axis == 0 ? rectangle_fraction(line.n, line.alpha, lo, hi, -0.5, 0.5)
                   : rectangle_fraction(line.n, line.alpha, -0.5, 0.5, lo, hi);
}

// rho = r_c / dx of cell i, or 0 on a planar mesh.
inline double scaled_radius(RadialWeights radial, const double* dx, int i) {
  return radial.centre != nullptr ? radial.centre[i] / dx[i] : 0.0;
}

// Signed soil volume per unit face area crossing face (i, j) in dt (F), and its complement
// G = u dt - F (the volume of the other phase).
struct FaceFlux {
  double f = 0.0;
  double g = 0.0;
};

inline FaceFlux face_flux_x(const double* const* c, double u, double dt, const double* dx,
                            const double* dy, int i, int j, DomainCells domain, RadialWeights radial) {
  if (u == 0.0) return {};
  const double udt = u * dt;
  const double frac =
      u > 0.0 ? swept_fraction(c, dx, dy, i, j, 0, true, udt / dx[i], domain, scaled_radius(radial, dx, i))
              : swept_fraction(c, dx, dy, i + 1, j, 0, false, -udt / dx[i + 1], domain, scaled_radius(radial, dx, i + 1));
  const double f = udt * frac;
  return {f, udt - f};
}

inline FaceFlux face_flux_y(const double* const* c, double v, double dt, const double* dx,
                            const double* dy, int i, int j, DomainCells domain, RadialWeights radial) {
  if (v == 0.0) return {};
  const double vdt = v * dt;
  const double rho = scaled_radius(radial, dx, i);
  const double frac = v > 0.0 ? swept_fraction(c, dx, dy, i, j, 1, true, vdt / dy[j], domain, rho)
                              : swept_fraction(c, dx, dy, i, j + 1, 1, false, -vdt / dy[j + 1], domain, rho);
  const double f = vdt * frac;
  return {f, vdt - f};
}

}  // namespace

// Weymouth & Yue's update c + (F_low - F_high)/h + cc (u_high - u_low) dt/h is applied in the
// algebraically identical form
//   cc = 0:  c_new = c + (F_low - F_high)/h
//   cc = 1:  c_new = c + (G_high - G_low)/h,   G = u dt - F,
// so that full cells surrounded by full cells (and empty by empty) stay exactly 1 (0) instead of
// drifting by round-off, which keeps the pure-cell fast path effective.
void vof_sweep(int axis, double dt, const double* const* c, const double* const* u,
               const double* const* cc, const double* dx, const double* dy, CellBox o,
               double** c_new, RadialWeights radial, double** face_soil, DomainCells domain) {
  const int i_end = o.xs + o.xm;
  const int j_end = o.ys + o.ym;
  if (axis == 0) {
    const bool weighted = radial.face != nullptr;
    for (int j = o.ys; j < j_end; ++j) {
      FaceFlux low = face_flux_x(c, u[j][o.xs - 1], dt, dx, dy, o.xs - 1, j, domain, radial);
      if (face_soil) face_soil[j][o.xs - 1] += low.f;
      double r_low = weighted ? radial.face[o.xs - 1] : 1.0;
      for (int i = o.xs; i < i_end; ++i) {
        const FaceFlux high = face_flux_x(c, u[j][i], dt, dx, dy, i, j, domain, radial);
        if (face_soil) face_soil[j][i] += high.f;
        const double r_high = weighted ? radial.face[i] : 1.0;
        const double h = weighted ? dx[i] * radial.centre[i] : dx[i];
        c_new[j][i] = cc[j][i] > 0.5 ? c[j][i] + (r_high * high.g - r_low * low.g) / h
                                     : c[j][i] + (r_low * low.f - r_high * high.f) / h;
        low = high;
        r_low = r_high;
      }
    }
    return;
  }
  // y sweep: rows are contiguous in memory, so accumulate face contributions row by row rather
  // than walking columns (no scratch storage needed).
  for (int j = o.ys; j < j_end; ++j)
    for (int i = o.xs; i < i_end; ++i) c_new[j][i] = c[j][i];
  for (int jf = o.ys - 1; jf < j_end; ++jf) {
    const bool below_owned = jf >= o.ys;
    const bool above_owned = jf + 1 < j_end;
    for (int i = o.xs; i < i_end; ++i) {
      const double v = u[jf][i];
      if (v == 0.0) continue;
      const FaceFlux fl = face_flux_y(c, v, dt, dx, dy, i, jf, domain, radial);
      if (face_soil) face_soil[jf][i] += fl.f;
      if (below_owned) c_new[jf][i] += cc[jf][i] > 0.5 ? fl.g / dy[jf] : -fl.f / dy[jf];
      if (above_owned)
        c_new[jf + 1][i] += cc[jf + 1][i] > 0.5 ? -fl.g / dy[jf + 1] : fl.f / dy[jf + 1];
    }
  }
}

double boundary_outflow(int axis, double dt, const double* const* c, const double* const* u, const double* dx,
                        const double* dy, CellBox o, DomainCells domain, RadialWeights radial) {
  const int nx = domain.nx, ny = domain.ny;
  double out = 0.0;
  const int i_end = o.xs + o.xm, j_end = o.ys + o.ym;
  if (axis == 0) {
    if (domain.periodic_x) return 0.0;
    const bool weighted = radial.face != nullptr;
    for (int j = o.ys; j < j_end; ++j) {
      if (o.xs == 0) out -= (weighted ? radial.face[-1] : 1.0) * face_flux_x(c, u[j][-1], dt, dx, dy, -1, j, domain, radial).f * dy[j];
      if (i_end == nx)
        out += (weighted ? radial.face[nx - 1] : 1.0) * face_flux_x(c, u[j][nx - 1], dt, dx, dy, nx - 1, j, domain, radial).f * dy[j];
    }
    return out;
  }
  for (int i = o.xs; i < i_end; ++i) {
    const double area = dx[i] * (radial.centre != nullptr ? radial.centre[i] : 1.0);
    if (o.ys == 0) out -= face_flux_y(c, u[-1][i], dt, dx, dy, i, -1, domain, radial).f * area;
    if (j_end == ny) out += face_flux_y(c, u[ny - 1][i], dt, dx, dy, i, ny - 1, domain, radial).f * area;
  }
  return out;
}

double face_soil_volume_x(int i, int j, double dt, const double* const* c, const double* const* u, const double* dx,
                          const double* dy, DomainCells domain) {
  return face_flux_x(c, u[j][i], dt, dx, dy, i, j, domain, {}).f * dy[j];
}

void dilatation_indicator(const double* const* c, CellBox o, double** cc) {
  for (int j = o.ys; j < o.ys + o.ym; ++j)
    for (int i = o.xs; i < o.xs + o.xm; ++i) cc[j][i] = c[j][i] > 0.5 ? 1.0 : 0.0;
}

double max_sweep_courant(int axis, double dt, const double* const* u, const double* dx,
                         const double* dy, CellBox o, RadialWeights radial, const double* const* region) {
  double cmax = 0.0;
  if (axis == 0) {
    for (int j = o.ys; j < o.ys + o.ym; ++j)
      for (int i = o.xs - 1; i < o.xs + o.xm; ++i) {
        if (region != nullptr && region[j][i] == 0.0 && region[j][i + 1] == 0.0) continue;
        double h = std::min(dx[i], dx[i + 1]);
        // The face's swept volume relative to each neighbour's volume: r_f / r_c, the larger of
        // the two (the inner cell's, whose centre lies at the smaller radius).
        if (radial.face != nullptr && radial.centre[i] > 0.0)
          h = std::min(dx[i] * radial.centre[i], dx[i + 1] * radial.centre[i + 1]) / radial.face[i];
        cmax = larger_or_nan(cmax, std::abs(u[j][i]) * dt / h);
      }
  } else {
    for (int j = o.ys - 1; j < o.ys + o.ym; ++j)
      for (int i = o.xs; i < o.xs + o.xm; ++i) {
        if (region != nullptr && region[j][i] == 0.0 && region[j + 1][i] == 0.0) continue;
        cmax = larger_or_nan(cmax, std::abs(u[j][i]) * dt / std::min(dy[j], dy[j + 1]));
      }
  }
  return cmax;
}

void soil_region(const double* const* in, CellBox o, double** region, double floor) {
  for (int j = o.ys; j < o.ys + o.ym; ++j)
    for (int i = o.xs; i < o.xs + o.xm; ++i) {
      bool any = false;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) any = any || std::abs(in[j + dj][i + di]) > floor;
      region[j][i] = any ? 1.0 : 0.0;
    }
}

}  // namespace granflow::interface
