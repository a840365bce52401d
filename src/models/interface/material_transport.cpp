#include "models/interface/material_transport.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace granflow::interface {

namespace {

// Superbee's limiter (Roe 1985): the most compressive of the TVD limiters, which keeps a contact
// between two materials a few cells wide where the donor's share alone would let it spread.
inline double superbee(double r) { return std::max({0.0, std::min(2.0 * r, 1.0), std::min(r, 2.0)}); }

using Shares = std::array<double, max_materials>;

// Cell (i, j, k) of a planar array [j][i] (whose one layer is k = 0) or of a volume [k][j][i]: one
// sweep serves both.
inline double at(const double* const* a, int i, int j, int) { return a[j][i]; }
inline double& at(double** a, int i, int j, int) { return a[j][i]; }
inline double at(const double* const* const* a, int i, int j, int k) { return a[k][j][i]; }
inline double& at(double*** a, int i, int j, int k) { return a[k][j][i]; }

// material_sweep on arrays of either layout (In: read, Out: written); `width` holds the cell widths
// along the axis.
template <class In, class Out>
void sweep_shares(int axis, double dt, In c, In c_new, int count, const In* m, const In* m0, In u, In face_soil, In cc,
                  const double* width, CellBox o, const Out* m_new, RadialWeights radial, const double* density,
                  Out face_density) {
  const bool weighted = axis == 0 && radial.face != nullptr;
  const int di = axis == 0, dj = axis == 1, dk = axis == 2;
  auto along = [axis](int i, int j, int k) { return axis == 0 ? i : (axis == 1 ? j : k); };
  // Shares of cell (i, j, k): the stored materials', then the base's (the rest).
  auto shares_of = [&](int i, int j, int k, Shares& s) {
    double rest = 1.0;
    for (int n = 0; n < count; ++n) rest -= (s[n] = at(m[n], i, j, k));
    s[count] = rest;
  };
  // The shares the soil crossing the face after cell (i, j, k) carries, summing to 1. Where the cell
  // upstream of the donor or the acceptor holds no soil, its shares mean nothing and the donor's own
  // are taken.
  auto face_shares = [&](int i, int j, int k, double f, Shares& s) {
    const int dir = f > 0.0 ? 1 : -1;
    const int id = f > 0.0 ? i : i + di, jd = f > 0.0 ? j : j + dj, kd = f > 0.0 ? k : k + dk;  // donor
    const int ia = id + dir * di, ja = jd + dir * dj, ka = kd + dir * dk;                        // acceptor
    const int iu = id - dir * di, ju = jd - dir * dj, ku = kd - dir * dk;                        // upstream of the donor
    shares_of(id, jd, kd, s);
    if (at(c, ia, ja, ka) <= no_soil || at(c, iu, ju, ku) <= no_soil) return;
    Shares a, up;
    shares_of(ia, ja, ka, a);
    shares_of(iu, ju, ku, up);
    // The share of the donor's soil that leaves through the face: the soil's own Courant number (the
    // face's swept volume over the donor's soil, radius-weighted in an axisymmetric x sweep). A donor
    // that gives all its soil away can give only its own shares (the TVD bound 1 - sigma).
    const double swept = std::abs(f) * (weighted ? radial.face[i] / radial.centre[id] : 1.0);
    const double courant = std::min(swept / (at(c, id, jd, kd) * width[along(id, jd, kd)]), 1.0);
    // Each material's face share limited by its own slope (superbee is continuous in the shares, so
    // round-off stays round-off), then the shares scaled to add up to 1: the soil through a face is
    // shared out whole. With two materials the scaling is exact (both are limited alike); with three or
    // more it can take a share a little past its bound, which the cell then clips (docs/method.md).
    // One limiter for all, the most restrictive, kept the sum but not the rank-independence: a jump of
    // round-off in one material set the others' limiter at random.
    const double keep = 0.5 * (1.0 - courant);
    Shares limited;
    double sum = 0.0;
    for (int n = 0; n <= count; ++n) {
      const double jump = a[n] - s[n];
      limited[n] = jump != 0.0 ? s[n] + keep * superbee((s[n] - up[n]) / jump) * jump : s[n];
      sum += limited[n];  // each between the donor's and the acceptor's, in [0, 1]
    }
    if (!(sum > 0.5)) return;  // shares swapping places between donor and acceptor: the donor's
    for (int n = 0; n <= count; ++n) s[n] = limited[n] / sum;
  };
  // Through the face after cell (i, j, k) along the axis: each material's volume (per unit face area,
  // times the face's radius).
  auto carried = [&](int i, int j, int k, Shares& out) {
    const double f = at(face_soil, i, j, k);
    if (f == 0.0) {
      out.fill(0.0);
      return;
    }
    face_shares(i, j, k, f, out);
    if (face_density) {
      double rho = 0.0;
      for (int n = 0; n < count; ++n) rho += out[n] * density[n + 1];
      at(face_density, i, j, k) = rho + out[count] * density[0];
    }
    const double volume = (weighted ? radial.face[i] : 1.0) * f;
    for (int n = 0; n < count; ++n) out[n] *= volume;
  };
  auto velocity = [&](int i, int j, int k) { return (weighted ? radial.face[i] : 1.0) * at(u, i, j, k); };
  Shares low, high;
  for (int k = o.zs; k < o.ze(); ++k)
    for (int j = o.ys; j < o.ye(); ++j)
      for (int i = o.xs; i < o.xe(); ++i) {
        const double h = width[along(i, j, k)] * (weighted ? radial.centre[i] : 1.0);
        carried(i - di, j - dj, k - dk, low);
        carried(i, j, k, high);
        const double dilatation =
            at(cc, i, j, k) > 0.5 ? (velocity(i, j, k) - velocity(i - di, j - dj, k - dk)) * dt / h : 0.0;
        const double c_old = at(c, i, j, k), c_now = at(c_new, i, j, k);
        double sum = 0.0;
        for (int n = 0; n < count; ++n) {
          const double q = c_old * at(m[n], i, j, k) + (low[n] - high[n]) / h + at(m0[n], i, j, k) * dilatation;
          sum += (at(m_new[n], i, j, k) = c_now > 0.0 ? std::clamp(q / c_now, 0.0, 1.0) : at(m[n], i, j, k));
        }
        // Shares a partition still where round-off in a sliver of soil (c_new of 1e-17, say) made them
        // add up past 1.
        if (sum > 1.0)
          for (int n = 0; n < count; ++n) at(m_new[n], i, j, k) /= sum;
      }
}

}  // namespace

void material_sweep(int axis, double dt, const double* const* c, const double* const* c_new, int count,
                    const double* const* const* m, const double* const* const* m0, const double* const* u,
                    const double* const* face_soil, const double* const* cc, const double* dx, const double* dy,
                    CellBox o, double** const* m_new, RadialWeights radial, const double* density,
                    double** face_density) {
  o.zs = 0;  // one plane
  o.zm = 1;
  sweep_shares(axis, dt, c, c_new, count, m, m0, u, face_soil, cc, axis == 0 ? dx : dy, o, m_new, radial, density,
               face_density);
}

void material_sweep_3d(int axis, double dt, const double* const* const* c, const double* const* const* c_new,
                       int count, const double* const* const* const* m, const double* const* const* const* m0,
                       const double* const* const* face_velocity, const double* const* const* face_soil,
                       const double* const* const* cc, CellWidths3 widths, CellBox owned, double*** const* m_new,
                       const double* density, double*** face_density) {
  sweep_shares(axis, dt, c, c_new, count, m, m0, face_velocity, face_soil, cc, widths.along(axis), owned, m_new,
               RadialWeights{}, density, face_density);
}

}  // namespace granflow::interface
