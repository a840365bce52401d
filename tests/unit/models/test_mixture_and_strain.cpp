// Mixture interpolation ([VoF] Eq. 1, App. A) and the Euler-Almansi strain ([VoF] Eqs. 13-14).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "models/interface/initial_shapes.hpp"
#include "models/mixture/mixture_interpolation.hpp"
#include "models/strain/euler_almansi.hpp"

namespace granflow {
namespace {

using mixture::InterpolationKind;
using mixture::MixtureInterpolation;

TEST(Mixture, LinearIsEquationOne) {
  const MixtureInterpolation lin;
  EXPECT_DOUBLE_EQ(lin(0.25, 1.0, 2651.0), 0.75 * 1.0 + 0.25 * 2651.0);
}

TEST(Mixture, ArctanHitsBothPhasesAndIsMonotone) {
  for (auto [M, N] : {std::pair{-0.45, 25.0}, std::pair{0.0, 5.0}, std::pair{0.3, 10.0}}) {
    const MixtureInterpolation a{InterpolationKind::arctan, M, N};
    EXPECT_EQ(a(0.0, 1.8e-5, 1e8), 1.8e-5) << M << " " << N;  // exact, however large the jump
    EXPECT_EQ(a(1.0, 1.8e-5, 1e8), 1e8) << M << " " << N;
    EXPECT_NEAR(a(1e-9, 1.0, 2650.0), 1.0, 1e-6 * 2650) << M << " " << N;  // and continuous there
    EXPECT_NEAR(a(1.0 - 1e-9, 1.0, 2650.0), 2650.0, 1e-6 * 2650) << M << " " << N;
    double last = a(0.0, 1.0, 2650.0);
    for (int k = 1; k <= 100; ++k) {
      const double v = a(k / 100.0, 1.0, 2650.0);
      EXPECT_GE(v, last - 1e-9);
      last = v;
    }
  }
}

TEST(Mixture, ArctanShiftMovesTheTransitionTowardsAir) {
  // M = -0.45 (the [VoF] Sec. 4.1 setting) gives a cell that is 10 % soil most of the soil's value,
  // which is the point of the interpolation: interface cells keep their strength.
  const MixtureInterpolation a{InterpolationKind::arctan, -0.45, 25.0};
  EXPECT_GT(a(0.1, 0.0, 1.0), 0.5);
  const MixtureInterpolation sym{InterpolationKind::arctan, 0.0, 5.0};
  EXPECT_NEAR(sym(0.5, 0.0, 1.0), 0.5, 1e-12);
}

TEST(EulerAlmansi, ZeroDisplacementGradientIsUnstrained) {
  strain::AlmansiStrain e;
  ASSERT_TRUE(strain::almansi_strain({}, e));
  EXPECT_DOUBLE_EQ(strain::deviatoric_norm(e), 0.0);
}

TEST(EulerAlmansi, SimpleShearMatchesClosedForm) {
  // Eulerian displacement of simple shear x = X + g Y: u = x - X = g y, so grad u = [[0, g], [0, 0]],
  // F = I - grad u = [[1, -g], [0, 1]], G = [[1, g], [0, 1]], e = (I - G G^T)/2 = [[-g^2/2, -g/2], [-g/2, 0]].
  const double g = 0.3;
  strain::AlmansiStrain e;
  ASSERT_TRUE(strain::almansi_strain({0.0, g, 0.0, 0.0}, e));
  EXPECT_NEAR(e.xx, -0.5 * g * g, 1e-15);
  EXPECT_NEAR(e.xy, -0.5 * g, 1e-15);
  EXPECT_NEAR(e.yy, 0.0, 1e-15);
  const double mean = e.xx / 3.0;
  const double expected = std::sqrt(std::pow(e.xx - mean, 2) + 2 * mean * mean + 2 * e.xy * e.xy);
  EXPECT_NEAR(strain::deviatoric_norm(e), expected, 1e-15);
}

// The printed form is (I - b)/2; the Euler-Almansi strain (I - b^-1)/2 = (H + H^T - H^T H)/2 with
// H = grad u is [[0, g/2], [g/2, -g^2/2]] in this shear. Their deviatoric norms agree at any g,
// sqrt(g^2/2 + g^4/6) (docs/method.md, "Strain").
TEST(EulerAlmansi, SimpleShearNormIsTheAlmansiStrainsAtAnyShear) {
  for (double g : {0.3, 1.0, 3.0}) {
    strain::AlmansiStrain e;
    ASSERT_TRUE(strain::almansi_strain({0.0, g, 0.0, 0.0}, e));
    const strain::AlmansiStrain almansi{0.0, 0.5 * g, -0.5 * g * g, 0.0};  // xx, xy, yy, hoop
    EXPECT_NEAR(strain::deviatoric_norm(e), strain::deviatoric_norm(almansi), 1e-13 * g * g) << g;
    EXPECT_NEAR(strain::deviatoric_norm(e), std::sqrt(g * g / 2 + g * g * g * g / 6), 1e-13 * g * g) << g;
  }
}

TEST(EulerAlmansi, RigidTranslationAndSingularGradient) {
  strain::AlmansiStrain e;
  EXPECT_TRUE(strain::almansi_strain({0.0, 0.0, 0.0, 0.0}, e));
  EXPECT_DOUBLE_EQ(strain::deviatoric_norm(e), 0.0);
  // A singular gradient leaves no strain of an earlier call behind: e is zeroed.
  ASSERT_TRUE(strain::almansi_strain({0.0, 1.0, 0.0, 0.0}, e));
  ASSERT_GT(strain::deviatoric_norm(e), 0.5);
  EXPECT_FALSE(strain::almansi_strain({1.0, 0.0, 0.0, 1.0}, e));  // F = 0
  EXPECT_DOUBLE_EQ(strain::deviatoric_norm(e), 0.0);
}

TEST(EulerAlmansi, AxisymmetricRadialStretchHasHoopStrain) {
  // Uniform radial expansion r = (1 + k) R, Eulerian displacement u_r = r - R = r k / (1 + k): d u_r/dr
  // and the hoop entry u_r/r are both k/(1+k), so F = diag(1/(1+k), 1, 1/(1+k)) and
  // e = (I - F^-2)/2 = diag((1 - (1+k)^2)/2, 0, (1 - (1+k)^2)/2).
  const double k = 0.2, q = k / (1 + k), e_rr = 0.5 * (1.0 - (1 + k) * (1 + k));
  strain::AlmansiStrain e;
  strain::DisplacementGradient g{q, 0.0, 0.0, 0.0};
  g.hoop = q;
  ASSERT_TRUE(strain::almansi_strain(g, e));
  EXPECT_NEAR(e.xx, e_rr, 1e-15);
  EXPECT_NEAR(e.hoop, e_rr, 1e-15);
  EXPECT_NEAR(e.yy, 0.0, 1e-15);
  // Deviator of diag(a, 0, a): (a/3, -2a/3, a/3), norm |a| sqrt(2/3).
  EXPECT_NEAR(strain::deviatoric_norm(e), std::abs(e_rr) * std::sqrt(2.0 / 3.0), 1e-15);
  g.hoop = 1.0;  // F_thth = 0: singular
  EXPECT_FALSE(strain::almansi_strain(g, e));
}

// In 3D: a gradient in the x-y plane alone gives the planar strain; a rigid rotation (about an axis
// off the grid's) none; shear across the layers and a stretch along z their closed forms; F singular none at all.
TEST(EulerAlmansi, In3dThePlanarStrainRigidRotationsShearAndStretch) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (int t = 0; t < 100; ++t) {
    const double gxx = u(rng), gxy = u(rng), gyx = u(rng), gyy = u(rng);
    strain::AlmansiStrain e2;
    strain::AlmansiStrain3 e3;
    const bool planar = strain::almansi_strain(strain::DisplacementGradient{gxx, gxy, gyx, gyy, 0.0}, e2);
    strain::DisplacementGradient3 g;
    g.g[0][0] = gxx, g.g[0][1] = gxy, g.g[1][0] = gyx, g.g[1][1] = gyy;
    ASSERT_EQ(strain::almansi_strain(g, e3), planar);
    if (!planar) continue;
    EXPECT_NEAR(e3.xx, e2.xx, 1e-12);
    EXPECT_NEAR(e3.yy, e2.yy, 1e-12);
    EXPECT_NEAR(e3.xy, e2.xy, 1e-12);
    EXPECT_EQ(e3.zz, 0.0);
    EXPECT_NEAR(strain::deviatoric_norm(e3), strain::deviatoric_norm(e2), 1e-12);
  }
  // A rigid rotation X = R^T x: u = (I - R^T) x, so F = R^T and G G^T = I.
  const double a = 0.7, b = -0.4;
  const double Rz[3][3] = {{std::cos(a), -std::sin(a), 0}, {std::sin(a), std::cos(a), 0}, {0, 0, 1}};
  const double Rx[3][3] = {{1, 0, 0}, {0, std::cos(b), -std::sin(b)}, {0, std::sin(b), std::cos(b)}};
  double R[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) R[i][j] += Rz[i][k] * Rx[k][j];
  strain::DisplacementGradient3 rotation;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rotation.g[i][j] = (i == j ? 1.0 : 0.0) - R[j][i];
  strain::AlmansiStrain3 e;
  ASSERT_TRUE(strain::almansi_strain(rotation, e));
  for (double component : {e.xx, e.yy, e.zz, e.xy, e.xz, e.yz}) EXPECT_NEAR(component, 0.0, 1e-15);
  // Simple shear of the layers, x = X + s Z: grad u = s e_x e_z^T, e = [[-s^2/2, 0, -s/2], [0, 0, 0], [-s/2, 0, 0]].
  const double s = 0.3;
  strain::DisplacementGradient3 shear;
  shear.g[0][2] = s;
  ASSERT_TRUE(strain::almansi_strain(shear, e));
  EXPECT_NEAR(e.xx, -0.5 * s * s, 1e-15);
  EXPECT_NEAR(e.xz, -0.5 * s, 1e-15);
  EXPECT_NEAR(e.zz, 0.0, 1e-15);
  EXPECT_NEAR(e.xy, 0.0, 1e-15);
  // A stretch along z by l: u_z = z (1 - 1/l), G_zz = l, e_zz = (1 - l^2)/2.
  const double l = 1.25;
  strain::DisplacementGradient3 stretch;
  stretch.g[2][2] = 1.0 - 1.0 / l;
  ASSERT_TRUE(strain::almansi_strain(stretch, e));
  EXPECT_NEAR(e.zz, 0.5 * (1.0 - l * l), 1e-15);
  EXPECT_NEAR(strain::deviatoric_norm(e), std::abs(e.zz) * std::sqrt(2.0 / 3.0), 1e-15);
  stretch.g[2][2] = 1.0;  // F_zz = 0
  EXPECT_FALSE(strain::almansi_strain(stretch, e));
  EXPECT_EQ(strain::deviatoric_norm(e), 0.0);
}

TEST(InitialShapes, BoxCircleAndPolygonFractions) {
  using namespace interface;
  const std::vector<Shape> box{Box{{0.0, 0.0}, {0.2, 0.1}}};
  EXPECT_DOUBLE_EQ(ShapeUnion(box).fraction(0.0, 0.01, 0.0, 0.01), 1.0);
  EXPECT_DOUBLE_EQ(ShapeUnion(box).fraction(0.2, 0.21, 0.0, 0.01), 0.0);
  EXPECT_NEAR(ShapeUnion(box).fraction(0.195, 0.205, 0.0, 0.01), 0.5, 1e-12);
  const std::vector<Shape> circle{Circle{{0.0, 0.0}, 1.0}};
  double area = 0.0;  // quarter of the unit disc on a 64 x 64 grid
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) area += ShapeUnion(circle).fraction(i / 64.0, (i + 1) / 64.0, j / 64.0, (j + 1) / 64.0) / 4096.0;
  EXPECT_NEAR(area, M_PI / 4, 2e-4);
  const std::vector<Shape> triangle{Polygon{{{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}}}};
  EXPECT_NEAR(ShapeUnion(triangle).fraction(0.0, 1.0, 0.0, 1.0, false, 200), 0.5, 1e-2);
  EXPECT_TRUE(union_contains({box[0], circle[0]}, 0.5, 0.5));
}

}  // namespace
}  // namespace granflow
