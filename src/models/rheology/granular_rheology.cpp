#include "models/rheology/granular_rheology.hpp"

#include <stdexcept>

namespace granflow::rheology {

namespace {

const RheologyParameters& checked(const RheologyParameters& parameters) {
  if (auto error = validate(parameters)) throw std::invalid_argument(*error);
  return parameters;
}

}  // namespace

GranularRheology::GranularRheology(const RheologyParameters& parameters)
    : parameters_(checked(parameters)),
      model_(parameters.model),
      friction_(parameters.friction),
      regularisation_(parameters.regularisation),
      mn_fit_(parameters.matsuoka_nakai_fit),
      needs_lode_angle_(yield_surface_of(parameters.model) != YieldSurface::drucker_prager),
      sin_phi_(std::sin(degrees_to_radians(parameters.friction_angle_deg))),
      cohesion_cos_phi_(parameters.cohesion * std::cos(degrees_to_radians(parameters.friction_angle_deg))),
      attraction_(sin_phi_ > 0.0 ? cohesion_cos_phi_ / sin_phi_ : 0.0),  // Matsuoka-Nakai needs phi > 0
      bingham_(DruckerPragerBingham::from_friction_angle(
          degrees_to_radians(parameters.friction_angle_deg), parameters.cohesion)),
      matsuoka_nakai_(MatsuokaNakai::from_k(
          parameters.matsuoka_nakai_fit == MatsuokaNakaiFit::isochoric_shear
              ? matsuoka_nakai_k_isochoric(sin_phi_)
              : matsuoka_nakai_k_triaxial(sin_phi_))),
      mu_of_i_{parameters.static_friction, parameters.limiting_friction,
               parameters.reference_inertial_number},
      grain_diameter_(parameters.grain_diameter),
      density_(parameters.density),
      inverse_density_(1.0 / parameters.density),
      regularisation_time_(parameters.regularisation_time),
      min_dynamic_viscosity_(parameters.min_dynamic_viscosity),
      clip_min_viscosity_(parameters.density * parameters.min_kinematic_viscosity),
      clip_max_viscosity_(parameters.density * parameters.max_kinematic_viscosity) {}

}  // namespace granflow::rheology
