#include "models/rheology/parameters.hpp"

#include <cmath>
#include <cstddef>

#include <fmt/format.h>

namespace granflow::rheology {

namespace {

// Enumerators are declared in the order of their name arrays.
template <typename Enum, std::size_t N>
std::string_view name_of(Enum value, const std::array<std::string_view, N>& names) noexcept {
  const auto index = static_cast<std::size_t>(value);
  return index < N ? names[index] : std::string_view{"invalid"};
}

template <typename Enum, std::size_t N>
std::optional<Enum> parse_name(std::string_view name,
                               const std::array<std::string_view, N>& names) noexcept {
  for (std::size_t i = 0; i < N; ++i) {
    if (names[i] == name) return static_cast<Enum>(i);
  }
  return std::nullopt;
}

template <typename Enum, std::size_t N>
bool is_listed(Enum value, const std::array<std::string_view, N>&) noexcept {
  return static_cast<std::size_t>(value) < N;
}

std::string bad(std::string_view name, double value, std::string_view requirement) {
  return fmt::format("rheology parameter {} = {} {}", name, value, requirement);
}

}  // namespace

std::string_view to_string(Model value) noexcept { return name_of(value, model_names); }
std::string_view to_string(YieldSurface value) noexcept {
  return name_of(value, yield_surface_names);
}
std::string_view to_string(FrictionSource value) noexcept {
  return name_of(value, friction_source_names);
}
std::string_view to_string(Regularisation value) noexcept {
  return name_of(value, regularisation_names);
}
std::string_view to_string(MatsuokaNakaiFit value) noexcept {
  return name_of(value, matsuoka_nakai_fit_names);
}

std::optional<Model> parse_model(std::string_view name) noexcept {
  return parse_name<Model>(name, model_names);
}
std::optional<YieldSurface> parse_yield_surface(std::string_view name) noexcept {
  return parse_name<YieldSurface>(name, yield_surface_names);
}
std::optional<FrictionSource> parse_friction_source(std::string_view name) noexcept {
  return parse_name<FrictionSource>(name, friction_source_names);
}
std::optional<Regularisation> parse_regularisation(std::string_view name) noexcept {
  return parse_name<Regularisation>(name, regularisation_names);
}
std::optional<MatsuokaNakaiFit> parse_matsuoka_nakai_fit(std::string_view name) noexcept {
  return parse_name<MatsuokaNakaiFit>(name, matsuoka_nakai_fit_names);
}

std::optional<std::string> validate(const RheologyParameters& p) {
  if (!is_listed(p.model, model_names)) return "rheology parameter model has an invalid value";
  if (!is_listed(p.friction, friction_source_names)) {
    return "rheology parameter friction has an invalid value";
  }
  if (!is_listed(p.regularisation, regularisation_names)) {
    return "rheology parameter regularisation has an invalid value";
  }
  if (!is_listed(p.matsuoka_nakai_fit, matsuoka_nakai_fit_names)) {
    return "rheology parameter matsuoka_nakai_fit has an invalid value";
  }
  // Negated comparisons so that NaN fails every check.
  // phi = 0 with C > 0 is an undrained clay: the Drucker-Prager cones are then von Mises, Mohr-Coulomb
  // is Tresca, each in plane strain with c_u = C ([VoF] Eq. 9 with tan(phi) = 0). Matsuoka-Nakai takes
  // its cohesion as C cot(phi) on a cone of slope sin(phi), which at phi = 0 is infinity times zero
  // (its limit is von Mises, the drucker_prager model), so it keeps phi > 0.
  if (!(p.cohesion >= 0.0 && std::isfinite(p.cohesion))) {
    return bad("cohesion (C)", p.cohesion, "must be finite and >= 0 Pa");
  }
  // Beyond any rock's; the viscosity of a block that stands grows with it, and at 1e15 Pa its ratio to
  // the air's passes what the solve can resolve in double precision (steps taken again by the thousand).
  if (p.cohesion > max_cohesion) {
    return bad("cohesion (C)", p.cohesion,
               "must be at most 1e9 Pa (beyond the cohesion of any rock; a block that must not move needs far less)");
  }
  const bool undrained = p.cohesion > 0.0 && p.model != Model::matsuoka_nakai;
  if (!((undrained ? p.friction_angle_deg >= 0.0 : p.friction_angle_deg > 0.0) && p.friction_angle_deg < 90.0)) {
    return bad("friction_angle (phi)", p.friction_angle_deg,
               undrained ? "must lie in [0, 90) degrees"
               : p.model == Model::matsuoka_nakai
                   ? "must lie in (0, 90) degrees (with matsuoka_nakai also with a cohesion; at phi = 0 it is drucker_prager)"
                   : "must lie in (0, 90) degrees ([0, 90) with a cohesion)");
  }
  // The cohesion is carried to a surface through its friction angle (the apex at p = -C cot(phi));
  // a friction from mu(I) has no angle to carry it.
  if (p.cohesion > 0.0 && p.friction == FrictionSource::mu_of_I) {
    return bad("cohesion (C)", p.cohesion,
               "needs friction = \"constant\" (a friction angle); set it to 0 with friction = \"mu_of_I\"");
  }
  if (!(p.regularisation_time > 0.0 && std::isfinite(p.regularisation_time))) {
    return bad("m (regularisation time)", p.regularisation_time, "must be finite and > 0 s");
  }
  if (!(p.min_dynamic_viscosity >= 0.0 && std::isfinite(p.min_dynamic_viscosity))) {
    return bad("mu_min", p.min_dynamic_viscosity,
               "must be finite and >= 0 Pa s");
  }
  if (!(p.min_kinematic_viscosity >= 0.0 && std::isfinite(p.min_kinematic_viscosity))) {
    return bad("nu_min", p.min_kinematic_viscosity,
               "must be finite and >= 0 m^2/s");
  }
  if (!(p.max_kinematic_viscosity > p.min_kinematic_viscosity &&
        std::isfinite(p.max_kinematic_viscosity))) {
    return bad("nu_max", p.max_kinematic_viscosity,
               fmt::format("must be finite and > nu_min = {} m^2/s",
                           p.min_kinematic_viscosity));
  }
  if (!(p.density > 0.0 && std::isfinite(p.density))) {
    return bad("density (rho_s)", p.density, "must be finite and > 0 kg/m^3");
  }
  if (!(p.grain_diameter > 0.0 && std::isfinite(p.grain_diameter))) {
    return bad("grain_diameter (d)", p.grain_diameter, "must be finite and > 0 m");
  }
  // mu_s and mu_2 replace sin(phi), so they must stay in (0, 1) like a sine.
  if (!(p.static_friction > 0.0 && p.static_friction < 1.0)) {
    return bad("mu_s", p.static_friction, "must lie in (0, 1)");
  }
  if (!(p.limiting_friction >= p.static_friction && p.limiting_friction < 1.0)) {
    return bad("mu_2", p.limiting_friction,
               fmt::format("must lie in [mu_s = {}, 1)", p.static_friction));
  }
  if (!(p.reference_inertial_number > 0.0 && std::isfinite(p.reference_inertial_number))) {
    return bad("I_0", p.reference_inertial_number,
               "must be finite and > 0");
  }
  if (p.friction == FrictionSource::mu_of_I && p.model == Model::drucker_prager_bingham) {
    return std::string{
        "rheology parameter friction = mu_of_I needs model drucker_prager, mohr_coulomb or "
        "matsuoka_nakai (drucker_prager_bingham is parametrised by phi and C)"};
  }
  return std::nullopt;
}

}  // namespace granflow::rheology
