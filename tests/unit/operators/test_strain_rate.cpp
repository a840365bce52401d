// The discrete strain rate at cell centres and on faces: exact for a linear velocity field on a graded
// grid (boundary faces to the ghosts included), and on faces the rate the face's stress multiplies.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "mesh/field.hpp"
#include "mesh/grid.hpp"
#include "operators/strain_rate.hpp"

namespace granflow {
namespace {

// A ghosted cell array [j][i], i in -2 .. nx+1, j in -2 .. ny+1, filled from f(x, y) at the centres.
struct GhostedArray {
  std::vector<double> data;
  std::vector<double*> rows;
  template <class F>
  GhostedArray(const Grid& g, F f) {
    const int w = Grid::ghost_width, mx = g.nx() + 2 * w, my = g.ny() + 2 * w;
    data.resize(size_t(mx) * my);
    for (int j = -w; j < g.ny() + w; ++j)
      for (int i = -w; i < g.nx() + w; ++i) data[size_t(j + w) * mx + (i + w)] = f(g.xc(i), g.yc(j));
    for (int j = 0; j < my; ++j) rows.push_back(data.data() + size_t(j) * mx + w);
  }
  const double* const* get() const { return rows.data() + Grid::ghost_width; }
};

// 6 x 5 cells over 0.3 x 0.2 m, graded along both axes.
GridSpec graded_spec() {
  GridSpec spec;
  spec.cells = {6, 5, 1};
  spec.upper = {0.3, 0.2};
  spec.grading = {1.4, 0.7};
  return spec;
}

TEST(StrainRate, ExactForALinearVelocityAtCentresAndOnEveryFace) {
  const Grid g(PETSC_COMM_SELF, graded_spec());
  const double a = 0.3, b = -1.7, c = 2.1, d = -0.3;  // u = a x + b y, v = c x + d y
  GhostedArray u(g, [&](double x, double y) { return a * x + b * y; });
  GhostedArray v(g, [&](double x, double y) { return c * x + d * y; });
  auto expect_exact = [&](const rheology::StrainRate& D) {
    EXPECT_NEAR(D.xx, a, 1e-12);
    EXPECT_NEAR(D.yy, d, 1e-12);
    EXPECT_NEAR(D.xy, 0.5 * (b + c), 1e-12);
    EXPECT_EQ(D.zz, 0.0);
  };
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) expect_exact(cell_strain_rate(g, u.get(), v.get(), i, j));
  // Faces from the west boundary face (i = -1, between the ghost and cell 0) to the east one.
  for (int j = 0; j < g.ny(); ++j)
    for (int i = -1; i < g.nx(); ++i) expect_exact(face_strain_rate(g, u.get(), v.get(), 0, i, j));
  for (int j = -1; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) expect_exact(face_strain_rate(g, u.get(), v.get(), 1, i, j));
}

// A layer sheared at the grid scale, u = exp(k y): the shear rate on a face is the compact difference
// (u_N - u_P) / dy across it, which lies between the two cells' central rates.
TEST(StrainRate, FaceShearIsTheCompactDifferenceAcrossTheFace) {
  GridSpec spec;
  spec.cells = {4, 8, 1};
  spec.upper = {0.04, 0.08};
  Grid g(PETSC_COMM_SELF, spec);
  const double k = std::log(3.0) / 0.01;  // three-fold per cell
  GhostedArray u(g, [&](double, double y) { return std::exp(k * y); });
  GhostedArray v(g, [](double, double) { return 0.0; });
  for (int j = 0; j + 1 < g.ny(); ++j) {
    const double compact = (std::exp(k * g.yc(j + 1)) - std::exp(k * g.yc(j))) / 0.01;
    const auto D = face_strain_rate(g, u.get(), v.get(), 1, 1, j);
    EXPECT_NEAR(2.0 * D.xy, compact, 1e-12 * compact);
    // The centre rates straddle it: the lower cell's is smaller, the upper cell's larger.
    EXPECT_LT(2.0 * cell_strain_rate(g, u.get(), v.get(), 1, j).xy, compact);
    EXPECT_GT(2.0 * cell_strain_rate(g, u.get(), v.get(), 1, j + 1).xy, compact);
  }
}

// Under numerics.wall_gradient = "quadratic" the wall face's rate takes the derivatives across the
// wall through the wall and the first two cells, as the momentum flux does: exact for a velocity
// quadratic in the distance from the wall, on every side of a graded grid, moving walls included.
TEST(StrainRate, QuadraticWallRateIsExactForAQuadraticProfile) {
  const Grid g(PETSC_COMM_SELF, graded_spec());
  const double X = 0.3, Y = 0.2, U = 0.7, a = 1.3, b = -40.0, e = -0.9, f = 25.0, q = 6.0;
  // Tangential component U + (a + q t) s + b s^2 and normal e s + f s^2, s the distance from the
  // wall and t the coordinate along it: the wall shear varies along the wall, and the derivative
  // along it from row to row.
  auto tangential = [&](double s, double t) { return U + (a + q * t) * s + b * s * s; };
  auto normal = [&](double s) { return e * s + f * s * s; };
  struct Wall {
    int axis, sign;
    double derivative_sign;  // d/d(axis) = derivative_sign * d/ds
  };
  for (const Wall w : {Wall{1, -1, 1.0}, Wall{1, 1, -1.0}, Wall{0, -1, 1.0}, Wall{0, 1, -1.0}}) {
    auto distance = [&](double x, double y) {
      return w.axis == 0 ? (w.sign < 0 ? x : X - x) : (w.sign < 0 ? y : Y - y);
    };
    auto along = [&](double x, double y) { return w.axis == 0 ? y : x; };
    GhostedArray u(g, [&](double x, double y) {
      return w.axis == 1 ? tangential(distance(x, y), along(x, y)) : normal(distance(x, y));
    });
    GhostedArray v(g, [&](double x, double y) {
      return w.axis == 0 ? tangential(distance(x, y), along(x, y)) : normal(distance(x, y));
    });
    const std::array<double, 2> wall_velocity = w.axis == 1 ? std::array{U, 0.0} : std::array{0.0, U};
    const int n_along = w.axis == 0 ? g.ny() : g.nx();
    for (int k = 0; k < n_along; ++k) {
      const int i = w.axis == 0 ? (w.sign < 0 ? 0 : g.nx() - 1) : k;
      const int j = w.axis == 1 ? (w.sign < 0 ? 0 : g.ny() - 1) : k;
      const double t = w.axis == 0 ? g.yc(j) : g.xc(i);
      const std::string where = "axis " + std::to_string(w.axis) + " sign " + std::to_string(w.sign);
      const auto D = quadratic_wall_strain_rate(g, u.get(), v.get(), w.axis, i, j, w.sign, wall_velocity, false);
      EXPECT_NEAR(D.xy, 0.5 * w.derivative_sign * (a + q * t), 1e-10) << where;
      EXPECT_NEAR(w.axis == 0 ? D.xx : D.yy, w.derivative_sign * e, 1e-10) << where;
      // The derivative along the wall is the wall face's own, as face_strain_rate takes it.
      const int il = w.sign < 0 && w.axis == 0 ? i - 1 : i, jl = w.sign < 0 && w.axis == 1 ? j - 1 : j;
      const auto F = face_strain_rate(g, u.get(), v.get(), w.axis, il, jl);
      EXPECT_DOUBLE_EQ(w.axis == 0 ? D.yy : D.xx, w.axis == 0 ? F.yy : F.xx) << where;
      // ... which differs from that of the faces further in (the derivative along grows with s).
      const auto inner = face_strain_rate(g, u.get(), v.get(), w.axis, il - w.sign * (w.axis == 0),
                                          jl - w.sign * (w.axis == 1));
      EXPECT_GT(std::abs((w.axis == 0 ? D.yy : D.xx) - (w.axis == 0 ? inner.yy : inner.xx)), 1e-3) << where;
      // A slip wall carries no shear; the normal derivative stays.
      const auto S = quadratic_wall_strain_rate(g, u.get(), v.get(), w.axis, i, j, w.sign, wall_velocity, true);
      EXPECT_EQ(S.xy, 0.0);
      EXPECT_NEAR(w.axis == 0 ? S.xx : S.yy, w.derivative_sign * e, 1e-10);
    }
  }
}

// 5 x 4 x 6 cells, graded along all three axes.
GridSpec graded_layers_spec() {
  GridSpec spec;
  spec.cells = {5, 4, 6};
  spec.lower = {0.0, -0.1, 0.2};
  spec.upper = {0.3, 0.2, 0.5};
  spec.grading = {1.4, 0.7, 2.0};
  return spec;
}

// In 3D, on a grid graded along all three axes: every component's gradient, exactly, for a linear
// velocity v = A x, at the centres and on the faces along each axis, ghosts included.
TEST(StrainRate, ExactForALinearVelocityIn3dAtCentresAndOnFacesAlongEachAxis) {
  const Grid g(PETSC_COMM_SELF, graded_layers_spec());
  const double A[3][3] = {{0.3, -1.2, 0.7}, {2.1, -0.5, 0.4}, {-0.9, 1.6, 0.2}};
  Field u(g), v(g), w(g);
  {
    FieldArray a[3] = {local_array(g, u), local_array(g, v), local_array(g, w)};
    const int gw = Grid::ghost_width;
    for (int k = -gw; k < g.nz() + gw; ++k)
      for (int j = -gw; j < g.ny() + gw; ++j)
        for (int i = -gw; i < g.nx() + gw; ++i)
          for (int c = 0; c < 3; ++c) a[c].volume()[k][j][i] = A[c][0] * g.xc(i) + A[c][1] * g.yc(j) + A[c][2] * g.zc(k);
  }
  ConstFieldArray ua = local_read(g, u), va = local_read(g, v), wa = local_read(g, w);
  const VelocityArrays3 vel{ua.volume(), va.volume(), wa.volume()};
  auto expect_sym_a = [&](const rheology::StrainRate& d, const std::string& where) {
    EXPECT_NEAR(d.xx, A[0][0], 1e-12) << where;
    EXPECT_NEAR(d.yy, A[1][1], 1e-12) << where;
    EXPECT_NEAR(d.zz, A[2][2], 1e-12) << where;
    EXPECT_NEAR(d.xy, 0.5 * (A[0][1] + A[1][0]), 1e-12) << where;
    EXPECT_NEAR(d.xz, 0.5 * (A[0][2] + A[2][0]), 1e-12) << where;
    EXPECT_NEAR(d.yz, 0.5 * (A[1][2] + A[2][1]), 1e-12) << where;
  };
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const std::string where = std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k);
        expect_sym_a(cell_strain_rate(g, vel, i, j, k), "cell " + where);
        for (int axis = 0; axis < 3; ++axis) expect_sym_a(face_strain_rate(g, vel, axis, i, j, k), "face " + where);
      }
  // The low boundary faces, between a ghost and the first cells.
  expect_sym_a(face_strain_rate(g, vel, 2, 2, 1, -1), "the face below the first layer");
}

// In 3D, on each of the six walls of a graded box: both tangential components U_t + (a_t + q_t r) s +
// b_t s^2 and the normal one e s + f s^2 (s the distance from the wall, r a coordinate along it), so
// the wall's two shears and its normal rate come out exact; a slip wall carries no shear.
TEST(StrainRate, QuadraticWallRateIn3dIsExactForAQuadraticProfileOnEveryWall) {
  const GridSpec spec = graded_layers_spec();
  const Grid g(PETSC_COMM_SELF, spec);
  const double e = -0.9, f = 25.0;
  const double U[3] = {0.7, -0.4, 0.25}, a[3] = {1.3, -0.6, 2.2}, b[3] = {-40.0, 15.0, 8.0}, q[3] = {6.0, -3.0, 4.0};
  for (int axis = 0; axis < 3; ++axis)
    for (int sign : {-1, 1}) {
      const double lo = spec.lower[axis], hi = spec.upper[axis];
      const int r_axis = (axis + 1) % 3;  // the coordinate the shear varies along
      auto distance = [&](const std::array<double, 3>& x) { return sign < 0 ? x[axis] - lo : hi - x[axis]; };
      auto component = [&](int c, const std::array<double, 3>& x) {
        const double s = distance(x);
        return c == axis ? e * s + f * s * s : U[c] + (a[c] + q[c] * x[r_axis]) * s + b[c] * s * s;
      };
      Field u(g), v(g), w(g);
      {
        FieldArray arr[3] = {local_array(g, u), local_array(g, v), local_array(g, w)};
        const int gw = Grid::ghost_width;
        for (int k = -gw; k < g.nz() + gw; ++k)
          for (int j = -gw; j < g.ny() + gw; ++j)
            for (int i = -gw; i < g.nx() + gw; ++i)
              for (int c = 0; c < 3; ++c) arr[c].volume()[k][j][i] = component(c, {g.xc(i), g.yc(j), g.zc(k)});
      }
      ConstFieldArray ua = local_read(g, u), va = local_read(g, v), wa = local_read(g, w);
      const VelocityArrays3 vel{ua.volume(), va.volume(), wa.volume()};
      std::array<double, 3> wall_velocity{U[0], U[1], U[2]};
      wall_velocity[axis] = 0.0;
      const double towards = -sign;  // d/d(axis) = towards * d/ds
      const int n[3] = {g.nx(), g.ny(), g.nz()};
      // The cells along the wall: every cell of the first layer from it.
      for (int m = 0; m < n[(axis + 1) % 3]; ++m)
        for (int l = 0; l < n[(axis + 2) % 3]; ++l) {
          int idx[3];
          idx[axis] = sign < 0 ? 0 : n[axis] - 1;
          idx[(axis + 1) % 3] = m;
          idx[(axis + 2) % 3] = l;
          const std::array<double, 3> centre{g.xc(idx[0]), g.yc(idx[1]), g.zc(idx[2])};
          std::array<double, 3> on_wall = centre;
          on_wall[axis] = sign < 0 ? lo : hi;
          const std::string where = "axis " + std::to_string(axis) + " sign " + std::to_string(sign);
          const auto D = quadratic_wall_strain_rate(g, vel, axis, idx[0], idx[1], idx[2], sign, wall_velocity, false);
          const auto S = quadratic_wall_strain_rate(g, vel, axis, idx[0], idx[1], idx[2], sign, wall_velocity, true);
          const double diag[3] = {D.xx, D.yy, D.zz}, slip_diag[3] = {S.xx, S.yy, S.zz};
          EXPECT_NEAR(diag[axis], towards * e, 1e-9) << where;
          EXPECT_NEAR(slip_diag[axis], towards * e, 1e-9) << where;
          // The normal component does not vary along the wall, so the shear of tangential component c
          // against the wall is half its derivative across it: a_c + q_c r at the wall, exactly.
          auto shear = [&](const rheology::StrainRate& d, int c) {
            const int first = std::min(axis, c), second = std::max(axis, c);
            return first == 0 ? (second == 1 ? d.xy : d.xz) : d.yz;
          };
          for (int c = 0; c < 3; ++c) {
            if (c == axis) continue;
            EXPECT_NEAR(2.0 * shear(D, c), towards * (a[c] + q[c] * on_wall[r_axis]), 1e-9) << where << ", component " << c;
            EXPECT_NEAR(shear(S, c), 0.0, 1e-12) << where << ", component " << c;
          }
        }
    }
}

// A velocity along the layers and the same on each (w = 0, no z dependence) has the planar rate.
TEST(StrainRate, AFlowTheSameOnEveryLayerHasThePlanarRate) {
  GridSpec spec;
  spec.cells = {4, 4, 3};
  spec.upper = {0.4, 0.4, 0.3};
  const Grid g(PETSC_COMM_SELF, spec);
  Field u(g), v(g), w(g);
  w.set(0.0);
  {
    FieldArray ua = local_array(g, u), va = local_array(g, v);
    const int gw = Grid::ghost_width;
    for (int k = -gw; k < g.nz() + gw; ++k)
      for (int j = -gw; j < g.ny() + gw; ++j)
        for (int i = -gw; i < g.nx() + gw; ++i) {
          ua.volume()[k][j][i] = std::sin(3.0 * g.xc(i)) * std::cos(2.0 * g.yc(j));
          va.volume()[k][j][i] = g.xc(i) * g.xc(i) - g.yc(j);
        }
  }
  ConstFieldArray ua = local_read(g, u), va = local_read(g, v), wa = local_read(g, w);
  const VelocityArrays3 vel{ua.volume(), va.volume(), wa.volume()};
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) {
        const auto d3 = cell_strain_rate(g, vel, i, j, k);
        const auto d2 = cell_strain_rate(g, ua.volume()[k], va.volume()[k], i, j);
        EXPECT_EQ(d3.xx, d2.xx);
        EXPECT_EQ(d3.yy, d2.yy);
        EXPECT_EQ(d3.xy, d2.xy);
        EXPECT_EQ(d3.zz, 0.0);
        EXPECT_EQ(d3.xz, 0.0);
        EXPECT_EQ(d3.yz, 0.0);
      }
}

}  // namespace
}  // namespace granflow
