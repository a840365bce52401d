// What a case file says about the granular rheology: model, friction law, regularisation and
// material constants, with their names as the case file spells them.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace granflow::rheology {

enum class Model {
  drucker_prager_bingham,  // [VoF] Eqs. 7-12
  drucker_prager,          // [YS] Eq. 24
  mohr_coulomb,            // [YS] Eq. 28
  matsuoka_nakai,          // [YS] Eqs. 29-34
};

// The shape of the yield surface in the deviatoric plane. Determined by the model
// (yield_surface_of), not stored separately, so that model and shape cannot disagree.
enum class YieldSurface { drucker_prager, mohr_coulomb, matsuoka_nakai };

// What stands in place of sin(phi): the constant friction angle, or mu(I) ([YS] Eq. 25, Sec. 6).
enum class FrictionSource { constant, mu_of_I };

enum class Regularisation {
  exponential,  // Papanastasiou, [VoF] Eq. 12 (m, mu_min)
  clip,         // kinematic viscosity clipped to [nu_min, nu_max], [YS] Sec. 2.4
};

// Calibration of k_MN: isochoric shear ([YS] Eq. 34, default) or triaxial compression/extension.
enum class MatsuokaNakaiFit { isochoric_shear, triaxial };

struct RheologyParameters {
  Model model = Model::drucker_prager_bingham;
  FrictionSource friction = FrictionSource::constant;
  Regularisation regularisation = Regularisation::exponential;
  MatsuokaNakaiFit matsuoka_nakai_fit = MatsuokaNakaiFit::isochoric_shear;

  double friction_angle_deg = 30.0;         // phi, degrees, in (0, 90); 0 too with a cohesion
  double cohesion = 0.0;                    // C, Pa ([VoF] Eq. 9; on the [YS] surfaces tau = C + sigma_n tan(phi)); constant friction only
  double regularisation_time = 1e5;         // m, s ([VoF] Eq. 12)
  double min_dynamic_viscosity = 1e-3;      // mu_min, Pa s ([VoF] Sec. 2)
  double min_kinematic_viscosity = 1e-5;    // nu_min, m^2/s ([YS] Sec. 4)
  double max_kinematic_viscosity = 1.0;     // nu_max, m^2/s ([YS] Sec. 4)
  double density = 2650.0;                  // rho_s, kg/m^3: nu = eta / rho_s, and I of mu(I)
  double grain_diameter = 0.5e-3;           // d, m (mu(I); Jop et al. 2006 glass beads)
  double static_friction = 0.38;            // mu_s = tan(20.9 deg) (Jop et al. 2006)
  double limiting_friction = 0.64;          // mu_2 = tan(32.76 deg)
  double reference_inertial_number = 0.279; // I_0
};

// The largest cohesion accepted, Pa (validate).
inline constexpr double max_cohesion = 1e9;

// An error message naming the first bad parameter, or nullopt if the set is usable.
std::optional<std::string> validate(const RheologyParameters& parameters);

constexpr YieldSurface yield_surface_of(Model model) noexcept {
  switch (model) {
    case Model::mohr_coulomb: return YieldSurface::mohr_coulomb;
    case Model::matsuoka_nakai: return YieldSurface::matsuoka_nakai;
    case Model::drucker_prager_bingham:
    case Model::drucker_prager: break;
  }
  return YieldSurface::drucker_prager;
}

// Names as written in case files, exactly.
inline constexpr std::array<std::string_view, 4> model_names{
    "drucker_prager_bingham", "drucker_prager", "mohr_coulomb", "matsuoka_nakai"};
inline constexpr std::array<std::string_view, 3> yield_surface_names{
    "drucker_prager", "mohr_coulomb", "matsuoka_nakai"};
inline constexpr std::array<std::string_view, 2> friction_source_names{"constant", "mu_of_I"};
inline constexpr std::array<std::string_view, 2> regularisation_names{"exponential", "clip"};
inline constexpr std::array<std::string_view, 2> matsuoka_nakai_fit_names{"isochoric_shear",
                                                                          "triaxial"};

std::string_view to_string(Model value) noexcept;
std::string_view to_string(YieldSurface value) noexcept;
std::string_view to_string(FrictionSource value) noexcept;
std::string_view to_string(Regularisation value) noexcept;
std::string_view to_string(MatsuokaNakaiFit value) noexcept;

// nullopt for anything but the exact names above (case-sensitive, no trimming).
std::optional<Model> parse_model(std::string_view name) noexcept;
std::optional<YieldSurface> parse_yield_surface(std::string_view name) noexcept;
std::optional<FrictionSource> parse_friction_source(std::string_view name) noexcept;
std::optional<Regularisation> parse_regularisation(std::string_view name) noexcept;
std::optional<MatsuokaNakaiFit> parse_matsuoka_nakai_fit(std::string_view name) noexcept;

}  // namespace granflow::rheology
