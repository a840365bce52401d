#include "io/case_advice.hpp"

#include <fmt/format.h>

namespace granflow {

std::vector<std::string> case_advice(const CaseConfig& config) {
  std::vector<std::string> advice;
  for (double t : config.output.times)
    if (t > config.time.end) {
      advice.push_back(fmt::format("output.times: {} s lies past time.end = {} s and is not written", t, config.time.end));
      break;
    }
  for (const auto& key : config.keys_without_effect) advice.push_back(key + "; this case gives it to no effect");
  if (!config.soil || !config.soil->rheology) return advice;
  // Valid values that are most often a slip in a granular case (a Newtonian pair of fluids may be
  // driven by its walls, or light): no gravity, gravity upwards, grams per cubic centimetre, radians.
  const auto& g = config.flow.gravity;
  const bool layers = config.mesh.dimension() == 3;
  const std::string given = layers ? fmt::format("[{}, {}, {}]", g[0], g[1], g[2]) : fmt::format("[{}, {}]", g[0], g[1]);
  if (g[0] == 0.0 && g[1] == 0.0 && g[2] == 0.0)
    advice.push_back(fmt::format("physics.gravity is {} (the default without [physics]): the soil has no weight", given));
  else if (g[1] > 0.0)
    advice.push_back(fmt::format("physics.gravity = {} points up (+y): the soil falls towards the top", given));
  if (config.soil->soil_density < 100.0)
    advice.push_back(fmt::format("soil.density = {} kg/m^3 is lighter than any soil (a density in g/cm^3 is 1000 times "
                                 "smaller than in kg/m^3)", config.soil->soil_density));
  if (config.soil->soil_density <= config.soil->air_density)
    advice.push_back(fmt::format("soil.density = {} kg/m^3 is not heavier than air.density = {} kg/m^3",
                                 config.soil->soil_density, config.soil->air_density));
  for (size_t k = 0; k < config.soil->materials.size(); ++k) {
    const auto& m = config.soil->materials[k];
    const double density = m.rheology.density;
    if (density == config.soil->soil_density) continue;  // said above, if at all
    if (density < 100.0)
      advice.push_back(fmt::format("soil.materials[{}].density = {} kg/m^3 ('{}') is lighter than any soil", k, density, m.name));
    else if (density <= config.soil->air_density)
      advice.push_back(fmt::format("soil.materials[{}].density = {} kg/m^3 ('{}') is not heavier than air.density = {} kg/m^3",
                                   k, density, m.name, config.soil->air_density));
  }
  auto radians_hint = [&](double degrees, const std::string& key) {
    if (degrees > 0.0 && degrees < 1.0)
      advice.push_back(fmt::format("{} = {} is in degrees: {} rad would be {:.3g} deg", key, degrees, degrees,
                                   degrees * 57.29577951308232));
  };
  auto radians = [&](const rheology::RheologyParameters& r, const std::string& key) {
    if (r.friction != rheology::FrictionSource::mu_of_I) radians_hint(r.friction_angle_deg, key);
  };
  const auto& r = *config.soil->rheology;
  radians(r, "soil.rheology.friction_angle");
  for (size_t k = 0; k < config.soil->materials.size(); ++k)
    if (config.soil->materials[k].rheology.friction_angle_deg != r.friction_angle_deg)  // said above, if at all
      radians(config.soil->materials[k].rheology, fmt::format("soil.materials[{}].friction_angle", k));
  auto wall_radians = [&](const std::optional<rheology::WallFriction>& friction, const std::string& wall) {
    if (friction) radians_hint(friction->friction_angle_degrees, wall + ".friction_angle");
  };
  for (Side side : sides_of_dimension(layers ? 3 : 2))
    wall_radians(boundary(config.flow.boundaries, side).friction, fmt::format("boundary.{}", side_name(side)));
  for (size_t k = 0; k < config.obstacle_friction.size(); ++k)
    wall_radians(config.obstacle_friction[k], fmt::format("obstacle[{}]", k));
  // The exponential regularisation ([VoF] Eq. 12) puts the soil at rest at up to m (3 alpha_phi p + k_c),
  // some 1e8 Pa s. Only the coupled solve with the face's own soil fraction holds such a pile next to
  // air (docs/method.md, "Known limitations"; docs/validation.md).
  const bool exponential = config.soil->rheology->regularisation == rheology::Regularisation::exponential;
  const bool holds_rest = config.flow.numerics.pressure_coupling == PressureCoupling::coupled &&
                          config.soil->face_fraction == FaceFraction::face;
  if (exponential && !holds_rest)
    advice.push_back(fmt::format(
        "soil.rheology.regularisation = \"exponential\" with numerics.pressure_coupling = \"{}\" and "
        "soil.face_fraction = \"{}\": a pile may not come to rest next to air. Soil at the exponential "
        "regularisation's viscosities is held by numerics.pressure_coupling = \"coupled\" with "
        "soil.yield_pressure, soil.strain_rate and soil.face_fraction = \"face\" (the example of docs/case_file.md)",
        config.flow.numerics.pressure_coupling == PressureCoupling::coupled      ? "coupled"
        : config.flow.numerics.pressure_coupling == PressureCoupling::projection ? "projection"
                                                                                 : "piso",
        config.soil->face_fraction == FaceFraction::face ? "face" : "cells"));
  return advice;
}

}  // namespace granflow
