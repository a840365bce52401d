// Soil materials carried with the soil on a mesh of layers (material_sweep_3d): each sweep the planar
// one's, along x and y layer by layer and along z as the planar sweep along y of the plane turned; and
// over whole steps of three sweeps each material's volume conserved to round-off, shares in [0, 1].
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "models/interface/material_transport.hpp"
#include "models/interface/vof_advection.hpp"
#include "models/interface/vof_advection_3d.hpp"

namespace granflow::interface {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kGhosts = 2;

// An array [k][j][i] of n[0] x n[1] x n[2] cells and two ghost layers, indexed globally from -2.
struct Volume {
  explicit Volume(int nx, int ny, int nz) : nx(nx), ny(ny), nz(nz) {
    const int sx = nx + 2 * kGhosts, sy = ny + 2 * kGhosts, sz = nz + 2 * kGhosts;
    values.assign(size_t(sx) * sy * sz, 0.0);
    rows.resize(size_t(sy) * sz);
    planes.resize(size_t(sz));
    for (int k = 0; k < sz; ++k) {
      for (int j = 0; j < sy; ++j) rows[size_t(k) * sy + j] = values.data() + (size_t(k) * sy + j) * sx + kGhosts;
      planes[size_t(k)] = rows.data() + size_t(k) * sy + kGhosts;
    }
  }
  // A copy points into its own values.
  Volume(const Volume& other) : Volume(other.nx, other.ny, other.nz) { values = other.values; }
  Volume& operator=(const Volume&) = delete;
  double*** v() { return planes.data() + kGhosts; }
  double& operator()(int i, int j, int k) { return v()[k][j][i]; }
  // Each ghost the nearest cell's value (edges and corners included).
  void copy_to_ghosts() {
    auto clamp = [](int i, int n) { return std::clamp(i, 0, n - 1); };
    for (int k = -kGhosts; k < nz + kGhosts; ++k)
      for (int j = -kGhosts; j < ny + kGhosts; ++j)
        for (int i = -kGhosts; i < nx + kGhosts; ++i)
          (*this)(i, j, k) = (*this)(clamp(i, nx), clamp(j, ny), clamp(k, nz));
  }
  int nx, ny, nz;
  std::vector<double> values;
  std::vector<double*> rows;
  std::vector<double**> planes;
};

// A plane [j][i] of the same ghost layout.
struct Plane {
  Plane(int nx, int ny) : volume(nx, ny, 1) {}
  double** rows() { return volume.v()[0]; }
  double& operator()(int i, int j) { return volume(i, j, 0); }
  Volume volume;
};

// Smooth, varied values: every face moves soil, shares differ from cell to cell.
double wave(double a, double b, double phase) { return 0.5 + 0.45 * std::sin(2.1 * a + 1.3 * b + phase); }

// One sweep of one material along `axis` on a mesh of layers whose values vary across x and `other`
// (1 or 2) only, and the planar sweep of the plane (x, other) along axis 0 or 1: the same numbers.
void compare_with_planar(int axis, int other) {
  const int nx = 7, n_other = 6, layers = 3, count = 2;
  const int ny = other == 1 ? n_other : layers, nz = other == 2 ? n_other : layers;
  Volume c(nx, ny, nz), c_new(nx, ny, nz), u(nx, ny, nz), f(nx, ny, nz), cc(nx, ny, nz), fd(nx, ny, nz);
  std::vector<Volume> m(count, Volume(nx, ny, nz)), m0 = m, m_new = m;
  Plane pc(nx, n_other), pc_new = pc, pu = pc, pf = pc, pcc = pc, pfd = pc;
  std::vector<Plane> pm(count, pc), pm0 = pm, pm_new = pm;
  // The plane's index q along `other`; r along the third axis, on which nothing depends.
  for (int k = -kGhosts; k < nz + kGhosts; ++k)
    for (int j = -kGhosts; j < ny + kGhosts; ++j)
      for (int i = -kGhosts; i < nx + kGhosts; ++i) {
        const int q = other == 1 ? j : k;
        const double x = i, y = q;
        c(i, j, k) = pc(i, q) = std::min(1.0, 1.2 * wave(x, y, 0.0));
        c_new(i, j, k) = pc_new(i, q) = std::min(1.0, 1.2 * wave(x, y, 0.3));
        u(i, j, k) = pu(i, q) = 0.3 * std::sin(0.7 * x - 0.4 * y);
        f(i, j, k) = pf(i, q) = 0.1 * std::cos(0.5 * x + 0.9 * y);
        cc(i, j, k) = pcc(i, q) = c(i, j, k) > 0.5 ? 1.0 : 0.0;
        for (int n = 0; n < count; ++n) {
          m[n](i, j, k) = pm[n](i, q) = 0.5 * wave(x, y, 1.0 + n);
          m0[n](i, j, k) = pm0[n](i, q) = 0.5 * wave(x, y, 2.0 + n);
        }
      }
  // Widths: along x, along `other` and across, each its own.
  std::vector<double> wx(nx + 2 * kGhosts), wo(n_other + 2 * kGhosts), wl(layers + 2 * kGhosts);
  for (size_t s = 0; s < wx.size(); ++s) wx[s] = 0.01 * (1.0 + 0.1 * double(s));
  for (size_t s = 0; s < wo.size(); ++s) wo[s] = 0.02 * (1.0 + 0.07 * double(s));
  for (size_t s = 0; s < wl.size(); ++s) wl[s] = 0.03;
  const double* dx = wx.data() + kGhosts;
  const double* d_other = wo.data() + kGhosts;
  const double* d_layers = wl.data() + kGhosts;
  const CellWidths3 widths{dx, other == 1 ? d_other : d_layers, other == 2 ? d_other : d_layers};
  const double density[3] = {2000.0, 2650.0, 3100.0};
  const double dt = 0.01;

  std::vector<const double* const* const*> mr, m0r;
  std::vector<double***> mnr;
  for (int n = 0; n < count; ++n) {
    mr.push_back(m[n].v());
    m0r.push_back(m0[n].v());
    mnr.push_back(m_new[n].v());
  }
  const CellBox owned{0, 0, nx, ny, 0, nz};
  material_sweep_3d(axis, dt, c.v(), c_new.v(), count, mr.data(), m0r.data(), u.v(), f.v(), cc.v(), widths, owned,
                    mnr.data(), density, fd.v());

  std::vector<const double* const*> pmr, pm0r;
  std::vector<double**> pmnr;
  for (int n = 0; n < count; ++n) {
    pmr.push_back(pm[n].rows());
    pm0r.push_back(pm0[n].rows());
    pmnr.push_back(pm_new[n].rows());
  }
  const int planar_axis = axis == 0 ? 0 : 1;
  material_sweep(planar_axis, dt, pc.rows(), pc_new.rows(), count, pmr.data(), pm0r.data(), pu.rows(), pf.rows(),
                 pcc.rows(), dx, d_other, CellBox{0, 0, nx, n_other}, pmnr.data(), RadialWeights{}, density,
                 pfd.rows());
  int compared = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const int q = other == 1 ? j : k;
        for (int n = 0; n < count; ++n) EXPECT_EQ(m_new[n](i, j, k), pm_new[n](i, q)) << i << " " << j << " " << k;
        ++compared;
      }
  EXPECT_EQ(compared, nx * ny * nz);
  // The density of the soil each face carried, on every face the sweep visits: the block's low face too.
  const int lo[3] = {axis == 0 ? -1 : 0, axis == 1 ? -1 : 0, axis == 2 ? -1 : 0};
  for (int k = lo[2]; k < nz; ++k)
    for (int j = lo[1]; j < ny; ++j)
      for (int i = lo[0]; i < nx; ++i) EXPECT_EQ(fd(i, j, k), pfd(i, other == 1 ? j : k)) << i << " " << j << " " << k;
}

TEST(MaterialTransport3d, EachSweepIsThePlanarSweepOfItsPlane) {
  compare_with_planar(0, 1);  // x, the field varying in x-y: layer by layer
  compare_with_planar(1, 1);  // y, likewise
  compare_with_planar(0, 2);  // x, the field varying in x-z: row by row of the x-z plane
  compare_with_planar(2, 2);  // z, likewise: the planar y sweep of the x-z plane
}

// A sphere of soil, its west half (x < 0.5) material 1 and its top (y > 0.6) material 2, stirred by a
// discretely divergence-free flow through all three axes that vanishes on the sides: over whole steps
// of three sweeps (x y z, then z y x) each material's volume is conserved to round-off and every share
// stays within [0, 1].
TEST(MaterialTransport3d, StepsOfThreeSweepsConserveEachMaterial) {
  const int n = 12, count = 2;
  const double h = 1.0 / n;
  Volume c(n, n, n), tmp(n, n, n), cc(n, n, n), face_soil(n, n, n);
  Volume u[3] = {Volume(n, n, n), Volume(n, n, n), Volume(n, n, n)};
  std::vector<Volume> m(count, Volume(n, n, n)), m_tmp = m, m0 = m;
  std::vector<double> widths_with_ghosts(n + 2 * kGhosts, h);
  const double* w = widths_with_ghosts.data() + kGhosts;
  const CellWidths3 widths{w, w, w};
  // Stream functions at the cells' edges: psi(x, y) drives u and v, phi(y, z) drives v and w, each
  // face's velocity their difference across it, so that every cell's net outflow telescopes to zero.
  auto psi = [](double x, double y) { return 0.4 * std::pow(std::sin(kPi * x) * std::sin(kPi * y), 2); };
  auto phi = [](double y, double z) { return 0.3 * std::pow(std::sin(kPi * y) * std::sin(kPi * z), 2); };
  for (int k = -1; k < n; ++k)
    for (int j = -1; j < n; ++j)
      for (int i = -1; i < n; ++i) {
        const double xf = (i + 1) * h, yf = (j + 1) * h, zf = (k + 1) * h;  // this cell's high faces
        const double xc = (i + 0.5) * h, yc = (j + 0.5) * h, zc = (k + 0.5) * h;
        u[0](i, j, k) = (psi(xf, yc + 0.5 * h) - psi(xf, yc - 0.5 * h)) / h;
        u[1](i, j, k) = -(psi(xc + 0.5 * h, yf) - psi(xc - 0.5 * h, yf)) / h + (phi(yf, zc + 0.5 * h) - phi(yf, zc - 0.5 * h)) / h;
        u[2](i, j, k) = -(phi(yc + 0.5 * h, zf) - phi(yc - 0.5 * h, zf)) / h;
      }
  auto inside = [](double x, double y, double z) {
    return std::pow(x - 0.5, 2) + std::pow(y - 0.5, 2) + std::pow(z - 0.5, 2) < 0.3 * 0.3;
  };
  constexpr int samples = 8;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double soil = 0.0, west = 0.0, top = 0.0;
        for (int a = 0; a < samples; ++a)
          for (int b = 0; b < samples; ++b)
            for (int d = 0; d < samples; ++d) {
              const double x = (i + (a + 0.5) / samples) * h, y = (j + (b + 0.5) / samples) * h,
                           z = (k + (d + 0.5) / samples) * h;
              if (!inside(x, y, z)) continue;
              soil += 1.0;
              if (y > 0.6) top += 1.0;
              else if (x < 0.5) west += 1.0;
            }
        c(i, j, k) = soil / (samples * samples * samples);
        m[0](i, j, k) = soil > 0.0 ? west / soil : 0.0;
        m[1](i, j, k) = soil > 0.0 ? top / soil : 0.0;
      }
  auto volumes = [&] {
    std::vector<double> v(count + 1, 0.0);
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          v[0] += c(i, j, k) * h * h * h;
          for (int q = 0; q < count; ++q) v[size_t(q) + 1] += c(i, j, k) * m[q](i, j, k) * h * h * h;
        }
    return v;
  };
  auto top_centroid = [&] {  // the top material's centroid's height
    double moment = 0.0, volume = 0.0;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          moment += c(i, j, k) * m[1](i, j, k) * (j + 0.5) * h;
          volume += c(i, j, k) * m[1](i, j, k);
        }
    return moment / volume;
  };
  const auto start = volumes();
  const double centroid0 = top_centroid();
  double worst = 0.0, lowest = 1.0, highest = 0.0;
  const double dt = 0.4 * h / 1.3;  // the largest face speed is below 1.3
  const CellBox owned{0, 0, n, n, 0, n};
  for (int step = 0; step < 30; ++step) {
    c.copy_to_ghosts();
    for (auto& a : m) a.copy_to_ghosts();
    dilatation_indicator(c.v(), owned, cc.v());
    for (int q = 0; q < count; ++q) m0[q].values = m[q].values;
    Volume* from = &c;
    Volume* to = &tmp;
    std::vector<Volume>* m_from = &m;
    std::vector<Volume>* m_to = &m_tmp;
    for (int s = 0; s < 3; ++s) {
      const int axis = step % 2 == 0 ? s : 2 - s;
      std::fill(face_soil.values.begin(), face_soil.values.end(), 0.0);
      vof_sweep(axis, dt, from->v(), u[axis].v(), cc.v(), widths, owned, to->v(), DomainCells3{n, n, n},
                face_soil.v());
      std::vector<const double* const* const*> mr, m0r;
      std::vector<double***> mnr;
      for (int q = 0; q < count; ++q) {
        mr.push_back((*m_from)[q].v());
        m0r.push_back(m0[q].v());
        mnr.push_back((*m_to)[q].v());
      }
      material_sweep_3d(axis, dt, from->v(), to->v(), count, mr.data(), m0r.data(), u[axis].v(), face_soil.v(),
                        cc.v(), widths, owned, mnr.data());
      to->copy_to_ghosts();
      for (auto& a : *m_to) a.copy_to_ghosts();
      std::swap(from, to);
      std::swap(m_from, m_to);
    }
    // Three sweeps end in tmp: back.
    c.values = from->values;
    for (int q = 0; q < count; ++q) m[q].values = (*m_from)[q].values;
    const auto now = volumes();
    for (size_t q = 0; q < now.size(); ++q) worst = std::max(worst, std::abs(now[q] / start[q] - 1.0));
    for (int q = 0; q < count; ++q)
      for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            lowest = std::min(lowest, m[q](i, j, k));
            highest = std::max(highest, m[q](i, j, k));
          }
  }
  // The contact moved: the top material's centroid is no longer where it started.
  const double moved = std::abs(top_centroid() - centroid0);
  std::printf("30 steps of three sweeps: largest relative change of the soil's and the materials' volumes %.2e; "
              "shares within [%.3g, %.3g]; the top material's centroid moved %.3f m\n",
              worst, lowest, highest, moved);
  EXPECT_LT(worst, 1e-13);
  EXPECT_GE(lowest, 0.0);
  EXPECT_LE(highest, 1.0);
  EXPECT_GT(moved, 0.05);
}

}  // namespace
}  // namespace granflow::interface
