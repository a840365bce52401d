// The stress ratio of Mohr-Coulomb and Matsuoka-Nakai to Drucker-Prager ([YS] Figs. 8, 11, 15) on
// the axisymmetric strain rates of a collapsing cylinder, against [YS] Table 1; and the Lode-angle
// histogram of the dissipated energy ([YS] Fig. 17).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "models/rheology/granular_rheology.hpp"
#include "models/rheology/lode_histogram.hpp"

namespace granflow::rheology {
namespace {

GranularRheology rheology_of(Model model) {
  RheologyParameters p;
  p.model = model;
  p.friction_angle_deg = 36.5;
  p.regularisation = Regularisation::clip;
  p.density = 1430.0;
  return GranularRheology(p);
}

// Axial compression of a column (D_zz < 0, D_rr = D_thth > 0): triaxial compression, theta = -30;
// axial stretching: triaxial extension, theta = +30; no hoop rate with D_rr = -D_zz: isochoric shear.
TEST(StressRatio, AxisymmetricDeformationsMatchTable1) {
  const StrainRate compression = axisymmetric_strain_rate(0.577, -1.155, 0.0, 0.577);
  const StrainRate extension = axisymmetric_strain_rate(-0.577, 1.155, 0.0, -0.577);
  const StrainRate shear = axisymmetric_strain_rate(1.0, -1.0, 0.0, 0.0);
  EXPECT_NEAR(lode_angle(compression) * 180.0 / M_PI, -30.0, 1e-3);
  EXPECT_NEAR(lode_angle(extension) * 180.0 / M_PI, 30.0, 1e-3);
  const auto mc = rheology_of(Model::mohr_coulomb), mn = rheology_of(Model::matsuoka_nakai);
  const auto dp = rheology_of(Model::drucker_prager);
  // Table 1 "relative" column, printed to two decimals (MN compression: the self-consistent 1.28,
  // see test_element_test.cpp for the misprint).
  EXPECT_NEAR(mc.stress_ratio_to_drucker_prager(compression, 100.0), 1.44, 0.005);
  EXPECT_NEAR(mn.stress_ratio_to_drucker_prager(compression, 100.0), 1.28, 0.005);
  EXPECT_NEAR(mc.stress_ratio_to_drucker_prager(extension, 100.0), 0.96, 0.005);
  EXPECT_NEAR(mn.stress_ratio_to_drucker_prager(extension, 100.0), 0.89, 0.005);
  EXPECT_NEAR(mc.stress_ratio_to_drucker_prager(shear, 100.0), 1.0, 1e-12);
  EXPECT_NEAR(mn.stress_ratio_to_drucker_prager(shear, 100.0), 1.0, 1e-9);
  EXPECT_EQ(dp.stress_ratio_to_drucker_prager(compression, 100.0), 1.0);
  EXPECT_EQ(mc.stress_ratio_to_drucker_prager(StrainRate{}, 100.0), 1.0);  // at rest
  // The ratio is the ratio of the viscosities at the same state, below the clip.
  const double p = 100.0;
  const StrainRate fast = 50.0 * compression;
  EXPECT_NEAR(mc.dynamic_viscosity(fast, p) / dp.dynamic_viscosity(fast, p), mc.stress_ratio_to_drucker_prager(fast, p),
              1e-12);
}

// With a cohesion each surface is its cohesionless cone at p + C cot(phi), so the ratio is the
// cones' and does not depend on C; at phi = 0 Mohr-Coulomb is Tresca, 2 / sqrt3 of von Mises in
// triaxial compression. It is still the ratio of the viscosities at the same state.
TEST(StressRatio, ACohesionLeavesTheRatioOfTheCones) {
  const StrainRate compression = axisymmetric_strain_rate(0.577, -1.155, 0.0, 0.577);
  auto with = [](Model model, double phi, double cohesion) {
    RheologyParameters q;
    q.model = model;
    q.friction_angle_deg = phi;
    q.cohesion = cohesion;
    q.regularisation = Regularisation::clip;
    q.density = 1430.0;
    return GranularRheology(q);
  };
  for (Model model : {Model::mohr_coulomb, Model::matsuoka_nakai}) {
    const double cohesionless = with(model, 36.5, 0.0).stress_ratio_to_drucker_prager(compression, 100.0);
    EXPECT_NEAR(with(model, 36.5, 5e3).stress_ratio_to_drucker_prager(compression, 100.0), cohesionless, 1e-12);
    EXPECT_NEAR(with(model, 36.5, 5e3).stress_ratio_to_drucker_prager(compression, 0.0), cohesionless, 1e-12);
  }
  const auto tresca = with(Model::mohr_coulomb, 0.0, 5e3), von_mises = with(Model::drucker_prager, 0.0, 5e3);
  EXPECT_NEAR(tresca.stress_ratio_to_drucker_prager(compression, 100.0), 2.0 / std::sqrt(3.0), 1e-3);
  const StrainRate fast = 1e3 * compression;  // above the clip's smallest viscosity
  EXPECT_NEAR(tresca.dynamic_viscosity(fast, 100.0) / von_mises.dynamic_viscosity(fast, 100.0),
              tresca.stress_ratio_to_drucker_prager(fast, 100.0), 1e-12);
}

// With mu(I) friction the Mohr-Coulomb and Matsuoka-Nakai ratios depend on mu, which depends on the
// pressure through I: the ratio is the viscosities' ratio at the cell's own state, not at 1 Pa.
TEST(StressRatio, MuOfIAtTheCellsPressure) {
  for (Model model : {Model::mohr_coulomb, Model::matsuoka_nakai}) {
    RheologyParameters p;
    p.model = model;
    p.friction = FrictionSource::mu_of_I;
    p.regularisation = Regularisation::clip;
    p.max_kinematic_viscosity = 1e6;  // not reached: the ratio of the viscosities is that of the stresses
    p.density = 1430.0;
    const GranularRheology surface(p);
    RheologyParameters q = p;
    q.model = Model::drucker_prager;
    const GranularRheology dp(q);
    const StrainRate compression = 20.0 * axisymmetric_strain_rate(0.577, -1.155, 0.0, 0.577);
    for (double pressure : {10.0, 300.0}) {
      const double ratio = surface.stress_ratio_to_drucker_prager(compression, pressure);
      EXPECT_NEAR(ratio, surface.dynamic_viscosity(compression, pressure) / dp.dynamic_viscosity(compression, pressure),
                  1e-12)
          << int(model) << " " << pressure;
    }
    // mu differs between the two pressures (I = 2 ||D|| d / sqrt(p / rho_s)), and so does the ratio.
    EXPECT_GT(std::abs(surface.stress_ratio_to_drucker_prager(compression, 10.0) -
                       surface.stress_ratio_to_drucker_prager(compression, 300.0)),
              1e-3);
  }
}

TEST(LodeHistogram, BinsCentredOnZeroAndTheTriaxialLimits) {
  LodeHistogram h;  // 31 bins of 2 degrees
  EXPECT_EQ(h.bins(), 31);
  EXPECT_DOUBLE_EQ(h.bin_width_deg(), 2.0);
  EXPECT_EQ(h.bin_of(0.0), 15);
  EXPECT_EQ(h.bin_of(0.99), 15);
  EXPECT_EQ(h.bin_of(-0.99), 15);
  EXPECT_EQ(h.bin_of(1.01), 16);
  EXPECT_EQ(h.bin_of(-30.0), 0);
  EXPECT_EQ(h.bin_of(30.0), 30);
  EXPECT_EQ(h.bin_of(45.0), 30);  // out of range: clamped
  EXPECT_EQ(h.bin_of(std::numeric_limits<double>::quiet_NaN()), 15);
  EXPECT_DOUBLE_EQ(h.lower_edge_deg(0), -31.0);
  EXPECT_DOUBLE_EQ(h.centre_deg(15), 0.0);
  h.add(-29.5, 1.0);
  h.add(0.3, 2.0);
  h.add(0.4, 0.5);
  EXPECT_DOUBLE_EQ(h.energy(0), 1.0);
  EXPECT_DOUBLE_EQ(h.energy(15), 2.5);
  EXPECT_DOUBLE_EQ(h.total(), 3.5);
  EXPECT_EQ(LodeHistogram(4).bins(), 5);  // made odd
}

// The relative shear stress 2 eta ||D|| / tau_y: under the exponential regularisation ([VoF] Eq. 12)
// 1 - exp(-2 m ||D||) + 2 mu_min ||D|| / tau_y, so 0 at rest, 1 - 1/e at ||D|| = 1 / (2 m) and 1 (plus
// the floor's share) well above; under the clip the kinematic cap nu_max holds it below 1 at slow rates;
// 1 where the soil has no strength (no pressure, no cohesion).
TEST(StressRatio, RelativeShearStressIsTheMobilisedShareOfTheStrength) {
  RheologyParameters p;
  p.model = Model::drucker_prager_bingham;
  p.friction_angle_deg = 30.0;
  p.regularisation_time = 1e5;  // m
  p.min_dynamic_viscosity = 1e-3;  // mu_min
  const GranularRheology dpb(p);
  const double pressure = 1e4;
  const double tau = dpb.evaluate(planar_strain_rate(1.0, -1.0, 0.0), pressure).yield_stress;
  ASSERT_GT(tau, 0.0);
  auto shear = [](double rate_norm) { return planar_strain_rate(0.0, 0.0, rate_norm); };  // ||D|| = D_xy
  EXPECT_NEAR(norm(deviatoric(shear(0.3))), 0.3, 1e-15);
  EXPECT_EQ(dpb.relative_shear_stress(shear(0.0), pressure), 0.0);
  EXPECT_NEAR(dpb.relative_shear_stress(shear(0.5 / p.regularisation_time), pressure), 1.0 - std::exp(-1.0) + 1e-3 / (p.regularisation_time * tau), 1e-12);
  EXPECT_NEAR(dpb.relative_shear_stress(shear(10.0), pressure), 1.0 + 2.0 * 1e-3 * 10.0 / tau, 1e-12);
  EXPECT_EQ(dpb.relative_shear_stress(shear(10.0), 0.0), 1.0);    // no pressure, no cohesion: no strength
  EXPECT_EQ(dpb.relative_shear_stress(shear(10.0), -5e3), 1.0);  // tension: none either
  // Drucker-Prager with the clip ([YS] Sec. 2.4): eta = clamp(tau / (2 ||D||), rho nu_min, rho nu_max).
  const auto dp = rheology_of(Model::drucker_prager);
  const double tau_dp = dp.evaluate(shear(1.0), pressure).yield_stress;
  const double slow = 1e-6, cap = 1430.0 * 1.0;  // nu_max = 1 m^2/s by default
  ASSERT_GT(tau_dp / (2.0 * slow), cap);
  EXPECT_NEAR(dp.relative_shear_stress(shear(slow), pressure), 2.0 * cap * slow / tau_dp, 1e-12);
  EXPECT_NEAR(dp.relative_shear_stress(shear(1e3), pressure), 1.0, 1e-12);
}

}  // namespace
}  // namespace granflow::rheology
