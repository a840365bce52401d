// Parameter names as the case file spells them, and validation messages naming the culprit.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "models/rheology/granular_rheology.hpp"
#include "models/rheology/parameters.hpp"

namespace granflow::rheology {
namespace {

TEST(RheologyParameters, ModelNamesRoundTripExactly) {
  EXPECT_EQ(parse_model("drucker_prager_bingham"), Model::drucker_prager_bingham);
  EXPECT_EQ(parse_model("drucker_prager"), Model::drucker_prager);
  EXPECT_EQ(parse_model("mohr_coulomb"), Model::mohr_coulomb);
  EXPECT_EQ(parse_model("matsuoka_nakai"), Model::matsuoka_nakai);
  for (auto name : model_names) EXPECT_EQ(to_string(*parse_model(name)), name);
  EXPECT_FALSE(parse_model("Drucker_Prager").has_value());
  EXPECT_FALSE(parse_model("drucker-prager").has_value());
  EXPECT_FALSE(parse_model(" mohr_coulomb").has_value());
  EXPECT_FALSE(parse_model("").has_value());
  EXPECT_FALSE(parse_model("mu_of_I").has_value());  // a friction law, not a model
}

TEST(RheologyParameters, OtherEnumNamesRoundTripExactly) {
  EXPECT_EQ(parse_regularisation("exponential"), Regularisation::exponential);
  EXPECT_EQ(parse_regularisation("clip"), Regularisation::clip);
  EXPECT_FALSE(parse_regularisation("clipping").has_value());
  EXPECT_EQ(parse_friction_source("constant"), FrictionSource::constant);
  EXPECT_EQ(parse_friction_source("mu_of_I"), FrictionSource::mu_of_I);
  EXPECT_FALSE(parse_friction_source("mu_of_i").has_value());
  EXPECT_EQ(parse_yield_surface("mohr_coulomb"), YieldSurface::mohr_coulomb);
  EXPECT_FALSE(parse_yield_surface("drucker_prager_bingham").has_value());
  EXPECT_EQ(parse_matsuoka_nakai_fit("triaxial"), MatsuokaNakaiFit::triaxial);
  EXPECT_EQ(parse_matsuoka_nakai_fit("isochoric_shear"), MatsuokaNakaiFit::isochoric_shear);
  EXPECT_EQ(to_string(Regularisation::clip), "clip");
  EXPECT_EQ(to_string(FrictionSource::mu_of_I), "mu_of_I");
  EXPECT_EQ(to_string(YieldSurface::matsuoka_nakai), "matsuoka_nakai");
}

TEST(RheologyParameters, ModelDeterminesYieldSurface) {
  EXPECT_EQ(yield_surface_of(Model::drucker_prager_bingham), YieldSurface::drucker_prager);
  EXPECT_EQ(yield_surface_of(Model::drucker_prager), YieldSurface::drucker_prager);
  EXPECT_EQ(yield_surface_of(Model::mohr_coulomb), YieldSurface::mohr_coulomb);
  EXPECT_EQ(yield_surface_of(Model::matsuoka_nakai), YieldSurface::matsuoka_nakai);
}

TEST(RheologyParameters, DefaultsAreValidAndFollowThePapers) {
  const RheologyParameters p;
  EXPECT_FALSE(validate(p).has_value());
  EXPECT_EQ(p.min_dynamic_viscosity, 1e-3);     // [VoF] Sec. 2
  EXPECT_EQ(p.min_kinematic_viscosity, 1e-5);   // [YS] Sec. 4
  EXPECT_EQ(p.max_kinematic_viscosity, 1.0);
  EXPECT_EQ(p.matsuoka_nakai_fit, MatsuokaNakaiFit::isochoric_shear);  // [YS] Eq. 34
}

// The message of the first failing check, which must name the parameter.
void expect_rejected(const RheologyParameters& p, const std::string& parameter_name) {
  const auto error = validate(p);
  ASSERT_TRUE(error.has_value()) << parameter_name;
  EXPECT_NE(error->find(parameter_name), std::string::npos) << *error;
  EXPECT_THROW(GranularRheology{p}, std::invalid_argument);
}

TEST(RheologyParameters, ValidationNamesTheBadParameter) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double phi : {0.0, 90.0, 95.0, -5.0, nan}) {
    RheologyParameters p;
    p.friction_angle_deg = phi;
    expect_rejected(p, "friction_angle (phi)");
  }
  for (double phi : {-1e-9, 90.0, nan}) {  // an undrained clay (C > 0) may have phi = 0, no less
    RheologyParameters p;
    p.cohesion = 2e4;
    p.friction_angle_deg = phi;
    expect_rejected(p, "friction_angle (phi)");
  }
  {
    RheologyParameters p;
    p.density = -1430.0;
    expect_rejected(p, "density");
  }
  for (double cohesion : {-1.0, 1.0000001e9, 1e20}) {  // at most 1e9 Pa, beyond any rock
    RheologyParameters p;
    p.cohesion = cohesion;
    expect_rejected(p, "cohesion");
  }
  {
    RheologyParameters p;
    p.cohesion = 1e9;
    EXPECT_FALSE(validate(p).has_value()) << *validate(p);
  }
  {
    RheologyParameters p;
    p.model = Model::mohr_coulomb;
    p.friction = FrictionSource::mu_of_I;
    p.cohesion = 5e3;  // a cohesion is carried by a friction angle, which mu(I) has not
    expect_rejected(p, "cohesion");
  }
  {
    RheologyParameters p;
    p.model = Model::matsuoka_nakai;
    p.cohesion = 5e3;
    p.friction_angle_deg = 0.0;  // its cohesion C cot(phi) on a cone of slope sin(phi): 0 times infinity
    expect_rejected(p, "friction_angle (phi)");
  }
  {
    RheologyParameters p;
    p.regularisation_time = 0.0;
    expect_rejected(p, "m (regularisation time)");
  }
  {
    RheologyParameters p;
    p.min_dynamic_viscosity = -1e-3;
    expect_rejected(p, "mu_min");
  }
  {
    RheologyParameters p;
    p.max_kinematic_viscosity = 1e-6;  // below nu_min
    expect_rejected(p, "nu_max");
  }
  {
    RheologyParameters p;
    p.grain_diameter = 0.0;
    expect_rejected(p, "grain_diameter");
  }
  {
    RheologyParameters p;
    p.static_friction = 1.2;
    expect_rejected(p, "mu_s");
  }
  {
    RheologyParameters p;
    p.limiting_friction = 0.2;  // below mu_s
    expect_rejected(p, "mu_2");
  }
  {
    RheologyParameters p;
    p.reference_inertial_number = -0.3;
    expect_rejected(p, "I_0");
  }
  {
    RheologyParameters p;
    p.model = Model::drucker_prager_bingham;
    p.friction = FrictionSource::mu_of_I;
    expect_rejected(p, "friction");
  }
  {
    RheologyParameters p;
    p.model = static_cast<Model>(17);
    expect_rejected(p, "model");
  }
}

TEST(RheologyParameters, MuOfIWithEveryYieldSurfaceIsValid) {
  for (Model model : {Model::drucker_prager, Model::mohr_coulomb, Model::matsuoka_nakai}) {
    RheologyParameters p;
    p.model = model;
    p.friction = FrictionSource::mu_of_I;
    EXPECT_FALSE(validate(p).has_value()) << to_string(model);
  }
}

}  // namespace
}  // namespace granflow::rheology

namespace granflow::rheology {
namespace {

// phi = 0 with a cohesion: the cone of [VoF] Eqs. 8-9 has alpha_phi = 0 and k_c = C, a yield stress C
// at every pressure (Tresca's c_u in plane strain).
// The same for the Drucker-Prager cone and Mohr-Coulomb of [YS] with a cohesion (von Mises and Tresca):
// C in plane shear; Tresca's C / cos(theta) elsewhere, 2 C / sqrt3 in triaxial compression.
TEST(RheologyParameters, UndrainedClayYieldsAtItsCohesionAtAnyPressure) {
  const StrainRate shear = planar_strain_rate(0.0, 0.0, 0.5);
  const double a = 2.0 / std::numbers::sqrt3, b = 1.0 / std::numbers::sqrt3;
  const StrainRate compression{-a, b, b, 0, 0, 0};
  for (Model model : {Model::drucker_prager_bingham, Model::drucker_prager, Model::mohr_coulomb}) {
    SCOPED_TRACE(std::string(to_string(model)));
    RheologyParameters p;
    p.model = model;
    p.friction_angle_deg = 0.0;
    p.cohesion = 2.5e4;
    ASSERT_FALSE(validate(p).has_value());
    const GranularRheology clay(p);
    for (double pressure : {0.0, 1e3, 1e6}) {
      EXPECT_DOUBLE_EQ(clay.evaluate(shear, pressure).yield_stress, 2.5e4) << pressure;
      EXPECT_NEAR(clay.evaluate(compression, pressure).yield_stress,
                  model == Model::mohr_coulomb ? 2.0 * 2.5e4 / std::numbers::sqrt3 : 2.5e4, 1e-9 * 2.5e4)
          << pressure;
    }
  }
}

// A c-phi soil on the [YS] surfaces: in plane shear (theta = 0) each gives Mohr-Coulomb's
// (sigma_1 - sigma_3) / 2 = p sin(phi) + C cos(phi), so the cohesion adds C cos(phi) at every pressure;
// with the pressure clipped at zero what is left in tension is that cohesive part alone.
TEST(RheologyParameters, CohesionAddsTheMohrCoulombStrengthInPlaneShear) {
  const StrainRate shear = planar_strain_rate(0.3, -0.3, 0.2);
  const double phi = 25.0 * std::numbers::pi / 180.0, cohesion = 5e3;
  for (Model model : {Model::drucker_prager, Model::mohr_coulomb, Model::matsuoka_nakai}) {
    SCOPED_TRACE(std::string(to_string(model)));
    RheologyParameters p;
    p.model = model;
    p.friction_angle_deg = 25.0;
    p.cohesion = cohesion;
    ASSERT_FALSE(validate(p).has_value());
    const GranularRheology soil(p);
    for (double pressure : {0.0, 2e3, 1e5}) {
      EXPECT_NEAR(soil.evaluate(shear, pressure).yield_stress,
                  pressure * std::sin(phi) + cohesion * std::cos(phi), 1e-10 * (pressure + cohesion))
          << pressure;
    }
    EXPECT_DOUBLE_EQ(soil.evaluate(shear, -3e3).yield_stress, soil.evaluate(shear, 0.0).yield_stress);
  }
}

}  // namespace
}  // namespace granflow::rheology
