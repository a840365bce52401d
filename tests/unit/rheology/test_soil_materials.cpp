// Several soils of one rheology: each material's strength alone, and a shared point's yield stress as
// the share-weighted mean of theirs.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "models/rheology/soil_materials.hpp"

namespace granflow::rheology {
namespace {

RheologyParameters clay() {
  RheologyParameters p;
  p.friction_angle_deg = 0.0;
  p.cohesion = 2e4;
  p.regularisation_time = 1e5;
  p.min_dynamic_viscosity = 1e-3;
  return p;
}

// The base's parameters with another strength (and yield surface).
RheologyParameters with_strength(const RheologyParameters& base, double phi, double cohesion,
                                 std::optional<Model> model = std::nullopt) {
  RheologyParameters p = base;
  p.friction_angle_deg = phi;
  p.cohesion = cohesion;
  if (model) p.model = *model;
  return p;
}

TEST(SoilMaterials, EachMaterialAloneIsItsOwnRheology) {
  const SoilMaterials soils(clay(), {with_strength(clay(), 0.0, 1e4), with_strength(clay(), 30.0, 0.0)});
  ASSERT_EQ(soils.count(), 3);
  const StrainRate rate = planar_strain_rate(0.3, -0.3, 0.2);
  const double pressure = 5e4;
  SoilMaterials::Shares shares{};
  EXPECT_EQ(soils.dynamic_viscosity(rate, pressure, shares.data()), GranularRheology(clay()).dynamic_viscosity(rate, pressure));
  shares[0] = 1.0;
  EXPECT_DOUBLE_EQ(soils.dynamic_viscosity(rate, pressure, shares.data()),
                   GranularRheology(with_strength(clay(), 0.0, 1e4)).dynamic_viscosity(rate, pressure));
  shares = {};
  shares[1] = 1.0;
  EXPECT_DOUBLE_EQ(soils.dynamic_viscosity(rate, pressure, shares.data()),
                   GranularRheology(with_strength(clay(), 30.0, 0.0)).dynamic_viscosity(rate, pressure));
}

// Half the soft clay (C = 1e4), a quarter each of the base (2e4) and the sand: the yield stress is
// 0.5 1e4 + 0.25 2e4 + 0.25 (3 alpha_phi p), regularised once ([VoF] Eq. 12):
// eta = mu_min + tau (1 - exp(-2 m ||D||)) / (2 ||D||).
TEST(SoilMaterials, ASharedPointYieldsAtTheShareWeightedMeanStress) {
  const SoilMaterials soils(clay(), {with_strength(clay(), 0.0, 1e4), with_strength(clay(), 30.0, 0.0)});
  const StrainRate rate = planar_strain_rate(0.0, 0.0, 0.5);
  const double pressure = 5e4;
  const double sand = GranularRheology(with_strength(clay(), 30.0, 0.0)).evaluate(rate, pressure).yield_stress;
  const double tau = 0.5 * 1e4 + 0.25 * 2e4 + 0.25 * sand;
  const double d = norm(deviatoric(rate));
  const double expected = 1e-3 + tau * (1.0 - std::exp(-2e5 * d)) / (2.0 * d);
  SoilMaterials::Shares shares{};
  shares[0] = 0.5;
  shares[1] = 0.25;
  EXPECT_NEAR(soils.dynamic_viscosity(rate, pressure, shares.data()), expected, 1e-12 * expected);
}

// The stress ratio to Drucker-Prager of Mohr-Coulomb soils of 20 and 40 deg, half and half: the mean of
// theirs (each depends on its friction), and each alone its own.
TEST(SoilMaterials, StressRatioIsTheSharesMeanOfTheMaterials) {
  RheologyParameters sand;
  sand.model = Model::mohr_coulomb;
  sand.friction_angle_deg = 20.0;
  const SoilMaterials soils(sand, {with_strength(sand, 40.0, 0.0)});
  const StrainRate compression{-1.0, 0.5, 0.5, 0.0, 0.0, 0.0};  // triaxial: the ratio is not 1 here
  const double loose = GranularRheology(sand).stress_ratio_to_drucker_prager(compression, 1e3);
  const double dense = GranularRheology(with_strength(sand, 40.0, 0.0)).stress_ratio_to_drucker_prager(compression, 1e3);
  ASSERT_GT(std::abs(loose - dense), 1e-3);
  SoilMaterials::Shares shares{};
  EXPECT_DOUBLE_EQ(soils.stress_ratio_to_drucker_prager(compression, 1e3, shares.data()), loose);
  shares[0] = 0.5;
  EXPECT_DOUBLE_EQ(soils.stress_ratio_to_drucker_prager(compression, 1e3, shares.data()), 0.5 * (loose + dense));
}

// The relative shear stress of shared-out soil: its viscosity's stress over the shares' mean yield
// stress. Alone, each material's own; half and half at a rate well above yield, 1 (plus the floor's share).
TEST(SoilMaterials, RelativeShearStressOfTheSharedOutSoil) {
  RheologyParameters sand;
  sand.friction_angle_deg = 20.0;
  const RheologyParameters dense = with_strength(sand, 40.0, 0.0);
  const SoilMaterials soils(sand, {dense});
  const StrainRate slow = planar_strain_rate(0.0, 0.0, 2e-6), fast = planar_strain_rate(0.0, 0.0, 5.0);
  SoilMaterials::Shares shares{};
  EXPECT_DOUBLE_EQ(soils.relative_shear_stress(slow, 1e3, shares.data()), GranularRheology(sand).relative_shear_stress(slow, 1e3));
  shares[0] = 1.0;
  EXPECT_DOUBLE_EQ(soils.relative_shear_stress(slow, 1e3, shares.data()), GranularRheology(dense).relative_shear_stress(slow, 1e3));
  shares[0] = 0.5;
  const double tau = 0.5 * (GranularRheology(sand).evaluate(fast, 1e3).yield_stress + GranularRheology(dense).evaluate(fast, 1e3).yield_stress);
  EXPECT_NEAR(soils.relative_shear_stress(fast, 1e3, shares.data()), 1.0 + 2.0 * sand.min_dynamic_viscosity * 5.0 / tau, 1e-12);
  EXPECT_NEAR(soils.relative_shear_stress(slow, 1e3, shares.data()), 1.0 - std::exp(-2.0 * sand.regularisation_time * 2e-6) + 2.0 * sand.min_dynamic_viscosity * 2e-6 / tau, 1e-12);
}

// A material of its own yield surface: a Matsuoka-Nakai sand (phi = 30 deg) in a case of
// Drucker-Prager-Bingham clay. Alone it is its own rheology, Lode angle and all, even where the base's
// surface needs none; half and half, the mean of the two yield stresses regularised once.
TEST(SoilMaterials, AMaterialMayHaveItsOwnYieldSurface) {
  const RheologyParameters sand = with_strength(clay(), 30.0, 0.0, Model::matsuoka_nakai);
  const SoilMaterials soils(clay(), {sand});
  const StrainRate compression{-1.0, 0.5, 0.5, 0.0, 0.0, 0.0};  // triaxial: Matsuoka-Nakai is not Drucker-Prager here
  const double pressure = 5e4;
  const GranularRheology own(sand);
  ASSERT_EQ(own.parameters().model, Model::matsuoka_nakai);
  RheologyParameters drucker_prager = sand;
  drucker_prager.model = Model::drucker_prager;
  const double tau = own.evaluate(compression, pressure).yield_stress;
  ASSERT_GT(std::abs(tau / GranularRheology(drucker_prager).evaluate(compression, pressure).yield_stress - 1.0), 0.05);
  SoilMaterials::Shares shares{};
  shares[0] = 1.0;
  EXPECT_DOUBLE_EQ(soils.dynamic_viscosity(compression, pressure, shares.data()), own.dynamic_viscosity(compression, pressure));
  shares[0] = 0.5;
  const double d = norm(deviatoric(compression));
  const double mean = 0.5 * (tau + 2e4);
  const double expected = 1e-3 + mean * (1.0 - std::exp(-2e5 * d)) / (2.0 * d);
  EXPECT_NEAR(soils.dynamic_viscosity(compression, pressure, shares.data()), expected, 1e-12 * expected);
}

// A mu(I) sand (its inertial number with its own density) beside the clay: alone its own rheology.
// A material of another regularisation is refused: a point's mixed yield stress is regularised once.
TEST(SoilMaterials, AMaterialMayHaveItsOwnFrictionLaw) {
  RheologyParameters sand = clay();
  sand.model = Model::drucker_prager;
  sand.friction = FrictionSource::mu_of_I;
  sand.cohesion = 0.0;
  sand.friction_angle_deg = 30.0;  // not read under mu(I)
  sand.density = 1500.0;
  const SoilMaterials soils(clay(), {sand});
  const StrainRate rate = planar_strain_rate(0.0, 0.0, 20.0);
  SoilMaterials::Shares shares{};
  shares[0] = 1.0;
  const double own = GranularRheology(sand).dynamic_viscosity(rate, 2e3);
  RheologyParameters heavier = sand;
  heavier.density = 2650.0;
  ASSERT_GT(std::abs(own / GranularRheology(heavier).dynamic_viscosity(rate, 2e3) - 1.0), 1e-3);  // I reads the density
  EXPECT_DOUBLE_EQ(soils.dynamic_viscosity(rate, 2e3, shares.data()), own);
  RheologyParameters other = sand;
  other.regularisation_time = 10.0;
  EXPECT_THROW(SoilMaterials(clay(), {other}), std::invalid_argument);
}

TEST(SoilMaterials, RefusesAnUnusableMaterialNamingIt) {
  try {
    SoilMaterials(clay(), {with_strength(clay(), 0.0, 1e4), with_strength(clay(), 0.0, 0.0)});  // phi = 0 and no cohesion: no strength at all
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("soil material 2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("friction_angle"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace granflow::rheology
