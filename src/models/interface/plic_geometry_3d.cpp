#include "models/interface/plic_geometry_3d.hpp"

#include <algorithm>
#include <cmath>

#include "models/interface/plic_geometry.hpp"

namespace granflow::interface {

namespace {

Normal3 normalise_l1(double mx, double my, double mz) {
  const double s = std::abs(mx) + std::abs(my) + std::abs(mz);
  if (!(s > 0.0) || !std::isfinite(s)) return {};
  return {mx / s, my / s, mz / s};
}

// A plane's coefficients reflected to be non-negative, sorted (b1 <= b2 <= b3) and scaled to sum to
// one: the frame of Scardovelli & Zaleski's branches, in which the soil grows from the corner (0,0,0)
// as a rises from 0 to 1.
struct SortedPlane {
  double b1, b2, b3;
};
SortedPlane sorted_plane(double m1, double m2, double m3, double sum) {
  double b[3] = {m1 / sum, m2 / sum, m3 / sum};
  std::sort(b, b + 3);
  return {b[0], b[1], b[2]};
}

// The soil's volume (value) and its rate of change with a (slope, the plane's section) for a in
// [0, 1/2]; the other half follows from V(a) = 1 - V(1 - a). Each branch is the cubic of its range,
// with the terms that a small b1 divides arranged as (u / b1) u u, u < b1, so that none cancels.
struct VolumeAndSlope {
  double value, slope;
};
VolumeAndSlope lower_half_volume(const SortedPlane& p, double a) {
  const double b1 = p.b1, b2 = p.b2, b3 = p.b3, b12 = b1 + b2;
  if (a < b1) {  // a tetrahedron at the corner
    const double r = a / b1;
    return {r * a * a / (6.0 * b2 * b3), r * a / (2.0 * b2 * b3)};
  }
  // The corner's tetrahedron less the part of it beyond x = 1 (a prism along the b1 edge)...
  const double base = (3.0 * a * a - 3.0 * a * b1 + b1 * b1) / (6.0 * b2 * b3);
  const double base_slope = (2.0 * a - b1) / (2.0 * b2 * b3);
  if (a < b2) return {base, base_slope};
  if (a < std::min(b12, b3)) {  // ...and less the part beyond y = 1
    const double u = a - b2, r = u / b1;
    return {base - r * u * u / (6.0 * b2 * b3), base_slope - r * u / (2.0 * b2 * b3)};
  }
  if (b12 <= b3) return {(a - 0.5 * b12) / b3, 1.0 / b3};  // a slab across the cube
  const double u = a - b2, w = a - b3;  // beyond y = 1 and z = 1 too; u, w < b1 as a <= 1/2 < b12
  return {base - (u / b1 * u * u + w / b1 * w * w) / (6.0 * b2 * b3),
          base_slope - (u / b1 * u + w / b1 * w) / (2.0 * b2 * b3)};
}

VolumeAndSlope sorted_volume(const SortedPlane& p, double a) {
  if (a <= 0.5) return lower_half_volume(p, a);
  const VolumeAndSlope v = lower_half_volume(p, 1.0 - a);
  return {1.0 - v.value, v.slope};
}

// Scardovelli & Zaleski's analytic inversion for ch = min(c, 1 - c) in [0, 1/2] (Basilisk's
// plane_alpha has the same branches): the start of the Newton polish.
double analytic_lower_alpha(const SortedPlane& p, double ch) {
  const double b1 = p.b1, b2 = p.b2, b3 = p.b3, b12 = b1 + b2;
  const double pr = 6.0 * b1 * b2 * b3;
  const double v1 = b1 > 0.0 ? b1 * b1 / (6.0 * b2 * b3) : 0.0;
  const double v2 = v1 + (b2 - b1) / (2.0 * b3);
  const double v3 = b3 < b12 ? (b3 * b3 * (3.0 * b12 - b3) + b1 * b1 * (b1 - 3.0 * b3) + b2 * b2 * (b2 - 3.0 * b3)) / pr
                             : b12 / (2.0 * b3);
  if (ch < v1) return std::cbrt(pr * ch);
  if (ch < v2) return 0.5 * (b1 + std::sqrt(b1 * b1 + 8.0 * b2 * b3 * (ch - v1)));
  if (ch < v3) {
    const double p12 = std::sqrt(2.0 * b1 * b2);
    const double q = 3.0 * (b12 - 2.0 * b3 * ch) / (4.0 * p12);
    const double cs = std::cos(std::acos(std::clamp(q, -1.0, 1.0)) / 3.0);
    return p12 * (std::sqrt(3.0 * (1.0 - cs * cs)) - cs) + b12;
  }
  if (b12 <= b3) return b3 * ch + 0.5 * b12;
  const double pp = b1 * (b2 + b3) + b2 * b3 - 0.25;
  if (!(pp > 0.0)) return 0.5;
  const double q = 3.0 * b1 * b2 * b3 * (0.5 - ch) / (2.0 * pp * std::sqrt(pp));
  const double cs = std::cos(std::acos(std::clamp(q, -1.0, 1.0)) / 3.0);
  return std::sqrt(pp) * (std::sqrt(3.0 * (1.0 - cs * cs)) - cs) + 0.5;
}

}  // namespace

double unit_cube_fraction(double mx, double my, double mz, double a) {
  for (double* m : {&mx, &my, &mz})
    if (*m < 0.0) {  // X -> 1 - X
      a -= *m;
      *m = -*m;
    }
  if (a <= 0.0) return 0.0;
  const double sum = mx + my + mz;
  if (a >= sum) return 1.0;
  return std::clamp(sorted_volume(sorted_plane(mx, my, mz, sum), a / sum).value, 0.0, 1.0);
}

double cube_fraction(Normal3 n, double alpha) {
  return unit_cube_fraction(n.nx, n.ny, n.nz, alpha + 0.5 * (n.nx + n.ny + n.nz));
}

double plane_alpha(double c, Normal3 n) {
  c = std::clamp(c, 0.0, 1.0);
  const double sum = std::abs(n.nx) + std::abs(n.ny) + std::abs(n.nz);
  if (!(sum > 0.0)) return 0.0;
  const SortedPlane p = sorted_plane(std::abs(n.nx), std::abs(n.ny), std::abs(n.nz), sum);
  const double ch = std::min(c, 1.0 - c);
  // Newton on the lower half's volume (increasing, its slope the plane's section), kept inside a
  // bracket that bisects where a step would leave it.
  double a = std::clamp(analytic_lower_alpha(p, ch), 0.0, 0.5), lo = 0.0, hi = 0.5;
  for (int k = 0; k < 50 && ch > 0.0; ++k) {
    const VolumeAndSlope v = lower_half_volume(p, a);
    const double r = v.value - ch;
    if (std::abs(r) <= 1e-17) break;
    (r > 0.0 ? hi : lo) = a;
    double next = v.slope > 0.0 ? a - r / v.slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == a) break;
    a = next;
  }
  if (c > 0.5) a = 1.0 - a;
  a *= sum;
  for (double m : {n.nx, n.ny, n.nz})
    if (m < 0.0) a += m;
  return a - 0.5 * (n.nx + n.ny + n.nz);
}

double box_fraction(Normal3 n, double alpha, const std::array<double, 3>& lower, const std::array<double, 3>& upper) {
  // The box mapped onto [0,1]^3: X = lower + (upper - lower) xi.
  return unit_cube_fraction(n.nx * (upper[0] - lower[0]), n.ny * (upper[1] - lower[1]), n.nz * (upper[2] - lower[2]),
                            alpha - n.nx * lower[0] - n.ny * lower[1] - n.nz * lower[2]);
}

double face_fraction(Normal3 n, double alpha, int axis, int sign) {
  const double m[3] = {n.nx, n.ny, n.nz};
  const double ma = m[(axis + 1) % 3], mb = m[(axis + 2) % 3];
  // On the face, with s, t in [-0.5, 0.5] along the other two axes, the soil is where ma s + mb t <= beta.
  const double beta = alpha - 0.5 * sign * m[axis];
  if (ma == 0.0 && mb == 0.0) return beta >= 0.0 ? 1.0 : 0.0;  // a face the plane only touches, soil along it
  return unit_square_fraction(ma, mb, beta + 0.5 * (ma + mb));
}

Normal3 youngs_normal(const Block3x3x3& b) {
  const auto& c = b.c;
  double g[3] = {0.0, 0.0, 0.0};
  // Each corner of the centre cell (low or high side along each axis) with the eight cells around it:
  // layers k0, k0 + 1, rows j0, j0 + 1, columns i0, i0 + 1.
  for (int k0 = 0; k0 < 2; ++k0)
    for (int j0 = 0; j0 < 2; ++j0)
      for (int i0 = 0; i0 < 2; ++i0) {
        double dc[3] = {0.0, 0.0, 0.0};  // high cells less low cells along each axis, four pairs each
        for (int p = 0; p < 2; ++p)
          for (int q = 0; q < 2; ++q) {
            dc[0] += c[k0 + p][j0 + q][i0 + 1] - c[k0 + p][j0 + q][i0];
            dc[1] += c[k0 + p][j0 + 1][i0 + q] - c[k0 + p][j0][i0 + q];
            dc[2] += c[k0 + 1][j0 + p][i0 + q] - c[k0][j0 + p][i0 + q];
          }
        g[0] += dc[0] / (0.5 * (b.dx[i0] + b.dx[i0 + 1]));
        g[1] += dc[1] / (0.5 * (b.dy[j0] + b.dy[j0 + 1]));
        g[2] += dc[2] / (0.5 * (b.dz[k0] + b.dz[k0 + 1]));
      }
  // -grad c, expressed in the centre cell's scaled coordinates.
  return normalise_l1(-g[0] * b.dx[1], -g[1] * b.dy[1], -g[2] * b.dz[1]);
}

Normal3 myc_normal(const Block3x3x3& b) {
  const double* width[3] = {b.dx, b.dy, b.dz};
  auto c_at = [&](const int q[3]) { return b.c[q[2]][q[1]][q[0]]; };  // q: offsets 0..2 along x, y, z
  // Candidates in physical coordinates, |n|_1 = 1: the three centred ones, then Youngs'.
  double m[4][3];
  for (int a = 0; a < 3; ++a) {
    const int t1 = (a + 1) % 3, t2 = (a + 2) % 3;
    // Heights along a of the 3 x 3 columns (physical lengths of soil), H[r][s] at offsets r along t1, s along t2.
    double H[3][3];
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) {
        H[r][s] = 0.0;
        for (int q = 0; q < 3; ++q) {
          int p[3];
          p[a] = q, p[t1] = r, p[t2] = s;
          H[r][s] += c_at(p) * width[a][q];
        }
      }
    // Soil on the low side along a (the low layer of the block holds more): the normal points to +a.
    double low = 0.0, high = 0.0;
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) {
        int p[3];
        p[t1] = r, p[t2] = s;
        p[a] = 0;
        low += c_at(p);
        p[a] = 2;
        high += c_at(p);
      }
    const double sign = low > high ? 1.0 : -1.0;
    // n = (sign, -dH/dt1, -dH/dt2) along (a, t1, t2), the height's slope central over the middle row.
    const double d1 = (H[2][1] - H[0][1]) / (0.5 * width[t1][0] + width[t1][1] + 0.5 * width[t1][2]);
    const double d2 = (H[1][2] - H[1][0]) / (0.5 * width[t2][0] + width[t2][1] + 0.5 * width[t2][2]);
    const double norm = 1.0 + std::abs(d1) + std::abs(d2);
    m[a][a] = sign / norm;
    m[a][t1] = -d1 / norm;
    m[a][t2] = -d2 / norm;
  }
  const Normal3 y = to_physical(youngs_normal(b), b.dx[1], b.dy[1], b.dz[1]);
  m[3][0] = y.nx, m[3][1] = y.ny, m[3][2] = y.nz;
  if (y.nx == 0.0 && y.ny == 0.0 && y.nz == 0.0) return {};
  int choice = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(m[a][a]) > std::abs(m[choice][choice])) choice = a;
  const double youngs_largest = std::max({std::abs(m[3][0]), std::abs(m[3][1]), std::abs(m[3][2])});
  if (std::abs(m[choice][choice]) > youngs_largest) choice = 3;
  // Back to the centre cell's scaled coordinates.
  return normalise_l1(m[choice][0] * b.dx[1], m[choice][1] * b.dy[1], m[choice][2] * b.dz[1]);
}

Normal3 to_physical(Normal3 n, double dx, double dy, double dz) { return normalise_l1(n.nx / dx, n.ny / dy, n.nz / dz); }

}  // namespace granflow::interface
