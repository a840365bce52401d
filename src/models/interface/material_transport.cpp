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

}  // namespace

void material_sweep(int axis, double dt, const double* const* c, const double* const* c_new, int count,
                    const double* const* const* m, const double* const* const* m0, const double* const* u,
                    const double* const* face_soil, const double* const* cc, const double* dx, const double* dy,
                    CellBox o, double** const* m_new, RadialWeights radial, const double* density,
                    double** face_density) {
  const bool weighted = axis == 0 && radial.face != nullptr;
  const int di = axis == 0, dj = axis == 1;
  // Shares of cell (i, j): the stored materials', then the base's (the rest).
  auto shares_of = [&](int i, int j, Shares& s) {
    double rest = 1.0;
    for (int k = 0; k < count; ++k) rest -= (s[k] = m[k][j][i]);
    s[count] = rest;
  };
  // The shares the soil crossing the face after cell (i, j) carries, summing to 1. Where the cell
  // upstream of the donor or the acceptor holds no soil, its shares mean nothing and the donor's own
  // are taken.
  auto face_shares = [&](int i, int j, double f, Shares& s) {
    const int dir = f > 0.0 ? 1 : -1;
    const int id = f > 0.0 ? i : i + di, jd = f > 0.0 ? j : j + dj;  // donor
    const int ia = id + dir * di, ja = jd + dir * dj;                  // acceptor
    const int iu = id - dir * di, ju = jd - dir * dj;                  // upstream of the donor
    shares_of(id, jd, s);
    if (c[ja][ia] <= no_soil || c[ju][iu] <= no_soil) return;
    Shares a, up;
    shares_of(ia, ja, a);
    shares_of(iu, ju, up);
    // The share of the donor's soil that leaves through the face: the soil's own Courant number (the
    // face's swept volume over the donor's soil, radius-weighted in an axisymmetric x sweep). A donor
    // that gives all its soil away can give only its own shares (the TVD bound 1 - sigma).
    const double swept = std::abs(f) * (weighted ? radial.face[i] / radial.centre[id] : 1.0);
    const double courant = std::min(swept / (c[jd][id] * (axis == 0 ? dx[id] : dy[jd])), 1.0);
    // Each material's face share limited by its own slope (superbee is continuous in the shares, so
    // round-off stays round-off), then the shares scaled to add up to 1: the soil through a face is
    // shared out whole. With two materials the scaling is exact (both are limited alike); with three or
    // more it can take a share a little past its bound, which the cell then clips (docs/method.md).
    // One limiter for all, the most restrictive, kept the sum but not the rank-independence: a jump of
    // round-off in one material set the others' limiter at random.
    const double keep = 0.5 * (1.0 - courant);
    Shares limited;
    double sum = 0.0;
    for (int k = 0; k <= count; ++k) {
      const double jump = a[k] - s[k];
      limited[k] = jump != 0.0 ? s[k] + keep * superbee((s[k] - up[k]) / jump) * jump : s[k];
      sum += limited[k];  // each between the donor's and the acceptor's, in [0, 1]
    }
    if (!(sum > 0.5)) return;  // shares swapping places between donor and acceptor: the donor's
    for (int k = 0; k <= count; ++k) s[k] = limited[k] / sum;
  };
  // Through the face after cell (i, j) along the axis: each material's volume (per unit face area,
  // times the face's radius).
  auto carried = [&](int i, int j, Shares& out) {
    const double f = face_soil[j][i];
    if (f == 0.0) {
      out.fill(0.0);
      return;
    }
    face_shares(i, j, f, out);
    if (face_density) {
      double rho = 0.0;
      for (int k = 0; k < count; ++k) rho += out[k] * density[k + 1];
      face_density[j][i] = rho + out[count] * density[0];
    }
    const double volume = (weighted ? radial.face[i] : 1.0) * f;
    for (int k = 0; k < count; ++k) out[k] *= volume;
  };
  auto velocity = [&](int i, int j) { return (weighted ? radial.face[i] : 1.0) * u[j][i]; };
  Shares low, high;
  for (int j = o.ys; j < o.ys + o.ym; ++j)
    for (int i = o.xs; i < o.xs + o.xm; ++i) {
      const double h = axis == 0 ? dx[i] * (weighted ? radial.centre[i] : 1.0) : dy[j];
      carried(i - di, j - dj, low);
      carried(i, j, high);
      const double dilatation = cc[j][i] > 0.5 ? (velocity(i, j) - velocity(i - di, j - dj)) * dt / h : 0.0;
      double sum = 0.0;
      for (int k = 0; k < count; ++k) {
        const double q = c[j][i] * m[k][j][i] + (low[k] - high[k]) / h + m0[k][j][i] * dilatation;
        sum += (m_new[k][j][i] = c_new[j][i] > 0.0 ? std::clamp(q / c_new[j][i], 0.0, 1.0) : m[k][j][i]);
      }
      // Shares a partition still where round-off in a sliver of soil (c_new of 1e-17, say) made them
      // add up past 1.
      if (sum > 1.0)
        for (int k = 0; k < count; ++k) m_new[k][j][i] /= sum;
    }
}

}  // namespace granflow::interface
