#include "models/interface/vof_advection_3d.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "mesh/largest.hpp"
#include "models/interface/plic_geometry_3d.hpp"

namespace granflow::interface {

namespace {

using Index = std::array<int, 3>;  // i, j, k

inline double at(const double* const* const* a, const Index& p) { return a[p[2]][p[1]][p[0]]; }

// Soil fraction of the strip of relative width s beside the face the flow leaves the upwind cell p
// through (its high face along `axis` if to_high, else its low face).
double swept_fraction(const double* const* const* c, CellWidths3 w, const Index& p, int axis, bool to_high, double s,
                      DomainCells3 domain) {
  const double cu = at(c, p);
  // Pure cells (the vast majority) need no reconstruction, and give exact 0/1 fluxes.
  if (cu <= 0.0) return 0.0;
  if (cu >= 1.0) return 1.0;
  const int n[3] = {domain.nx, domain.ny, domain.nz};
  const int first_bounded = domain.periodic_x ? 1 : 0;  // beyond a periodic side: the other end's cells
  auto outside = [&](const Index& q) {
    for (int a = first_bounded; a < 3; ++a)
      if (q[a] < 0 || q[a] >= n[a]) return true;
    return false;
  };
  const bool bounded = domain.nx > 0;
  if (bounded && outside(p)) return cu;  // a boundary ghost: the mixture coming in, uniform
  Block3x3x3 b;
  double lo = 1.0, hi = 0.0;
  for (int dk = 0; dk < 3; ++dk)
    for (int dj = 0; dj < 3; ++dj)
      for (int di = 0; di < 3; ++di) {
        Index q{p[0] - 1 + di, p[1] - 1 + dj, p[2] - 1 + dk};
        if (bounded)  // the soil going on unchanged beyond a side
          for (int a = first_bounded; a < 3; ++a) q[a] = std::clamp(q[a], 0, n[a] - 1);
        const double v = at(c, q);
        b.c[dk][dj][di] = v;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
  for (int d = 0; d < 3; ++d) {
    b.dx[d] = w.dx[p[0] - 1 + d];
    b.dy[d] = w.dy[p[1] - 1 + d];
    b.dz[d] = w.dz[p[2] - 1 + d];
  }
  // A flat neighbourhood has no orientation (a plane would amplify round-off to O(1) within one
  // sweep), so take the plane parallel to the flow (donor cell), as in 2D.
  if (hi - lo < 1e-8) return cu;
  const Normal3 normal = myc_normal(b);
  if (normal.nx == 0.0 && normal.ny == 0.0 && normal.nz == 0.0) return cu;
  if (!(s > 0.0)) return cu;
  s = std::min(s, 1.0);
  std::array<double, 3> lower{-0.5, -0.5, -0.5}, upper{0.5, 0.5, 0.5};
  if (to_high) lower[axis] = 0.5 - s;
  else upper[axis] = -0.5 + s;
  return box_fraction(normal, plane_alpha(cu, normal), lower, upper);
}

// Signed soil volume per unit face area crossing the face between p and its +1 neighbour along the
// axis in dt (F), and the other phase's (G = u dt - F).
struct FaceFlux {
  double f = 0.0;
  double g = 0.0;
};

FaceFlux face_flux(const double* const* const* c, double u, double dt, CellWidths3 w, Index p, int axis,
                   DomainCells3 domain) {
  if (u == 0.0) return {};
  const double udt = u * dt;
  const double* h = w.along(axis);
  double frac;
  if (u > 0.0) {
    frac = swept_fraction(c, w, p, axis, true, udt / h[p[axis]], domain);
  } else {
    ++p[axis];
    frac = swept_fraction(c, w, p, axis, false, -udt / h[p[axis]], domain);
  }
  const double f = udt * frac;
  return {f, udt - f};
}

}  // namespace

// Weymouth & Yue's update in the form of the 2D sweep (vof_advection.cpp): cc = 0, c + (F_low -
// F_high)/h; cc = 1, c + (G_high - G_low)/h, so that pure regions stay exactly pure. Each face is
// visited once, x innermost whatever the axis (as the 2D y sweep walks its rows), and its fluxes
// added to the owned cells on both its sides.
void vof_sweep(int axis, double dt, const double* const* const* c, const double* const* const* u,
               const double* const* const* cc, CellWidths3 w, CellBox o, double*** c_new, DomainCells3 domain,
               double*** face_soil) {
  for (int k = o.zs; k < o.ze(); ++k)
    for (int j = o.ys; j < o.ye(); ++j)
      for (int i = o.xs; i < o.xe(); ++i) c_new[k][j][i] = c[k][j][i];
  const int start[3] = {o.xs, o.ys, o.zs}, end[3] = {o.xe(), o.ye(), o.ze()};
  int lo[3] = {start[0], start[1], start[2]};
  --lo[axis];  // the faces on the block's low side too
  const double* h = w.along(axis);
  for (int k = lo[2]; k < end[2]; ++k)
    for (int j = lo[1]; j < end[1]; ++j)
      for (int i = lo[0]; i < end[0]; ++i) {
        const double velocity = u[k][j][i];
        if (velocity == 0.0) continue;
        const Index low{i, j, k};
        const FaceFlux flux = face_flux(c, velocity, dt, w, low, axis, domain);
        if (face_soil) face_soil[k][j][i] += flux.f;
        const int s = low[axis];
        if (s >= start[axis])  // the face is the high face of the owned cell below it
          c_new[k][j][i] += cc[k][j][i] > 0.5 ? flux.g / h[s] : -flux.f / h[s];
        if (s + 1 < end[axis]) {  // and the low face of the owned cell above it
          Index high = low;
          ++high[axis];
          c_new[high[2]][high[1]][high[0]] += at(cc, high) > 0.5 ? -flux.g / h[s + 1] : flux.f / h[s + 1];
        }
      }
}

double boundary_outflow(int axis, double dt, const double* const* const* c, const double* const* const* u,
                        CellWidths3 w, CellBox o, DomainCells3 domain) {
  const int n[3] = {domain.nx, domain.ny, domain.nz};
  const int start[3] = {o.xs, o.ys, o.zs}, end[3] = {o.xe(), o.ye(), o.ze()};
  double out = 0.0;
  if (axis == 0 && domain.periodic_x) return out;
  // The low boundary's faces (index -1 along the axis) and the high one's (n - 1), where owned.
  for (const int s : {-1, n[axis] - 1}) {
    if (s == -1 ? start[axis] != 0 : end[axis] != n[axis]) continue;
    int lo[3] = {start[0], start[1], start[2]}, hi[3] = {end[0], end[1], end[2]};
    lo[axis] = s;
    hi[axis] = s + 1;
    const double sign = s == -1 ? -1.0 : 1.0;  // outward
    for (int k = lo[2]; k < hi[2]; ++k)
      for (int j = lo[1]; j < hi[1]; ++j)
        for (int i = lo[0]; i < hi[0]; ++i) {
          if (u[k][j][i] == 0.0) continue;
          const int t1 = axis == 0 ? 1 : 0, t2 = axis == 2 ? 1 : 2;  // the face's two tangential axes
          const Index p{i, j, k};
          const double area = w.along(t1)[p[t1]] * w.along(t2)[p[t2]];
          out += sign * face_flux(c, u[k][j][i], dt, w, p, axis, domain).f * area;
        }
  }
  return out;
}

double face_soil_volume_x(int i, int j, int k, double dt, const double* const* const* c,
                          const double* const* const* u, CellWidths3 w, DomainCells3 domain) {
  return face_flux(c, u[k][j][i], dt, w, Index{i, j, k}, 0, domain).f * w.dy[j] * w.dz[k];
}

void soil_region(const double* const* const* in, CellBox o, double*** region, double floor) {
  for (int k = o.zs; k < o.ze(); ++k)
    for (int j = o.ys; j < o.ye(); ++j)
      for (int i = o.xs; i < o.xe(); ++i) {
        bool any = false;
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) any = any || std::abs(in[k + dk][j + dj][i + di]) > floor;
        region[k][j][i] = any ? 1.0 : 0.0;
      }
}

void dilatation_indicator(const double* const* const* c, CellBox o, double*** cc) {
  for (int k = o.zs; k < o.ze(); ++k)
    for (int j = o.ys; j < o.ye(); ++j)
      for (int i = o.xs; i < o.xe(); ++i) cc[k][j][i] = c[k][j][i] > 0.5 ? 1.0 : 0.0;
}

double max_sweep_courant(int axis, double dt, const double* const* const* u, CellWidths3 w, CellBox o) {
  const double* h = w.along(axis);
  double largest = 0.0;
  for (int k = o.zs - (axis == 2); k < o.ze(); ++k)
    for (int j = o.ys - (axis == 1); j < o.ye(); ++j)
      for (int i = o.xs - (axis == 0); i < o.xe(); ++i) {
        const int s = axis == 0 ? i : (axis == 1 ? j : k);
        largest = larger_or_nan(largest, std::abs(u[k][j][i]) * dt / std::min(h[s], h[s + 1]));
      }
  return largest;
}

}  // namespace granflow::interface
