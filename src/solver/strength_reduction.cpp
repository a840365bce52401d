#include "solver/strength_reduction.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include <toml++/toml.h>

#include "io/case_error.hpp"
#include "solver/simulation.hpp"

namespace granflow {

namespace {

// soil.materials as the case gives them, each with the friction angle and cohesion given: an override
// that replaces the array whole (--set cannot address one element), every other key of a material kept.
std::string materials_with(const CaseConfig& config, const std::vector<std::array<double, 2>>& strengths) {
  const toml::table root = toml::parse(config.as_run);
  const toml::array* given = root["soil"]["materials"].as_array();
  std::string out;
  for (size_t k = 0; k < strengths.size(); ++k) {
    std::string entry = fmt::format("friction_angle = {}, cohesion = {}", strengths[k][0], strengths[k][1]);
    for (const auto& [key, value] : *given->get(k)->as_table()) {
      if (key == "friction_angle" || key == "cohesion") continue;
      if (const auto text = value.value_exact<std::string>())
        entry += fmt::format(", {} = \"{}\"", key.str(), *text);  // names and choices: plain words
      else if (const auto number = value.value<double>())
        entry += fmt::format(", {} = {}", key.str(), *number);
    }
    out += fmt::format("{}{{{}}}", out.empty() ? "" : ", ", entry);
  }
  return "soil.materials=[" + out + "]";
}

// x to 15 significant digits: a reduced angle or a bisection's factor as a decimal reads (30 at F = 1,
// not 29.999999999999996; F = 2.4, not 2.4000000000000004) in the trials' records, directories and
// messages, and differs from x far below any tolerance of the analysis.
double decimal(double x) { return std::stod(fmt::format("{:.15g}", x)); }

// The friction angle of a wall (or obstacle) whose tan(delta) is divided by the factor, degrees.
double reduced_wall_angle(const rheology::WallFriction& friction, double factor) {
  return decimal(std::atan(friction.friction_coefficient / factor) / (std::numbers::pi / 180.0));
}

// The case's text with each obstacle's own friction divided by the factor: --set cannot address one
// element of the obstacle array, so the array is rewritten in the text, every other key kept.
std::string obstacles_reduced(const CaseConfig& config, double factor) {
  toml::table root = toml::parse(config.as_run);
  toml::array* obstacles = root["obstacle"].as_array();
  for (size_t k = 0; k < config.obstacle_friction.size(); ++k)
    if (const auto& friction = config.obstacle_friction[k]) {
      toml::table& obstacle = *obstacles->get(k)->as_table();
      obstacle.insert_or_assign("friction_angle", reduced_wall_angle(*friction, factor));
      obstacle.insert_or_assign("adhesion", friction->adhesion / factor);
    }
  std::ostringstream text;
  text << root;
  return text.str();
}

}  // namespace

CaseConfig reduced_strength(const CaseConfig& config, double factor) {
  if (!(factor > 0.0 && std::isfinite(factor)))
    throw CaseError(fmt::format("strength reduction: the factor {} is not a positive number", factor));
  if (!config.soil || !config.soil->rheology)
    throw CaseError(fmt::format("{}: strength reduction needs soil with a rheology ([soil.rheology]) to reduce",
                                config.source.string()));
  for (Side s : sides_of_dimension(config.mesh.dimension()))
    if (boundary(config.flow.boundaries, s).kind == BoundaryKind::inlet)
      throw CaseError(fmt::format("{}: boundary.{} is an inlet: strength reduction looks for the factor at which a "
                                  "slope at rest fails, and a slope fed by an inlet is not at rest (make the side a "
                                  "wall)", config.source.string(), side_name(s)));
  const auto& r = *config.soil->rheology;
  if (r.friction != rheology::FrictionSource::constant)
    throw CaseError(fmt::format("{}: strength reduction divides a constant friction angle; mu(I) friction has none "
                                "(use soil.rheology.friction = \"constant\")",
                                config.source.string()));
  const double deg = std::numbers::pi / 180.0;
  auto reduced_friction = [&](double phi) { return decimal(std::atan(std::tan(phi * deg) / factor) / deg); };
  const auto& num = config.flow.numerics;
  std::vector<std::string> keys{fmt::format("soil.rheology.friction_angle={}", reduced_friction(r.friction_angle_deg)),
                                fmt::format("soil.rheology.cohesion={}", r.cohesion / factor),
                                fmt::format("numerics.outer_iterations={}", std::max(num.outer_iterations, 10)),
                                fmt::format("numerics.outer_tolerance={}", std::min(num.outer_tolerance, 1e-6)),
                                "soil.displacement=true",
                                "time.rest_speed=0"};  // each trial runs to time.end, or until it fails
  if (!config.soil->materials.empty()) {  // every soil material's strength too
    std::vector<std::array<double, 2>> strengths;
    for (const auto& m : config.soil->materials) {
      if (m.rheology.friction != rheology::FrictionSource::constant)
        throw CaseError(fmt::format("{}: strength reduction divides a constant friction angle; the soil material '{}' "
                                    "has mu(I) friction, which has none", config.source.string(), m.name));
      strengths.push_back({reduced_friction(m.rheology.friction_angle_deg), m.rheology.cohesion / factor});
    }
    keys.push_back(materials_with(config, strengths));
  }
  for (Side side : planar_sides)  // and a wall's friction against the soil: the interface is as weak in the same measure
    if (const auto& friction = boundary(config.flow.boundaries, side).friction) {
      keys.push_back(fmt::format("boundary.{}.friction_angle={}", side_name(side), reduced_wall_angle(*friction, factor)));
      keys.push_back(fmt::format("boundary.{}.adhesion={}", side_name(side), friction->adhesion / factor));
    }
  const bool obstacle_friction = std::any_of(config.obstacle_friction.begin(), config.obstacle_friction.end(),
                                             [](const auto& f) { return f.has_value(); });
  CaseConfig reduced = parse_case(obstacle_friction ? obstacles_reduced(config, factor) : config.as_run, keys, config.source);
  reduced.overrides.insert(reduced.overrides.begin(), config.overrides.begin(), config.overrides.end());
  // The record of the trial's case (granflow_case.toml) lists its overrides; the obstacles' friction,
  // rewritten in the text, is listed as what it is, an element no --set can address.
  for (size_t k = 0; k < config.obstacle_friction.size(); ++k)
    if (const auto& friction = config.obstacle_friction[k])
      reduced.overrides.push_back(fmt::format("obstacle[{}].friction_angle={}, adhesion={} (in the text below)", k,
                                              reduced_wall_angle(*friction, factor), friction->adhesion / factor));
  return reduced;
}

std::filesystem::path trial_directory(const std::filesystem::path& out, double factor) {
  return out.empty() ? out : out / fmt::format("F_{}", factor);  // the shortest form: distinct factors, distinct names
}


StrengthTrial strength_trial(MPI_Comm comm, const CaseConfig& config, const std::filesystem::path& out, double factor,
                             double limit_setting) {
  StrengthTrial trial;
  trial.factor = factor;
  const auto start = std::chrono::steady_clock::now();
  Simulation sim(comm, reduced_strength(config, factor), trial_directory(out, factor));
  const double limit = limit_setting > 0.0 ? limit_setting : sim.soil()->moved_distance();
  struct Moved {};  // the soil has moved past the limit: the trial's verdict is in
  try {
    sim.run([&](Simulation& running, double) {
      ++trial.steps;
      if (!(running.last_step().velocity_change < running.config().flow.numerics.outer_tolerance)) ++trial.unconverged_steps;
      if (running.soil()->largest_displacement() > limit) throw Moved{};
    });
  } catch (const Moved&) {
    if (!out.empty()) sim.write_output();  // the state at which it was seen to fail
  } catch (const DivergenceError& e) {
    trial.diverged = true;
    trial.divergence = e.what();
  }
  trial.largest_displacement = sim.soil()->largest_displacement();
  trial.displacement_limit = limit;
  trial.fails = trial.diverged || trial.largest_displacement > limit;
  trial.time = sim.time();
  trial.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return trial;
}

StrengthReductionResult factor_of_safety(MPI_Comm comm, const CaseConfig& config, const std::filesystem::path& out,
                                         const StrengthReductionSettings& settings,
                                         const std::function<void(const StrengthTrial&)>& on_trial,
                                         const std::vector<StrengthTrial>& earlier) {
  reduced_strength(config, settings.first_factor);  // the case's own errors, before any trial runs
  if (!(settings.tolerance > 0.0))
    throw CaseError(fmt::format("strength reduction: the tolerance {} is not a positive number", settings.tolerance));
  StrengthReductionResult result;
  auto trial = [&](double factor) {
    const auto known = std::find_if(earlier.begin(), earlier.end(), [factor](const StrengthTrial& e) { return e.factor == factor; });
    StrengthTrial t;
    if (known != earlier.end()) {
      t = *known;
      t.earlier = true;
    } else {
      t = strength_trial(comm, config, out, factor, settings.displacement_limit);
    }
    result.trials.push_back(t);
    if (t.fails) result.fails_at = std::min(result.fails_at, factor);
    else result.stands_at = std::max(result.stands_at, factor);
    if (on_trial) on_trial(t);
  };
  // A bracket: double while the soil stands, halve while it fails.
  double factor = settings.first_factor;
  trial(factor);
  while (!result.bracketed()) {
    factor = result.stands_at > 0.0 ? factor * 2.0 : factor / 2.0;
    if (factor > settings.largest_factor || factor < settings.smallest_factor) return result;
    trial(factor);
  }
  while (result.fails_at - result.stands_at > settings.tolerance) {
    const double middle = decimal(0.5 * (result.stands_at + result.fails_at));
    if (middle <= result.stands_at || middle >= result.fails_at) break;  // the factors' last bit
    trial(middle);
  }
  return result;
}

}  // namespace granflow
