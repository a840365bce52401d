#include "io/case_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <pthread.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cerrno>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

#include "io/case_error.hpp"
#include "io/height_map_file.hpp"
#include "io/points_file.hpp"
#include "io/table_reader.hpp"
#include "io/text_file.hpp"
#include "io/utf8_text.hpp"
#include "models/rheology/parameters.hpp"

namespace granflow {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
// A case file is text of some kilobytes; a shape of a million points is some 30 MiB (and belongs in a
// points_file).
constexpr std::size_t case_file_limit = std::size_t(64) << 20;
// A granular case's air band by default, in cells: the soil's pile is the whole domain's with it
// (docs/method.md, "Air band").
constexpr int default_air_band = 12;

// The key of a --set assignment: before its '=', without the blanks a TOML line may have around the key
// and its dots ("time.end = 0.1"); empty without an '='.
std::string override_key(const std::string& assignment) {
  const auto eq = assignment.find('=');
  std::string key;
  if (eq != std::string::npos)
    for (char ch : assignment.substr(0, eq))
      if (ch != ' ' && ch != '\t') key += ch;
  return key;
}

// Whether a message about the case names a key that the --set assignment gave, or an entry under it
// ("initial.soil[0].radius" of initial.soil): the key before the message's first ": " (and before
// " = " where the value follows it); or a table the assignment's key lies in, when the message is a
// rheology check of that key ("soil.rheology: rheology parameter friction_angle (phi) = 95 ...").
bool names_key_of(std::string_view message, const std::string& assignment) {
  const std::string key = override_key(assignment);
  if (key.empty()) return false;
  std::string_view named = message.substr(0, message.find(": "));
  named = named.substr(0, named.find(" = "));
  if (named.starts_with(key) && (named.size() == key.size() || named[key.size()] == '.' || named[key.size()] == '['))
    return true;
  if (!(key.size() > named.size() && key.starts_with(named) && key[named.size()] == '.')) return false;
  const std::string parameter = "parameter " + key.substr(key.rfind('.') + 1);
  const auto at = message.find(parameter, named.size());
  const std::size_t end = at + parameter.size();
  return at != std::string_view::npos &&
         (end == message.size() || !(std::isalnum(static_cast<unsigned char>(message[end])) || message[end] == '_'));
}

void apply_override(toml::table& root, const std::string& assignment) {
  // The case as run is recorded as TOML, which is UTF-8 throughout (a bare word would be kept as it is).
  if (!is_valid_utf8(assignment))
    throw CaseError(fmt::format("--set '{}': the text is not valid UTF-8", utf8_or_escaped(assignment)));
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw CaseError(fmt::format("--set '{}': expected KEY=VALUE", assignment));
  const std::string key = override_key(assignment);
  if (key.empty()) throw CaseError(fmt::format("--set '{}': expected KEY=VALUE", assignment));
  const auto whole_array_only = [&](const std::string& array) {
    return CaseError(fmt::format("--set '{}': an element of an array cannot be set alone; set the whole array, "
                                 "--set '{}=[...]' (an array of tables as --set 'initial.soil=[{{shape = \"box\", "
                                 "lower = [0, 0], upper = [0.2, 0.1]}}]')",
                                 assignment, array.empty() ? "KEY" : array));
  };
  if (key.find_first_of("[]") != std::string::npos) throw whole_array_only(key.substr(0, key.find_first_of("[]")));
  // Keys are read as dotted bare words; a quoted part would be taken with its quotes.
  if (key.find_first_of("\"'") != std::string::npos)
    throw CaseError(fmt::format("--set '{}': write the key without quotes (e.g. mesh.cells)", assignment));
  const std::string value = assignment.substr(eq + 1);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value);
  } catch (const toml::parse_error& e) {
    // A bare word is a string (--set soil.yield_pressure=face); a value that starts as a number, a
    // string, an array or a table but does not parse is a mistake to name, not a string.
    const auto start = value.find_first_not_of(" \t");
    const char first = start == std::string::npos ? '\0' : value[start];
    if (std::string_view("\"'[{+-.").find(first) != std::string_view::npos || std::isdigit(static_cast<unsigned char>(first)))
      throw CaseError(fmt::format("--set '{}': the value is not valid TOML: {}", assignment, e.description()));
    parsed = toml::table{{"v", value}};
  }
  if (parsed.size() != 1)  // "0.02\nmesh.cells = [1, 1]": more keys on further lines, which would be dropped
    throw CaseError(fmt::format("--set '{}': the value holds more than one key; give one KEY=VALUE per --set",
                                assignment));
  toml::table* t = &root;
  std::string_view rest = key;
  while (true) {
    const auto dot = rest.find('.');
    const std::string part(rest.substr(0, dot));
    if (part.empty()) throw CaseError(fmt::format("--set '{}': empty key component", assignment));
    if (dot == std::string_view::npos) {
      t->insert_or_assign(part, *parsed.get("v"));
      return;
    }
    toml::node* n = t->get(part);
    if (!n) {
      t->insert(part, toml::table{});
      n = t->get(part);
    }
    if (n->is_array_of_tables()) throw whole_array_only(key.substr(0, key.size() - rest.size() + part.size()));
    if (!n->is_table()) throw CaseError(fmt::format("--set '{}': '{}' is not a table", assignment, part));
    t = n->as_table();
    rest = rest.substr(dot + 1);
  }
}

LinearSolverSettings read_linear_solver(TableReader r, LinearSolverSettings d) {
  d.ksp_type = r.string("ksp_type", d.ksp_type);
  d.pc_type = r.string("pc_type", d.pc_type);
  d.rtol = r.number("rtol", d.rtol);
  r.require_range("rtol", d.rtol, 0.0, std::nextafter(1.0, 0.0), "in [0, 1)");  // PETSc refuses 1 itself
  d.atol = r.number("atol", d.atol);
  r.require_range("atol", d.atol, 0.0, inf);
  d.max_iterations = r.integer_in("max_iterations", d.max_iterations, 1, 1000000000);
  d.max_reuse = r.integer_in("reuse_preconditioner", d.max_reuse, 1, 1000000);
  r.finish();
  return d;
}

// A wall's own friction against the soil (a side of type "wall", an obstacle), if it gives one; its keys
// go to two_phase_keys, which collects the keys given that only a case with soil uses.
std::optional<rheology::WallFriction> read_wall_friction(TableReader& r, std::vector<std::string>& two_phase_keys) {
  for (const char* key : {"friction_angle", "adhesion"}) r.known_elsewhere(key);  // named if a key is misspelt
  if (!r.has("friction_angle") && !r.has("adhesion")) return std::nullopt;
  for (const char* key : {"friction_angle", "adhesion"})
    if (r.has(key)) two_phase_keys.push_back(r.key_path(key));
  const double adhesion = r.number("adhesion", 0.0);
  r.require_range("adhesion", adhesion, 0.0, std::numeric_limits<double>::infinity(), "zero or positive");
  if (!r.has("friction_angle") && adhesion == 0.0)
    throw CaseError(fmt::format("{}: 0 without a friction_angle leaves the wall no strength; a wall without friction "
                                "is type = \"slip\"", r.key_path("adhesion")));
  const double delta = r.number("friction_angle", 0.0);
  if (!(delta >= 0.0 && delta < 90.0) || (delta == 0.0 && adhesion == 0.0))
    throw CaseError(fmt::format("{}: {} is outside (0, 90) degrees ([0, 90) with an adhesion above zero); a wall "
                                "without friction is type = \"slip\"", r.key_path("friction_angle"), delta));
  return rheology::WallFriction::from_angle(delta, adhesion);
}

// Exactly `count` numbers (a point or a vector of the mesh's dimension), or the fallback.
std::vector<double> numbers_of_size(TableReader& r, std::string_view key, std::vector<double> fallback, size_t count,
                                    const char* what) {
  const auto v = r.numbers(key, std::move(fallback));
  if (v.size() != count) throw CaseError(fmt::format("{}: expected {} numbers ({}), got {}", r.key_path(key), count, what, v.size()));
  return v;
}

void read_material_name(TableReader& r, std::string& material) {
  material = r.string("material", "");
  if (r.has("material") && material.empty())
    throw CaseError(r.key_path("material") + ": empty; name a [[soil.materials]] entry, or leave the key out for the "
                    "rheology's own soil");
}

// The soil material `name`, given at key_path: 0 for none (the rheology's own soil), k for
// materials[k - 1].
int material_index(const std::string& name, const std::string& key_path, const std::vector<SoilMaterial>& materials) {
  if (name.empty()) return 0;
  const auto it =
      std::find_if(materials.begin(), materials.end(), [&](const SoilMaterial& m) { return m.name == name; });
  if (it != materials.end()) return int(it - materials.begin()) + 1;
  std::string names;
  for (const auto& m : materials) names += (names.empty() ? "" : ", ") + m.name;
  throw CaseError(fmt::format("{}: no soil material named '{}' ({})", key_path, name,
                              names.empty() ? "the case has no [[soil.materials]]" : "the case's are: " + names));
}

// two_phase_keys: collects the keys given that only a case with soil uses; dimension: the mesh's;
// materials: the case's soil materials (an inlet's soil may be one), none without soil.
BoundaryCondition read_boundary(TableReader r, bool& is_axis, std::vector<std::string>& two_phase_keys, int dimension,
                                const std::vector<SoilMaterial>* materials) {
  BoundaryCondition bc;
  const std::string type =
      r.choice("type", "", {"wall", "slip", "symmetry", "atmosphere", "axis", "periodic", "inlet"});
  is_axis = type == "axis";
  if (type == "periodic") {
    bc.kind = BoundaryKind::periodic;  // joined to the opposite side; read_boundaries checks the pair
  } else if (type == "axis") {
    bc.kind = BoundaryKind::slip;  // symmetry: u_r = 0, no shear; the face at r = 0 has no area
  } else if (type == "wall") {
    bc.kind = BoundaryKind::wall;
    if (dimension == 3) {
      const auto velocity = numbers_of_size(r, "velocity", {0.0, 0.0, 0.0}, 3, "[u, v, w] on a mesh of layers");
      bc.velocity = {velocity[0], velocity[1], velocity[2]};
    } else {
      const auto velocity = r.pair("velocity", {0.0, 0.0});
      bc.velocity = {velocity[0], velocity[1], 0.0};
    }
    bc.friction = read_wall_friction(r, two_phase_keys);
  } else if (type == "slip" || type == "symmetry") {
    bc.kind = BoundaryKind::slip;  // a symmetry plane is a slip wall: no normal velocity, no shear
  } else if (type == "inlet") {
    bc.kind = BoundaryKind::inlet;
    if (!r.has("velocity"))
      throw CaseError(fmt::format("{}: missing (an inlet's velocity into the domain, m/s){}", r.key_path("velocity"),
                                  r.misspelling_of("velocity")));
    const auto velocity = dimension == 3 ? numbers_of_size(r, "velocity", {}, 3, "[u, v, w] on a mesh of layers")
                                         : numbers_of_size(r, "velocity", {}, 2, "[u, v]");
    for (size_t c = 0; c < velocity.size(); ++c) bc.velocity[c] = bc.inflow_velocity[c] = velocity[c];
    if (r.has("schedule")) {  // [t, factor] pairs: the inflow's velocity by time
      bc.inflow_schedule = r.pairs("schedule", 1);
      for (size_t k = 0; k < bc.inflow_schedule.size(); ++k) {
        const auto& [t, factor] = bc.inflow_schedule[k];
        if (!(t >= 0.0))
          throw CaseError(fmt::format("{}: the time of pair {} is {} s; times are from the start, 0 or later",
                                      r.key_path("schedule"), k, t));
        if (k > 0 && !(t >= bc.inflow_schedule[k - 1][0]))
          throw CaseError(fmt::format("{}: the times must not decrease (pair {} at {} s after pair {} at {} s)",
                                      r.key_path("schedule"), k, t, k - 1, bc.inflow_schedule[k - 1][0]));
        if (k > 1 && t == bc.inflow_schedule[k - 2][0])
          throw CaseError(fmt::format("{}: three pairs at {} s; a jump is two pairs of one time",
                                      r.key_path("schedule"), t));
        if (!(factor >= 0.0))
          throw CaseError(fmt::format("{}: the factor of pair {} is {}; the inflow's velocity is scaled by a factor "
                                      "of 0 or more (0 closes the inlet, as a wall at rest)",
                                      r.key_path("schedule"), k, factor));
      }
    }
    for (const char* key : {"soil_fraction", "soil_depth", "material"})
      if (r.has(key)) {  // named as such before their values are checked against a soil there is not
        if (!materials)
          throw CaseError(fmt::format("{}: applies to cases with soil only (this case has [fluid], no [soil])",
                                      r.key_path(key)));
        two_phase_keys.push_back(r.key_path(key));
      }
    for (int axis = 0; axis < 3; ++axis) {  // the opening: [low, high] across the side (read_boundaries checks)
      const std::string key = fmt::format("span_{}", "xyz"[axis]);
      if (!r.has(key)) continue;
      if (axis == 2 && dimension != 3)
        throw CaseError(fmt::format("{}: a planar mesh has no z across its sides (a mesh of layers has, "
                                    "mesh.cells = [nx, ny, nz])", r.key_path(key)));
      const auto span = numbers_of_size(r, key, {}, 2, "[low, high] of the opening, m");
      if (!(span[0] < span[1]))
        throw CaseError(fmt::format("{}: [{}, {}]; the opening runs from its low end to a higher one",
                                    r.key_path(key), span[0], span[1]));
      bc.inflow_span[axis] = {span[0], span[1]};
    }
    bc.inflow_soil_fraction = r.number("soil_fraction", 0.0);
    r.require_range("soil_fraction", bc.inflow_soil_fraction, 0.0, 1.0);
    bc.inflow_soil_depth = r.number("soil_depth", bc.inflow_soil_depth);
    r.require_range("soil_depth", bc.inflow_soil_depth, 1e-300, std::numeric_limits<double>::infinity(), "positive");
    if (materials) {
      std::string material;
      read_material_name(r, material);
      bc.inflow_material = material_index(material, r.key_path("material"), *materials);
    }
  } else {
    bc.kind = BoundaryKind::atmosphere;
    bc.pressure = r.number("pressure", 0.0);
    bc.total_pressure = r.choice("pressure_kind", "total", {"total", "static"}) == "total";
    if (r.has("inflow_soil_fraction")) two_phase_keys.push_back(r.key_path("inflow_soil_fraction"));
    bc.inflow_soil_fraction = r.number("inflow_soil_fraction", 0.0);
    r.require_range("inflow_soil_fraction", bc.inflow_soil_fraction, 0.0, 1.0);
  }
  r.finish();
  return bc;
}

mixture::MixtureInterpolation read_mixing(TableReader& m, const std::string& property) {
  const std::string name = m.choice(property, "linear", {"linear", "arctan"});
  mixture::InterpolationKind kind = mixture::InterpolationKind::linear;
  mixture::parse_interpolation_kind(name, kind);
  if (kind != mixture::InterpolationKind::arctan) return {};
  const double M = m.number("arctan_M", 0.0);
  m.require_range("arctan_M", M, -0.5, 0.5);
  const double N = m.number("arctan_N", 1.0);
  m.require_range("arctan_N", N, 1e-6, 1e6);
  return {kind, M, N};
}

template <class Enum, class Parse>
Enum read_enum(TableReader& r, std::string_view key, Enum fallback, Parse parse, const auto& names) {
  const std::string text = r.string(key, std::string(rheology::to_string(fallback)));
  if (auto v = parse(text)) return *v;
  std::string list;
  for (auto n : names) list += (list.empty() ? "" : ", ") + std::string(n);
  throw CaseError(fmt::format("{}: '{}' is not one of: {}", r.key_path(key), text, list));
}

// The keys of a rheology table over `p`, which holds their defaults. A soil material's (material)
// shares the rheology's regularisation, whose keys are refused there, and one whose friction is mu(I),
// which takes no cohesion, does not inherit the rheology's.
void read_rheology_keys(TableReader& r, rheology::RheologyParameters& p, bool material) {
  using namespace rheology;
  p.model = read_enum(r, "model", p.model, parse_model, model_names);
  p.friction = read_enum(r, "friction", p.friction, parse_friction_source, friction_source_names);
  if (material) {
    for (std::string_view k : {"regularisation", "m", "mu_min", "nu_min", "nu_max"})
      if (r.has(k))
        throw CaseError(fmt::format("{}: the soils share the regularisation of [soil.rheology]; set it there", r.key_path(k)));
  } else {
    p.regularisation = read_enum(r, "regularisation", p.regularisation, parse_regularisation, regularisation_names);
  }
  p.matsuoka_nakai_fit =
      read_enum(r, "matsuoka_nakai_fit", p.matsuoka_nakai_fit, parse_matsuoka_nakai_fit, matsuoka_nakai_fit_names);
  // Constants the chosen model, friction or regularisation does not read are refused, naming what
  // reads them: a case that sets mu_2 under a constant friction would otherwise run without it.
  auto only_with = [&](std::initializer_list<std::string_view> keys, bool applies, std::string_view what) {
    if (applies) return;
    for (auto k : keys)
      if (r.has(k)) {
        // An entry of an array of tables (soil.materials[0]) is replaced with its whole array.
        const bool entry = r.path().find('[') != std::string::npos;
        throw CaseError(fmt::format("{}: used only with {}; this case does not use it, so remove it{}", r.key_path(k), what,
                                    entry ? "" : fmt::format(" (on the command line, --set '{}={{...}}' replaces the "
                                                             "whole table)", r.path())));
      }
  };
  const bool exponential = p.regularisation == Regularisation::exponential;
  if (!material) {
    only_with({"m", "mu_min"}, exponential, "regularisation = \"exponential\" (the default)");
    only_with({"nu_min", "nu_max"}, !exponential, "regularisation = \"clip\"");
  }
  only_with({"grain_diameter", "mu_s", "mu_2", "I_0"}, p.friction == FrictionSource::mu_of_I, "friction = \"mu_of_I\"");
  only_with({"friction_angle"}, p.friction == FrictionSource::constant,
            "friction = \"constant\" (the default; under mu_of_I, mu_s, mu_2 and I_0 give the friction)");
  only_with({"matsuoka_nakai_fit"}, p.model == Model::matsuoka_nakai, "model = \"matsuoka_nakai\"");
  p.friction_angle_deg = r.number("friction_angle", p.friction_angle_deg);
  p.cohesion = r.number("cohesion", material && p.friction == FrictionSource::mu_of_I ? 0.0 : p.cohesion);
  if (!material) {
    p.regularisation_time = r.number("m", p.regularisation_time);
    p.min_dynamic_viscosity = r.number("mu_min", p.min_dynamic_viscosity);
    p.min_kinematic_viscosity = r.number("nu_min", p.min_kinematic_viscosity);
    p.max_kinematic_viscosity = r.number("nu_max", p.max_kinematic_viscosity);
  }
  p.grain_diameter = r.number("grain_diameter", p.grain_diameter);
  p.static_friction = r.number("mu_s", p.static_friction);
  p.limiting_friction = r.number("mu_2", p.limiting_friction);
  p.reference_inertial_number = r.number("I_0", p.reference_inertial_number);
}

rheology::RheologyParameters read_rheology(TableReader r, double soil_density) {
  rheology::RheologyParameters p;
  p.density = soil_density;
  read_rheology_keys(r, p, false);
  r.finish();
  if (auto err = validate(p)) throw CaseError(fmt::format("{}: {}", r.path(), *err));
  return p;
}

// A polygon from its listed vertices. A point repeated next to itself, or the first point repeated at
// the end to close the outline, adds an edge of no length; it is dropped. `where` names the vertices'
// source in errors.
interface::Polygon polygon_of(std::vector<std::array<double, 2>> points, const std::string& where) {
  interface::Polygon polygon{std::move(points)};
  auto& v = polygon.vertices;
  v.erase(std::unique(v.begin(), v.end()), v.end());
  while (v.size() > 1 && v.back() == v.front()) v.pop_back();
  if (v.size() < 3) throw CaseError(fmt::format("{}: the polygon needs at least 3 distinct points", where));
  if (interface::self_intersecting(polygon))
    throw CaseError(fmt::format("{}: the polygon crosses itself (two of its edges meet)", where));
  // Points on one line enclose nothing: their area is the round-off of the products it sums (a long,
  // thin polygon's area is small against its extent squared, not against those products).
  double twice_area = 0.0, products = 0.0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const auto& p = v[k];
    const auto& q = v[(k + 1) % v.size()];
    const double a = (p[0] - v[0][0]) * (q[1] - v[0][1]), b = (q[0] - v[0][0]) * (p[1] - v[0][1]);
    twice_area += a - b;
    products += std::abs(a) + std::abs(b);
  }
  if (!(std::abs(twice_area) > 1e-12 * products))
    throw CaseError(fmt::format("{}: the polygon encloses no area (its points lie on one line)", where));
  return polygon;
}

// material: where given, the shape's `material` key is read into it ("" when absent); elsewhere the key
// is unknown.
interface::Shape read_shape(TableReader r, std::string* material = nullptr) {
  if (material) read_material_name(r, *material);
  if (r.has("shape") && r.string("shape", "") == "height_map")
    throw CaseError(r.key_path("shape") + ": a height map is a solid of a mesh of layers (mesh.cells of three "
                    "numbers); on a planar mesh a terrain profile is a polygon (points or points_file)");
  const std::string shape = r.choice("shape", "", {"box", "circle", "ring", "polygon"});
  interface::Shape out;
  if (shape == "box") {
    interface::Box b{r.required_pair("lower"), r.required_pair("upper")};
    if (!(b.upper[0] > b.lower[0] && b.upper[1] > b.lower[1]))
      throw CaseError(fmt::format("{}.upper: the box is empty (upper must exceed lower in x and y)", r.path()));
    out = b;
  } else if (shape == "circle") {
    interface::Circle c{r.required_pair("centre"), r.required_number("radius")};
    r.require_range("radius", c.radius, 1e-300, 1e300, "positive");
    out = c;
  } else if (shape == "ring") {
    interface::Ring ring{r.required_pair("centre"), r.required_number("inner_radius"), r.required_number("outer_radius")};
    r.require_range("inner_radius", ring.inner_radius, 1e-300, 1e300, "positive");
    r.require_range("outer_radius", ring.outer_radius, 1e-300, 1e300, "positive");
    if (!(ring.outer_radius > ring.inner_radius))
      throw CaseError(fmt::format("{}: the ring is empty (outer_radius {} must exceed inner_radius {}; a disc is shape = \"circle\")",
                                  r.key_path("outer_radius"), ring.outer_radius, ring.inner_radius));
    out = ring;
  } else {
    r.known_elsewhere("points_file");  // read into `points` before (read_points_files)
    out = polygon_of(r.pairs("points", 3), r.key_path("points"));
  }
  r.finish();
  return out;
}

// A height map's nodes (`origin`, `spacing`, `heights`: rows along z, each along x; a `heights_file` was
// read into them before, read_height_map_files) and the `bottom` of its solid.
interface::HeightMap read_height_map(TableReader& r) {
  r.known_elsewhere("heights_file");
  interface::HeightMap map;
  auto required = [&](const char* key, const char* what) {
    if (!r.has(key)) throw CaseError(fmt::format("{}: missing ({}){}", r.key_path(key), what, r.misspelling_of(key)));
    return numbers_of_size(r, key, {}, 2, what);
  };
  const auto origin = required("origin", "[x, z] of the first node");
  const auto spacing = required("spacing", "[dx, dz] between the nodes");
  for (const double d : spacing)
    if (!(d > 0.0)) throw CaseError(fmt::format("{}: expected two positive numbers [dx, dz]", r.key_path("spacing")));
  map.spacing = {spacing[0], spacing[1]};
  const auto rows = r.grid("heights", 2, 2);
  map.nz = int(rows.size());
  map.nx = int(rows.front().size());
  for (const auto& row : rows) map.heights.insert(map.heights.end(), row.begin(), row.end());
  // `offset` moves the map as a whole: an elevation model in survey coordinates to the mesh's.
  const auto offset = numbers_of_size(r, "offset", {0.0, 0.0, 0.0}, 3, "[x, y, z] added to the map's coordinates");
  map.origin = {origin[0] + offset[0], origin[1] + offset[2]};
  for (double& h : map.heights) h += offset[1];
  if (auto bottom = r.optional_number("bottom")) {
    map.bottom = *bottom;
    const double top = *std::max_element(map.heights.begin(), map.heights.end());
    if (!(top > map.bottom))
      throw CaseError(fmt::format("{}: the height map is empty (its highest node, {} m, is not above its bottom, {} m)",
                                  r.key_path("bottom"), top, map.bottom));
  }
  return map;
}

// On a mesh of layers, a shape of its own (interface::Shape3): a box of three-number corners, a sphere,
// a vertical cylinder (a granular column) or the ground under a height map; none for a planar shape,
// which is extruded across the whole depth.
std::optional<interface::Shape3> read_solid(TableReader r, std::string* material = nullptr) {
  if (material) read_material_name(r, *material);
  const std::string shape =
      r.choice("shape", "", {"box", "circle", "ring", "polygon", "sphere", "cylinder", "height_map"});
  auto point3 = [&](const char* key) {
    if (!r.has(key)) throw CaseError(r.key_path(key) + ": missing" + r.misspelling_of(key));
    const auto v = numbers_of_size(r, key, {}, 3, "[x, y, z]");
    return interface::Point3{v[0], v[1], v[2]};
  };
  std::optional<interface::Shape3> out;
  if (shape == "box" && r.has("lower") && r.numbers("lower", {}).size() == 3) {
    const interface::Box3 b{point3("lower"), point3("upper")};
    for (int a = 0; a < 3; ++a)
      if (!(b.upper[a] > b.lower[a]))
        throw CaseError(fmt::format("{}.upper: the box is empty (upper must exceed lower in x, y and z)", r.path()));
    out = b;
  } else if (shape == "sphere") {
    const interface::Sphere ball{point3("centre"), r.required_number("radius")};
    r.require_range("radius", ball.radius, 1e-300, 1e300, "positive");
    out = ball;
  } else if (shape == "cylinder") {
    const auto centre = numbers_of_size(r, "centre", {}, 2, "[x, z] of its vertical axis");
    const interface::VerticalCylinder column{{centre[0], centre[1]}, r.required_number("radius"),
                                             r.required_number("bottom"), r.required_number("top")};
    r.require_range("radius", column.radius, 1e-300, 1e300, "positive");
    if (!(column.top > column.bottom))
      throw CaseError(fmt::format("{}: the cylinder is empty (top {} must exceed bottom {})", r.key_path("top"),
                                  column.top, column.bottom));
    out = column;
  } else if (shape == "height_map") {
    out = read_height_map(r);
  }
  if (out) r.finish();
  return out;
}

// One of [[soil.materials]]: a soil of the rheology's regularisation with its own rheology otherwise
// (each key the rheology's unless given) and density.
SoilMaterial read_material(TableReader r, const std::optional<rheology::RheologyParameters>& rheology,
                           double soil_density) {
  using namespace rheology;
  if (!rheology)
    throw CaseError(r.path() + ": soil materials need a granular soil ([soil.rheology]), whose regularisation they share");
  SoilMaterial m;
  m.name = r.required_string("name");
  const bool plain = !m.name.empty() && std::all_of(m.name.begin(), m.name.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-';
  });
  if (!plain)
    throw CaseError(fmt::format("{}: '{}' is not a plain name (letters, digits, '_' and '-'; it names an output field)",
                                r.key_path("name"), m.name));
  m.rheology = *rheology;
  m.rheology.density = r.number("density", soil_density);
  r.require_range("density", m.rheology.density, 1e-300, inf, "positive");
  read_rheology_keys(r, m.rheology, true);
  // Under mu(I) the angle is not read (nor may it be given): the rheology's own, of a constant friction,
  // is not this soil's, and is put back to the unread default a mu(I) [soil.rheology] holds.
  if (m.rheology.friction == FrictionSource::mu_of_I) m.rheology.friction_angle_deg = RheologyParameters{}.friction_angle_deg;
  if (m.rheology.friction == FrictionSource::constant && rheology->friction != FrictionSource::constant &&
      !r.has("friction_angle"))
    throw CaseError(r.key_path("friction_angle") + ": required: the rheology's friction is mu(I), which has no angle to take");
  r.finish();
  if (auto err = validate(m.rheology)) throw CaseError(fmt::format("{}: {}", r.path(), *err));
  return m;
}

// without_effect: collects the keys given that the soil's other choices make of no effect.
SoilSettings read_soil(TableReader& top, std::vector<std::string>& without_effect, int dimension) {
  SoilSettings s;
  {
    TableReader a = top.table("air");
    if (!a.present()) throw CaseError("air: missing table [air] (density and viscosity of the light phase)" + top.misspelling_of("air"));
    s.air_density = a.required_number("density");
    a.require_range("density", s.air_density, 1e-300, inf, "positive");
    s.air_viscosity = a.required_number("viscosity");
    a.require_range("viscosity", s.air_viscosity, 0.0, inf, "zero or positive");
    a.finish();
  }
  {
    TableReader so = top.table("soil");
    s.soil_density = so.required_number("density");
    so.require_range("density", s.soil_density, 1e-300, inf, "positive");
    TableReader rh = so.table("rheology");
    if (rh.present()) {
      if (so.has("viscosity"))
        throw CaseError(so.key_path("viscosity") + ": used only without [soil.rheology] (a Newtonian soil); a granular "
                        "soil's viscosity comes from its rheology");
      s.rheology = read_rheology(rh, s.soil_density);
    } else {
      if (!so.has("viscosity"))
        throw CaseError("soil: neither a [soil.rheology] table (a granular soil) nor soil.viscosity (a Newtonian one)" +
                        so.misspelling_of("rheology") + so.misspelling_of("viscosity"));
      s.soil_viscosity = so.required_number("viscosity");
      so.require_range("viscosity", s.soil_viscosity, 0.0, inf, "zero or positive");
    }
    for (TableReader material : so.tables("materials")) {
      s.materials.push_back(read_material(material, s.rheology, s.soil_density));
      const auto& name = s.materials.back().name;
      for (size_t k = 0; k + 1 < s.materials.size(); ++k)
        if (s.materials[k].name == name)
          throw CaseError(fmt::format("{}: the name '{}' is taken by soil.materials[{}]", material.key_path("name"), name, k));
    }
    if (s.materials.size() + 1 > size_t(rheology::SoilMaterials::max_count))
      throw CaseError(fmt::format("soil.materials: {} materials, more than the {} a case may have besides the rheology's own",
                                  s.materials.size(), rheology::SoilMaterials::max_count - 1));
    // N/m; water against air 0.072 at 20 C. Zero: none (the surface force is not computed).
    s.surface_tension = so.number("surface_tension", 0.0);
    so.require_range("surface_tension", s.surface_tension, 0.0, inf, "zero or positive");
    if (so.has("contact_angle") && s.surface_tension == 0.0)
      throw CaseError(so.key_path("contact_angle") +
                      ": needs soil.surface_tension > 0 (it shapes the surface force at walls)");
    s.contact_angle = so.number("contact_angle", 90.0);
    so.require_range("contact_angle", s.contact_angle, 1.0, 179.0, "in [1, 179] degrees");
    s.displacement = so.boolean("displacement", s.rheology.has_value());
    // A granular soil's viscosity is taken on the faces by default, each choice defaulting to the one
    // before it: the cells' evaluations let a pile next to air creep (docs/method.md).
    const bool granular = s.rheology.has_value();
    const std::string yp = so.choice("yield_pressure", granular ? "face" : "cell", {"cell", "face", "lithostatic_floor"});
    s.yield_pressure = yp == "face" ? YieldPressure::face
                       : yp == "lithostatic_floor" ? YieldPressure::lithostatic_floor : YieldPressure::cell;
    const std::string sr = so.choice("strain_rate", granular && yp == "face" ? "face" : "cell", {"cell", "face"});
    s.strain_rate = sr == "face" ? StrainRateAt::face : StrainRateAt::cell;
    if (s.strain_rate == StrainRateAt::face && s.yield_pressure != YieldPressure::face)
      throw CaseError("soil.strain_rate = \"face\" needs soil.yield_pressure = \"face\" (the viscosity is then taken on "
                      "faces); for the cells' evaluations throughout, set soil.strain_rate = \"cell\" and "
                      "soil.face_fraction = \"cells\" too");
    const std::string ff = so.choice("face_fraction", granular && sr == "face" ? "face" : "cells", {"cells", "face"});
    s.face_fraction = ff == "face" ? FaceFraction::face : FaceFraction::cells;
    if (s.face_fraction == FaceFraction::face && s.strain_rate != StrainRateAt::face)
      throw CaseError("soil.face_fraction = \"face\" needs soil.strain_rate = \"face\" (one evaluation on the face); "
                      "with the cells' strain rates, set soil.face_fraction = \"cells\" too");
    s.failure_strain = so.number("failure_strain", s.failure_strain);
    so.require_range("failure_strain", s.failure_strain, 1e-6, 10.0);
    if (so.has("failure_strain") && !s.displacement)
      without_effect.push_back(so.key_path("failure_strain") + ": the failure line needs soil.displacement = true");
    so.finish();
  }
  {
    TableReader m = top.table("mixture");
    s.density_mixing = read_mixing(m, "density");
    s.viscosity_mixing = read_mixing(m, "viscosity");
    const bool arctan = s.density_mixing.kind() == mixture::InterpolationKind::arctan ||
                        s.viscosity_mixing.kind() == mixture::InterpolationKind::arctan;
    for (const char* key : {"arctan_M", "arctan_N"})
      if (m.has(key) && !arctan) {
        without_effect.push_back(m.key_path(key) + ": used only with mixture.density or mixture.viscosity = \"arctan\"");
        // Read, so that it is not an unknown key, and held to its range as where it is used.
        if (std::string_view(key) == "arctan_M")
          m.require_range(key, m.number(key, 0.0), -0.5, 0.5);
        else
          m.require_range(key, m.number(key, 1.0), 1e-6, 1e6);
      }
    m.finish();
  }
  {
    // Without it the domain starts free of soil, which only an inlet of soil can fill (checked with
    // the boundaries, load_case).
    TableReader init = top.table("initial");
    for (TableReader shape : init.tables("soil")) {
      std::string material;
      // On a mesh of layers a shape of its own, or a planar one extruded across the depth.
      const auto solid = dimension == 3 ? read_solid(shape, &material) : std::nullopt;
      if (solid) s.initial_soil_3d.push_back(*solid);
      else s.initial_soil.push_back(read_shape(shape, &material));
      s.initial_shape_is_solid.push_back(solid.has_value());
      s.initial_material.push_back(material_index(material, shape.key_path("material"), s.materials));
    }
    if (s.initial_soil.empty() && s.initial_soil_3d.empty() && !init.misspelling_of("soil").empty())
      throw CaseError("initial.soil: at least one shape is required" + init.misspelling_of("soil"));
    init.finish();
  }
  return s;
}

GridSpec read_mesh(TableReader& top) {
  GridSpec mesh;
  TableReader m = top.table("mesh");
  if (!m.present()) throw CaseError("mesh: missing table [mesh]" + top.misspelling_of("mesh"));
  auto cells = m.numbers("cells", {}, 2);
  if (cells.size() != 2 && cells.size() != 3)
    throw CaseError("mesh.cells: expected two integers [nx, ny], or three [nx, ny, nz] for a mesh of layers (3D)");
  for (double n : cells) {
    if (n < 1 || n != std::floor(n))
      throw CaseError(fmt::format("mesh.cells: {} is not a positive whole number of cells", n));
    if (n > 1e8) throw CaseError(fmt::format("mesh.cells: {:.0f} cells along an axis, more than 1e8", n));
  }
  const int dimension = int(cells.size());
  if (dimension == 3 && cells[2] < 2)
    throw CaseError("mesh.cells: one cell along z is a planar mesh; give two counts [nx, ny] (a mesh of layers has "
                    "nz >= 2)");
  mesh.cells = {int(cells[0]), int(cells[1]), dimension == 3 ? int(cells[2]) : 1};
  // PETSc's indices here are 32-bit; the coupled solve's matrix holds about 3 x 35 entries a cell.
  constexpr double max_cells = 2e7;
  const double cell_count = cells[0] * cells[1] * (dimension == 3 ? cells[2] : 1.0);
  if (cell_count > max_cells)
    throw CaseError(fmt::format("mesh.cells: {} = {:.3g} cells, more than the {:.0e} this build can index",
                                fmt::join(cells, " x "), cell_count, max_cells));
  if (dimension == 3) {
    const auto lower = numbers_of_size(m, "lower", {0.0, 0.0, 0.0}, 3, "[x, y, z] on a mesh of layers");
    if (!m.has("upper")) throw CaseError("mesh.upper: missing (the domain's upper corner, [x, y, z])" + m.misspelling_of("upper"));
    const auto upper = numbers_of_size(m, "upper", {}, 3, "[x, y, z] on a mesh of layers");
    mesh.lower = {lower[0], lower[1], lower[2]};
    mesh.upper = {upper[0], upper[1], upper[2]};
  } else {
    const auto lower = m.pair("lower", {0.0, 0.0}), upper = m.required_pair("upper");
    mesh.lower = {lower[0], lower[1], 0.0};
    mesh.upper = {upper[0], upper[1], 1.0};
  }
  constexpr const char* axis_names[3] = {"x", "y", "z"};
  for (int a = 0; a < dimension; ++a)
    if (!(mesh.upper[a] > mesh.lower[a]))
      throw CaseError(fmt::format("mesh.upper: the domain is empty along {} (upper {} <= lower {})",
                                  axis_names[a], mesh.upper[a], mesh.lower[a]));
  for (int a = 0; a < dimension; ++a) {
    // Cells narrower than a nanometre are no continuum (a mesh in other units than metres?), and
    // cells far narrower than the coordinates' size lose their faces' positions to round-off.
    const double width = (mesh.upper[a] - mesh.lower[a]) / mesh.cells[a];
    const double reach = std::max(std::abs(mesh.lower[a]), std::abs(mesh.upper[a]));
    if (width < 1e-9)
      throw CaseError(fmt::format("mesh: cells {:.3g} m wide along {}, narrower than a nanometre, where no "
                                  "continuum model holds (lengths are in metres)", width, axis_names[a]));
    if (width < 1e-9 * reach)
      throw CaseError(fmt::format("mesh: cells {:.3g} m wide along {} at coordinates up to {:.3g} m: fewer than "
                                  "10 significant digits are left for their faces' positions (move mesh.lower "
                                  "nearer the origin)", width, axis_names[a], reach));
  }
  mesh.axisymmetric = m.choice("geometry", "planar", {"planar", "axisymmetric"}) == "axisymmetric";
  if (mesh.axisymmetric && dimension == 3)
    throw CaseError("mesh.geometry: an axisymmetric mesh is one layer (r, z); give two cell counts [nr, nz]");
  if (mesh.axisymmetric && mesh.lower[0] < 0.0)
    throw CaseError(fmt::format("mesh.lower: an axisymmetric mesh needs r >= 0 (x = r), got {}", mesh.lower[0]));
  const auto grading = dimension == 3 ? numbers_of_size(m, "grading", {1.0, 1.0, 1.0}, 3, "one ratio per axis")
                                      : numbers_of_size(m, "grading", {1.0, 1.0}, 2, "one ratio per axis");
  for (double g : grading) m.require_range("grading", g, 1e-3, 1e3);
  mesh.grading = {grading[0], grading[1], dimension == 3 ? grading[2] : 1.0};
  m.finish();
  return mesh;
}

// time_interface_courant: the sweeps' Courant number, which belongs to the soil's settings.
TimeSettings read_time(TableReader& top, double& time_interface_courant, std::vector<std::string>& two_phase_keys,
                       std::vector<std::string>& without_effect) {
  TimeSettings time;
  TableReader t = top.table("time");
  if (!t.present()) throw CaseError("time: missing table [time]" + top.misspelling_of("time"));
  time.end = t.required_number("end");
  // A step far below a nanosecond makes the inertia rho V / dt swamp every other coefficient of the
  // momentum rows, and V / a_P of the pressure rows underflows: the solve would fail, not the case.
  constexpr double shortest = 1e-9;
  const char* at_least = "at least 1e-9 s";
  t.require_range("end", time.end, shortest, inf, at_least);
  time.dt = t.number("dt", std::min(1e-3, time.end));
  t.require_range("dt", time.dt, shortest, inf, at_least);
  time.adaptive = t.boolean("adaptive", true);
  time.courant = t.number("courant", 0.5);
  t.require_range("courant", time.courant, 1e-6, 1e3);
  for (const char* key : {"courant_region", "interface_courant", "interface_substeps", "rest_speed"})
    if (t.has(key)) two_phase_keys.push_back(t.key_path(key));
  time.courant_region = t.choice("courant_region", "all", {"all", "soil"}) == "soil" ? CourantRegion::soil : CourantRegion::all;
  time.max_dt = t.number("max_dt", inf);
  t.require_range("max_dt", time.max_dt, shortest, inf, at_least);
  time.max_growth = t.number("max_growth", 1.2);
  t.require_range("max_growth", time.max_growth, 1.0, 10.0);
  time_interface_courant = t.number("interface_courant", 0.45);
  t.require_range("interface_courant", time_interface_courant, 1e-3, 0.49);
  time.interface_substeps = t.integer_in("interface_substeps", 1, 1, 100);
  time.steady_tolerance = t.number("steady_tolerance", 0.0);
  t.require_range("steady_tolerance", time.steady_tolerance, 0.0, inf);
  time.rest_speed = t.number("rest_speed", 0.0);
  t.require_range("rest_speed", time.rest_speed, 0.0, inf);
  time.max_steps = t.integer("max_steps", time.max_steps);
  t.require_range("max_steps", double(time.max_steps), 1, 1e12);
  if (!time.adaptive)
    for (const char* key : {"courant", "max_growth", "courant_region"})
      if (t.has(key)) without_effect.push_back(t.key_path(key) + ": time.adaptive = false takes the fixed step time.dt");
  t.finish();
  return time;
}

BoundarySet read_boundaries(TableReader& top, const GridSpec& mesh, std::vector<std::string>& two_phase_keys,
                            const std::vector<SoilMaterial>* materials) {
  BoundarySet boundaries;
  TableReader b = top.table("boundary");
  if (!b.present()) throw CaseError("boundary: missing table [boundary] (west, east, south, north)" + top.misspelling_of("boundary"));
  const int dimension = mesh.dimension();
  const auto mesh_sides = sides_of_dimension(dimension);
  if (dimension == 2)
    for (Side s : {Side::front, Side::back})
      if (b.has(side_name(s)))
        throw CaseError(fmt::format("boundary.{}: a planar mesh has no front and back sides (a mesh of layers has, "
                                    "mesh.cells = [nx, ny, nz])", side_name(s)));
  std::vector<TableReader> sides;  // all read first: a side missing is then not taken for another misspelt
  for (Side s : mesh_sides) sides.push_back(b.table(side_name(s)));
  for (Side s : mesh_sides) {
    bool is_axis = false;
    TableReader& side = sides[int(s)];
    if (!side.present())
      throw CaseError(fmt::format("{}: missing (every side needs a boundary type){}", side.path(),
                                  b.misspelling_of(side_name(s))));
    boundaries[int(s)] = read_boundary(side, is_axis, two_phase_keys, dimension, materials);
    if (is_axis && !(s == Side::west && mesh.axisymmetric && mesh.lower[0] == 0.0))
      throw CaseError(fmt::format("boundary.{}.type: \"axis\" is the west side at r = 0 of an axisymmetric mesh "
                                  "(mesh.geometry = \"axisymmetric\", mesh.lower[0] = 0)", side_name(s)));
    if (!is_axis && s == Side::west && mesh.axisymmetric && mesh.lower[0] == 0.0)
      throw CaseError("boundary.west.type: an axisymmetric mesh starting at r = 0 needs type = \"axis\" there");
  }
  b.finish();
  // Periodic sides come in the west-east pair: flow leaving through one enters through the other.
  for (Side s : mesh_sides) {
    if (boundaries[int(s)].kind != BoundaryKind::periodic) continue;
    if (normal_axis(s) != 0)
      throw CaseError(fmt::format("boundary.{}.type: only the west and east sides can be periodic (joined along x)",
                                  side_name(s)));
    const Side other = s == Side::west ? Side::east : Side::west;
    if (boundaries[int(other)].kind != BoundaryKind::periodic)
      throw CaseError(fmt::format("boundary.{}.type: a periodic side needs the opposite side periodic too "
                                  "(boundary.{} = {{ type = \"periodic\" }})", side_name(s), side_name(other)));
  }
  for (Side s : mesh_sides) {
    const auto& bc = boundaries[int(s)];
    if (bc.kind == BoundaryKind::wall && bc.velocity[normal_axis(s)] != 0.0)
      throw CaseError(fmt::format("boundary.{}.velocity: a wall cannot move through itself (normal component must be 0)",
                                  side_name(s)));
    if (bc.kind != BoundaryKind::inlet) continue;
    const int axis = normal_axis(s);
    const bool low = is_low_side(s);
    const double inward = low ? bc.velocity[axis] : -bc.velocity[axis];
    if (!(inward > 0.0))
      throw CaseError(fmt::format("boundary.{}.velocity: an inlet's velocity must point into the domain (its {} "
                                  "component {} than 0); a wall sliding along itself is type = \"wall\"",
                                  side_name(s), "xyz"[axis], low ? "greater" : "less"));
    for (int across = 0; across < mesh.dimension(); ++across) {
      const auto& span = bc.inflow_span[across];
      if (!std::isfinite(span[0]) && !std::isfinite(span[1])) continue;
      if (across == axis) {
        const char* along[3][2] = {{"span_y", "span_y, span_z"}, {"span_x", "span_x, span_z"}, {"", "span_x, span_y"}};
        throw CaseError(fmt::format("boundary.{}.span_{}: the {} side lies across {}; its opening is given along the "
                                    "side ({})", side_name(s), "xyz"[axis], side_name(s), "xyz"[axis],
                                    along[axis][mesh.dimension() == 3]));
      }
      if (!(span[0] < mesh.upper[across] && span[1] > mesh.lower[across]))
        throw CaseError(fmt::format("boundary.{}.span_{}: [{}, {}] lies outside the side, which runs from {} to {} "
                                    "along {}", side_name(s), "xyz"[across], span[0], span[1], mesh.lower[across],
                                    mesh.upper[across], "xyz"[across]));
    }
    if (carries_soil(bc) && !(bc.inflow_span[1][0] < mesh.lower[1] + bc.inflow_soil_depth))
      throw CaseError(fmt::format("boundary.{}.span_y: the opening starts at y = {}, above the soil's depth (up to y = "
                                  "{}), so the inlet would let in air only; lower the opening, deepen soil_depth, or "
                                  "leave soil_fraction out", side_name(s), bc.inflow_span[1][0],
                                  mesh.lower[1] + bc.inflow_soil_depth));
    if (axis == 1 && std::isfinite(bc.inflow_soil_depth))
      throw CaseError(fmt::format("boundary.{}.soil_depth: the depth is measured up from the bottom along y, so it "
                                  "applies to inlets on the west, east, front or back sides; on the {} side the "
                                  "whole inlet carries soil_fraction", side_name(s), side_name(s)));
  }
  if (has_inlet(boundaries) &&
      std::none_of(boundaries.begin(), boundaries.end(),
                   [](const BoundaryCondition& bc) { return bc.kind == BoundaryKind::atmosphere; }))
    throw CaseError("boundary: an inlet needs an open side (type = \"atmosphere\") for its flow to leave by; "
                    "the incompressible flow of a closed domain cannot take in more");
  return boundaries;
}

// granular: the case's soil has a rheology, whose cases default to the coupled solve; band: the air
// band that solve takes by default (0 where none may be laid).
NumericsSettings read_numerics(TableReader& top, bool granular, int band,
                               std::vector<std::string>& keys_without_effect) {
  NumericsSettings num;
  TableReader n = top.table("numerics");
  const std::string conv = n.choice("convection", "quick", {"upwind", "central", "blended", "quick"});
  parse_convection_scheme(conv, num.convection);
  const std::string coupling =
      n.choice("pressure_coupling", granular ? "coupled" : "projection", {"projection", "piso", "coupled"});
  num.pressure_coupling = coupling == "projection" ? PressureCoupling::projection
                          : coupling == "piso"     ? PressureCoupling::piso
                                                   : PressureCoupling::coupled;
  if (n.has("rotational_coefficient"))
    throw CaseError(fmt::format("{}: removed; the projection's rotational pressure correction diverged at steps of two "
                                "to twenty times rho h^2 / mu and more (the more, the smaller the coefficient), even "
                                "at a constant viscosity, and sped nothing up where it held (docs/method.md). Leave "
                                "the key out",
                                n.key_path("rotational_coefficient")));
  num.blending = n.number("blending", num.blending);
  n.require_range("blending", num.blending, 0.0, 1.0);
  num.outer_iterations = n.integer_in("outer_iterations", num.outer_iterations, 1, 1000);
  num.outer_tolerance = n.number("outer_tolerance", num.outer_tolerance);
  n.require_range("outer_tolerance", num.outer_tolerance, 0.0, 1.0);
  num.look_ahead_viscosity =
      n.choice("first_viscosity", "previous_step", {"previous_step", "look_ahead"}) == "look_ahead";
  num.mean_viscosity_pressure =
      n.choice("viscosity_pressure", "last_iterate", {"last_iterate", "mean_of_last_two"}) == "mean_of_last_two";
  num.air_band = n.integer_in("air_band", coupling == "coupled" ? band : 0, 0, 1000000);
  num.reuse_first_factorisation =
      n.choice("later_iterations", "own_factorisation", {"own_factorisation", "first_factorisation"}) ==
      "first_factorisation";
  num.krylov_iterations = n.integer_in("krylov_iterations", num.krylov_iterations, 1, 100);
  num.pressure_correctors = n.integer_in("pressure_correctors", num.pressure_correctors, 1, 100);
  num.momentum_predictor = n.boolean("momentum_predictor", num.momentum_predictor);
  num.transpose_stress = n.boolean("transpose_stress", num.transpose_stress);
  const std::string fv = n.choice("face_viscosity", "harmonic", {"harmonic", "arithmetic"});
  num.face_viscosity = fv == "harmonic" ? FaceViscosity::harmonic : FaceViscosity::arithmetic;
  num.quadratic_wall_gradient = n.choice("wall_gradient", "two_point", {"two_point", "quadratic"}) == "quadratic";
  // Conservative transport needs the coupled solve, whose continuity rows take each cell's own
  // momentum coefficient; the projection's mobility dt/rho cannot follow the mass a cell's momentum
  // then accelerates (docs/method.md, "Momentum").
  const bool coupled = num.pressure_coupling == PressureCoupling::coupled;
  num.conservative_momentum = n.choice("momentum_transport", coupled ? "conservative" : "advective",
                                       {"conservative", "advective"}) == "conservative";
  if (num.conservative_momentum && !coupled)
    throw CaseError(fmt::format("numerics.momentum_transport: \"conservative\" needs numerics.pressure_coupling = "
                                "\"coupled\" (it is \"{}\"); use \"advective\" with the projection and PISO",
                                coupling));
  num.density_jump_keeps_kinetic_energy =
      n.choice("density_jump", "keep_kinetic_energy", {"keep_kinetic_energy", "keep_velocity"}) == "keep_kinetic_energy";
  auto without_effect = [&](const char* key, bool used, const char* why) {
    if (n.has(key) && !used) keys_without_effect.push_back(n.key_path(key) + ": " + why);
  };
  without_effect("density_jump", num.conservative_momentum,
                 "used only with numerics.momentum_transport = \"conservative\" (the coupled solve's default)");
  without_effect("blending", conv == "blended", "used only with numerics.convection = \"blended\"");
  // The projection and PISO factorise nothing: a case switched to them keeps its coupled settings.
  without_effect("later_iterations", coupled, "used only with numerics.pressure_coupling = \"coupled\"");
  // One outer iteration has no later ones to solve by its factorisation.
  without_effect("later_iterations", !(coupled && num.reuse_first_factorisation && num.outer_iterations == 1),
                 "\"first_factorisation\" has no effect with numerics.outer_iterations = 1: there are no later "
                 "iterations");
  without_effect("krylov_iterations", coupled && num.reuse_first_factorisation && num.outer_iterations > 1,
                 "used only with numerics.later_iterations = \"first_factorisation\", the coupled solve and more "
                 "than one outer iteration");
  // Of no effect, so bound by nothing: its solver's requirements (read_solvers) do not apply either.
  num.reuse_first_factorisation = num.reuse_first_factorisation && coupled && num.outer_iterations > 1;
  without_effect("pressure_correctors", num.pressure_coupling == PressureCoupling::piso,
                 "used only with numerics.pressure_coupling = \"piso\"");
  without_effect("momentum_predictor", num.pressure_coupling == PressureCoupling::piso,
                 "used only with numerics.pressure_coupling = \"piso\" (the projection always predicts, the "
                 "coupled solve has no predictor)");
  n.finish();
  return num;
}

void read_solvers(TableReader& top, FlowSettings& flow) {
  TableReader s = top.table("solver");
  flow.momentum_solver = read_linear_solver(s.table("momentum"), flow.momentum_solver);
  flow.pressure_solver = read_linear_solver(s.table("pressure"), flow.pressure_solver);
  flow.coupled_solver = read_linear_solver(s.table("coupled"), flow.coupled_solver);
  // Cholesky factors need a symmetric positive definite matrix. On the saddle point they do not
  // stop; on the momentum matrix (not symmetric: convection) they solve another system, silently.
  for (const char* spd_only : {"icc", "cholesky"}) {
    if (flow.coupled_solver.pc_type == spd_only)
      throw CaseError(fmt::format("solver.coupled.pc_type: '{}' needs a symmetric positive definite matrix, and the "
                                  "coupled velocity-pressure system is a saddle point (use \"lu\")", spd_only));
    if (flow.momentum_solver.pc_type == spd_only)
      throw CaseError(fmt::format("solver.momentum.pc_type: '{}' needs a symmetric positive definite matrix, and the "
                                  "momentum matrix is not symmetric (convection); use \"hypre\", \"ilu\" or \"lu\"",
                                  spd_only));
  }
  // The later outer iterations' Krylov solve keeps continuity exact only on the factorised matrix.
  if (flow.numerics.reuse_first_factorisation && flow.coupled_solver.max_reuse > 1)
    throw CaseError("numerics.later_iterations: \"first_factorisation\" needs solver.coupled.reuse_preconditioner = 1: "
                    "a step's first iteration must factorise its own matrix for the later ones to hold its continuity rows");
  if (flow.numerics.reuse_first_factorisation && flow.coupled_solver.pc_type != "lu" &&
      flow.coupled_solver.pc_type != "redundant")
    throw CaseError(fmt::format("numerics.later_iterations: \"first_factorisation\" needs solver.coupled.pc_type = "
                                "\"lu\" or \"redundant\" (it is \"{}\"): only an exact factorisation of the first "
                                "iteration's matrix keeps its continuity rows in the later ones; or set "
                                "numerics.later_iterations = \"own_factorisation\"", flow.coupled_solver.pc_type));
  s.finish();
}

// One [[output.line]]; `earlier` are the lines before it, whose names it may not take again.
LineSample read_line_sample(TableReader& l, const GridSpec& mesh, const std::vector<LineSample>& earlier) {
  LineSample s;
  s.name = l.required_string("name");
  if (s.name.empty()) throw CaseError(fmt::format("{}.name: must not be empty", l.path()));
  // Its files' names, .NAME_NNNNN.csv.tmpPID while written, must stay within 255 bytes.
  constexpr size_t longest_name = 200;
  if (s.name.size() > longest_name)
    throw CaseError(fmt::format("{}.name: {} characters, more than {} (the files named after it would pass the "
                                "file system's limit)", l.path(), s.name.size(), longest_name));
  for (char ch : s.name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-'))
      throw CaseError(fmt::format("{}.name: '{}' may hold only letters, digits, '_' and '-'", l.path(), s.name));
  // The solver's own files must not be overwritten by a line's samples.
  // "stability": stability.csv marks a directory as a stability analysis's, which a run refuses.
  for (const char* own : {"history", "surface", "failure_line", "column_height", "lode_dissipation", "fields", "stability"})
    if (s.name == own)
      throw CaseError(fmt::format("{}.name: '{}' is the name of one of the run's own output files{}", l.path(), s.name,
                                  s.name == "stability" ? " (a stability analysis's table, stability.csv)" : ""));
  // Numbered files are NAME_NNNNN.csv: a name ending in '_' and five digits could be one of them.
  if (const size_t u = s.name.find_last_of('_');
      u != std::string::npos && s.name.size() - u > 5 &&
      std::all_of(s.name.begin() + long(u) + 1, s.name.end(),
                  [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)); }))
    throw CaseError(fmt::format("{}.name: '{}' ends in '_' and five digits, like the numbered output "
                                "files (NAME_NNNNN.csv) it could overwrite", l.path(), s.name));
  for (const auto& other : earlier)
    if (other.name == s.name) throw CaseError(fmt::format("{}.name: a second line named '{}'", l.path(), s.name));
  // [x, y] on a planar mesh, [x, y, z] on a mesh of layers.
  const int axes = mesh.dimension();
  auto point = [&](const char* key) -> std::array<double, 3> {
    if (axes == 2) {
      const auto p = l.required_pair(key);
      return {p[0], p[1], 0.0};
    }
    if (!l.has(key)) throw CaseError(l.key_path(key) + ": missing" + l.misspelling_of(key));
    const auto v = numbers_of_size(l, key, {}, 3, "[x, y, z]");
    return {v[0], v[1], v[2]};
  };
  s.start = point("start");
  s.end = point("end");
  for (const auto& [key, p] : {std::pair{"start", s.start}, std::pair{"end", s.end}})
    for (int a = 0; a < axes; ++a)
      if (!(p[a] >= mesh.lower[a] && p[a] <= mesh.upper[a])) {
        if (axes == 2)
          throw CaseError(fmt::format("{}.{}: [{}, {}] lies outside the domain [{}, {}] x [{}, {}]", l.path(), key,
                                      p[0], p[1], mesh.lower[0], mesh.upper[0], mesh.lower[1], mesh.upper[1]));
        throw CaseError(fmt::format("{}.{}: [{}, {}, {}] lies outside the domain [{}, {}] x [{}, {}] x [{}, {}]",
                                    l.path(), key, p[0], p[1], p[2], mesh.lower[0], mesh.upper[0], mesh.lower[1],
                                    mesh.upper[1], mesh.lower[2], mesh.upper[2]));
      }
  if (s.start == s.end) throw CaseError(fmt::format("{}.end: the line ends where it starts", l.path()));
  s.points = l.integer_in("points", 101, 2, 10000000);
  l.finish();
  return s;
}

OutputSettings read_output(TableReader& top, const GridSpec& mesh, double end_time) {
  OutputSettings output;
  TableReader o = top.table("output");
  output.interval = o.number("interval", 0.0);
  o.require_range("interval", output.interval, 0.0, inf);
  constexpr double max_outputs = 1e5;
  if (output.interval > 0.0 && end_time / output.interval > max_outputs)
    throw CaseError(fmt::format("output.interval: {} s gives {:.3g} outputs to time.end = {} s, more than {:.0e}",
                                output.interval, end_time / output.interval, end_time, max_outputs));
  output.times = o.numbers("times", {});
  // Times past time.end are not written (a run shortened with --set time.end keeps its list; the
  // run's start warns of them, case_advice).
  for (double t : output.times) o.require_range("times", t, 0.0, inf, "zero or positive");
  if (double(output.times.size()) > max_outputs)
    throw CaseError(fmt::format("output.times: {} times, more than {:.0e} outputs", output.times.size(), max_outputs));
  output.fields = o.boolean("fields", true);
  output.checkpoints = o.boolean("checkpoints", true);
  output.progress_seconds = o.number("progress_seconds", 2.0);
  o.require_range("progress_seconds", output.progress_seconds, 0.0, inf, "zero (no progress line) or positive");
  for (TableReader l : o.tables("line")) output.lines.push_back(read_line_sample(l, mesh, output.lines));
  o.finish();
  return output;
}

PhaseSettings read_fluid(TableReader& top) {
  PhaseSettings fluid;
  TableReader f = top.table("fluid");
  if (!f.present())
    throw CaseError("fluid: missing table [fluid] (density and viscosity), or [soil] and [air]" +
                    top.misspelling_of("fluid") + top.misspelling_of("soil"));
  fluid.density = f.required_number("density");
  f.require_range("density", fluid.density, 1e-300, inf, "positive");
  fluid.viscosity = f.required_number("viscosity");
  f.require_range("viscosity", fluid.viscosity, 0.0, inf, "zero or positive");
  f.finish();
  return fluid;
}

// The domain's corners in the x-y plane, where the shapes are drawn.
interface::Point plane_lower(const GridSpec& mesh) { return {mesh.lower[0], mesh.lower[1]}; }
interface::Point plane_upper(const GridSpec& mesh) { return {mesh.upper[0], mesh.upper[1]}; }

// Why a shape within [lo, hi] covers no area of the mesh's domain (interface::overlaps): it lies
// outside, or what lies inside is too small to count. A ring whose hole holds the domain is said so.
std::string no_area_in_domain(const interface::Shape& shape, const GridSpec& mesh) {
  const auto [lo, hi] = interface::bounding_box(shape);
  // A ring covers none of the domain where its outer disc does: its hole holds it (interface::overlaps).
  if (const auto* ring = std::get_if<interface::Ring>(&shape);
      ring && interface::overlaps(interface::Circle{ring->centre, ring->outer_radius}, plane_lower(mesh), plane_upper(mesh)))
    return fmt::format("the ring's hole (radius {} about [{}, {}]) holds the whole domain [{}, {}] x [{}, {}]",
                       ring->inner_radius, ring->centre[0], ring->centre[1], mesh.lower[0], mesh.upper[0],
                       mesh.lower[1], mesh.upper[1]);
  const bool outside = !(lo[0] < mesh.upper[0] && hi[0] > mesh.lower[0] && lo[1] < mesh.upper[1] && hi[1] > mesh.lower[1]);
  return fmt::format("the shape, within [{}, {}] x [{}, {}], covers {} area of the domain [{}, {}] x [{}, {}]{}", lo[0],
                     hi[0], lo[1], hi[1], outside ? "no" : "next to no", mesh.lower[0], mesh.upper[0], mesh.lower[1],
                     mesh.upper[1], outside ? "" : " (less than 1e-12 of it: a shape far smaller than a cell)");
}

// A solid of a mesh of layers must reach into the domain; `what` names it in the message.
void require_solid_in_domain(const interface::Shape3& solid, const GridSpec& mesh, const std::string& what) {
  const auto [lo, hi] = interface::bounding_box(solid);
  bool inside = true;
  for (int a = 0; a < 3; ++a) inside = inside && lo[a] < mesh.upper[a] && hi[a] > mesh.lower[a];
  // A height map without a bottom reaches down without end.
  auto span = [](double low, double high) {
    return std::isinf(low) ? fmt::format("below {:.6g}", high) : fmt::format("[{:.6g}, {:.6g}]", low, high);
  };
  if (!inside)
    throw CaseError(fmt::format("{} within x {}, y {}, z {} lies outside the domain [{}, {}] x [{}, {}] x [{}, {}]", what,
                                span(lo[0], hi[0]), span(lo[1], hi[1]), span(lo[2], hi[2]), mesh.lower[0],
                                mesh.upper[0], mesh.lower[1], mesh.upper[1], mesh.lower[2], mesh.upper[2]));
}

// What a mesh of layers has so far (docs/method.md, "Known limitations"), refused with the key to change.
void require_what_layers_have(const CaseConfig& c) {
  if (c.mesh.dimension() == 2) return;
  if (c.soil)
    for (const auto& solid : c.soil->initial_soil_3d) require_solid_in_domain(solid, c.mesh, "initial.soil: a shape");
  for (size_t k = 0; k < c.obstacle_solids.size(); ++k)
    require_solid_in_domain(c.obstacle_solids[k], c.mesh, fmt::format("obstacle[{}]: the shape", k));
}

// Rules between tables, once every table is read: shapes within the domain, and what obstacles and
// the air band need of the rest of the case.
void require_consistent(const CaseConfig& c) {
  require_what_layers_have(c);
  if (c.soil) {
    // A shape may reach past the domain (it is clipped), but one wholly outside it holds no soil.
    for (size_t k = 0; k < c.soil->initial_soil.size(); ++k)
      if (!interface::overlaps(c.soil->initial_soil[k], plane_lower(c.mesh), plane_upper(c.mesh)))
        throw CaseError(fmt::format("initial.soil[{}]: {}", k, no_area_in_domain(c.soil->initial_soil[k], c.mesh)));
  }
  auto frictional_wall = [&](const std::string& wall) {
    if (!c.soil) return;
    if (!c.soil->rheology)
      throw CaseError(fmt::format("{}: a wall's friction (friction_angle, adhesion) acts on a granular soil, and this "
                                  "case's soil is Newtonian (no [soil.rheology])", wall));
    if (c.soil->yield_pressure != YieldPressure::face)  // SoilPhase::update_face_viscosity sets the wall's faces
      throw CaseError(fmt::format("{}: a wall's friction (friction_angle, adhesion) needs soil.yield_pressure = \"face\" "
                                  "(the viscosity is then taken on faces, the wall's among them)", wall));
  };
  for (Side s : box_sides)
    if (boundary(c.flow.boundaries, s).friction) frictional_wall(fmt::format("boundary.{}", side_name(s)));
  for (size_t k = 0; k < c.obstacle_friction.size(); ++k)
    if (c.obstacle_friction[k]) frictional_wall(fmt::format("obstacle[{}]", k));
  for (size_t k = 0; k < c.obstacles.size(); ++k)
    if (!interface::overlaps(c.obstacles[k], plane_lower(c.mesh), plane_upper(c.mesh)))
      throw CaseError(fmt::format("obstacle[{}]: {}", k, no_area_in_domain(c.obstacles[k], c.mesh)));
  if (c.has_obstacles()) {
    // The obstacles' walls are built into the coupled solve's rows and the operators it uses.
    if (c.flow.numerics.pressure_coupling != PressureCoupling::coupled)
      throw CaseError("obstacle: needs numerics.pressure_coupling = \"coupled\" (the projection and PISO do not "
                      "know blocked cells)");
    if (c.mesh.axisymmetric) throw CaseError("obstacle: not on an axisymmetric mesh (this case has mesh.geometry = \"axisymmetric\")");
  }
  if (c.mesh.periodic_x) {
    if (c.mesh.axisymmetric)
      throw CaseError("boundary.west.type: periodic sides are not on an axisymmetric mesh (this case has "
                      "mesh.geometry = \"axisymmetric\")");
    if (c.mesh.grading[0] != 1.0)
      throw CaseError(fmt::format("mesh.grading: periodic west and east sides need cells of one width along x, so "
                                  "that the two ends meet (grading {} along x; give 1.0)", c.mesh.grading[0]));
    if (c.mesh.cells[0] < 3)
      throw CaseError(fmt::format("mesh.cells: periodic west and east sides need at least 3 cells along x, got {}",
                                  c.mesh.cells[0]));
    if (c.flow.numerics.air_band > 0)
      throw CaseError("numerics.air_band: the air band's region does not reach across periodic sides; set "
                      "numerics.air_band = 0 (the whole domain is solved)");
  }
  if (c.time.rest_speed > 0.0 && c.soil && !c.soil->displacement)
    throw CaseError("time.rest_speed: needs soil.displacement = true (the soil must have moved before it can come to "
                    "rest, which its displacement tells)");
  if (c.flow.numerics.air_band > 0) {
    // The air beyond the band is held at rest under the pressure of the air column above it.
    if (c.flow.numerics.pressure_coupling != PressureCoupling::coupled)
      throw CaseError("numerics.air_band: applies to pressure_coupling = \"coupled\" only");
    if (!c.soil) throw CaseError("numerics.air_band: needs a [soil] phase to solve around");
    if (c.flow.gravity[0] != 0.0 || c.flow.gravity[2] != 0.0)
      throw CaseError("numerics.air_band: needs gravity along y (the air beyond the band is hydrostatic)");
    // The band is laid again once the soil comes within half of it of its edge; in between, each of a
    // step's sweeps may carry a sliver of soil one cell further (as SoilPhase::advect reckons), and
    // soil that crossed the region's edge would cross faces no continuity row balances, and its
    // volume be lost.
    const int band = c.flow.numerics.air_band;
    const int reach = c.time.interface_substeps;
    if (band - band / 2 < reach + 1)
      throw CaseError(fmt::format("numerics.air_band = {}: too narrow for steps of {} sweep(s) "
                                  "(time.interface_substeps), each of which may carry soil a cell further; it must "
                                  "be at least {}",
                                  band, reach, 2 * reach + 1));
  }
}

CaseConfig read_case(const toml::table& root, const std::filesystem::path& source) {
  CaseConfig c;
  c.source = source;
  double interface_courant = 0.45;
  std::vector<std::string> two_phase_keys;  // given, but used only with soil
  TableReader top(&root, "");
  c.title = top.string("title", source.stem().string());
  c.mesh = read_mesh(top);
  c.time = read_time(top, interface_courant, two_phase_keys, c.keys_without_effect);
  {
    TableReader p = top.table("physics");
    if (c.mesh.dimension() == 3) {
      const auto g = numbers_of_size(p, "gravity", {0.0, 0.0, 0.0}, 3, "[gx, gy, gz] on a mesh of layers");
      c.flow.gravity = {g[0], g[1], g[2]};
    } else {
      const auto g = p.pair("gravity", {0.0, 0.0});
      c.flow.gravity = {g[0], g[1], 0.0};
    }
    // The flow is the same in every half-plane through the axis: a force along r would point out of
    // each half-plane's own axis in a different direction, which no body force does.
    if (c.mesh.axisymmetric && c.flow.gravity[0] != 0.0)
      throw CaseError(fmt::format("physics.gravity: {} along r in an axisymmetric mesh; gravity there acts along the "
                                  "axis (y = z): [0, gz]", c.flow.gravity[0]));
    p.finish();
  }
  if (top.has("soil")) {
    if (top.has("fluid"))
      throw CaseError("fluid: a two-phase case ([soil] and [air]) takes no [fluid] table (the light phase is [air])");
    c.soil = read_soil(top, c.keys_without_effect, c.mesh.dimension());
  } else {
    // The tables only a case with soil reads, named as such rather than as unknown.
    for (const char* table : {"air", "mixture", "initial"})
      if (top.has(table))
        throw CaseError(fmt::format("{}: applies to cases with soil only (this case has no [soil]{}){}", table,
                                    top.has("fluid") ? ", and [fluid] for its one phase" : "", top.misspelling_of("soil")));
    c.fluid = read_fluid(top);
  }
  c.flow.boundaries = read_boundaries(top, c.mesh, two_phase_keys, c.soil ? &c.soil->materials : nullptr);
  if (c.soil) {  // each material is laid out by a shape or comes in through an inlet
    std::vector<bool> used(c.soil->materials.size() + 1, false);
    for (int m : c.soil->initial_material) used[size_t(m)] = true;
    for (const auto& bc : c.flow.boundaries)
      if (carries_soil(bc)) used[size_t(bc.inflow_material)] = true;
    for (size_t k = 1; k < used.size(); ++k)
      if (!used[k])
        throw CaseError(fmt::format("soil.materials[{}]: no initial.soil shape is of material '{}' (give one `material "
                                    "= \"{}\"`), nor does an inlet carry it", k - 1, c.soil->materials[k - 1].name,
                                    c.soil->materials[k - 1].name));
  }
  if (c.soil && c.soil->initial_soil.empty() && c.soil->initial_soil_3d.empty() &&
      std::none_of(c.flow.boundaries.begin(), c.flow.boundaries.end(), carries_soil)) {
    if (!top.has("initial"))
      throw CaseError("initial: missing table [[initial.soil]] (where the soil starts; only an inlet of soil can fill "
                      "a domain that starts without)" + top.misspelling_of("initial"));
    throw CaseError("initial.soil: at least one shape is required (only an inlet of soil can fill a domain that "
                    "starts without)" + top.table("initial").misspelling_of("soil"));
  }
  c.mesh.periodic_x = boundary(c.flow.boundaries, Side::west).kind == BoundaryKind::periodic;
  // Air at rest on a periodic slope: its weight along x is carried as by its hydrostatic pressure.
  if (c.mesh.periodic_x && c.soil) c.flow.periodic_ambient_density = c.soil->air_density;
  // A granular case's coupled solve covers its soil and an air band by default, wide enough for the
  // step's sweeps, where one may be laid (require_consistent): not across periodic sides, nor where
  // the air beyond is not hydrostatic along y.
  // A mesh of layers takes the projection by default.
  const bool layers = c.mesh.dimension() == 3;
  const bool granular = c.soil && c.soil->rheology;
  const bool band_allowed = granular && !c.mesh.periodic_x && c.flow.gravity[0] == 0.0 && c.flow.gravity[2] == 0.0;
  c.flow.numerics = read_numerics(top, granular && !layers,
                                  band_allowed ? std::max(default_air_band, 2 * c.time.interface_substeps + 1) : 0,
                                  c.keys_without_effect);
  read_solvers(top, c.flow);
  c.output = read_output(top, c.mesh, c.time.end);
  for (TableReader obstacle : top.tables("obstacle")) {
    c.obstacle_friction.push_back(read_wall_friction(obstacle, two_phase_keys));
    // An elevation model rougher than the cells stands in single columns; lowered by default, as a user
    // would resample it to the mesh by hand (the other solids are drawn for the mesh, and refused).
    const bool height_map = layers && obstacle.has("shape") && obstacle.string("shape", "") == "height_map";
    c.obstacle_lowers_thin_ridges.push_back(height_map && obstacle.choice("thin_ridges", "lower", {"lower", "refuse"}) == "lower");
    if (layers) {  // a solid, or a planar shape across the whole depth (a terrain profile's ridge)
      if (auto solid = read_solid(obstacle)) c.obstacle_solids.push_back(*solid);
      else c.obstacle_solids.push_back(interface::Extrusion{read_shape(obstacle), c.mesh.lower[2], c.mesh.upper[2]});
    } else {
      c.obstacles.push_back(read_shape(obstacle));
    }
  }
  top.finish();
  for (auto& bc : c.flow.boundaries)
    if (bc.kind == BoundaryKind::atmosphere)
      bc.outside_density = c.soil ? c.soil->density_mixing(bc.inflow_soil_fraction, c.soil->air_density, c.soil->soil_density)
                                  : c.fluid.density;
  if (!c.soil && !two_phase_keys.empty())
    throw CaseError(fmt::format("{}: applies to cases with soil only (this case has [fluid], no [soil])", two_phase_keys.front()));
  if (c.soil) c.soil->interface_courant = interface_courant;
  require_consistent(c);
  return c;
}

// toml++ writes a float with 17 significant digits (0.20000000000000001): each float outside the
// strings of `toml` is written again as the shortest text that reads back to the same double (0.2),
// kept a TOML float (2650.0, not the integer 2650).
std::string shortest_floats(std::string_view toml) {
  std::string out;
  out.reserve(toml.size());
  size_t k = 0;
  while (k < toml.size()) {
    const char ch = toml[k];
    if (ch == '\'' || ch == '"') {  // a string, written through (a basic string's \" does not end it)
      const std::string triple(3, ch);  // a multi-line string ends at its own three quotes only
      size_t end;
      if (toml.substr(k, 3) == triple) {
        end = k + 3;
        while (end < toml.size() && toml.substr(end, 3) != triple) end += ch == '"' && toml[end] == '\\' ? 2 : 1;
        end = std::min(end + 3, toml.size());
        while (end < toml.size() && toml[end] == ch) ++end;  // up to two quotes of the content before the closing three
      } else {
        end = k + 1;
        while (end < toml.size() && toml[end] != ch) end += ch == '"' && toml[end] == '\\' ? 2 : 1;
        end = std::min(end + 1, toml.size());
      }
      out.append(toml.substr(k, end - k));
      k = end;
      continue;
    }
    const bool starts_value = (std::isdigit(static_cast<unsigned char>(ch)) || ch == '-' || ch == '+') &&
                              (k == 0 || std::string_view(" \t[,=").find(toml[k - 1]) != std::string_view::npos);
    if (starts_value) {
      size_t end = k;
      while (end < toml.size() && std::string_view("0123456789+-.eE_").find(toml[end]) != std::string_view::npos) ++end;
      const std::string token(toml.substr(k, end - k));
      const size_t next = toml.find_first_not_of(" \t", end);
      const bool is_key = next != std::string_view::npos && toml[next] == '=';  // a bare key of digits, kept
      if (!is_key && token.find_first_of(".eE") != std::string::npos && token.find('_') == std::string::npos) {
        double x = 0.0;
        const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), x);
        char buffer[64];
        if (ec == std::errc() && ptr == token.data() + token.size()) {
          const auto written = std::to_chars(buffer, buffer + sizeof buffer, x);
          std::string shortest(buffer, written.ptr);
          if (shortest.find_first_of(".e") == std::string::npos) shortest += ".0";
          out += shortest;
          k = end;
          continue;
        }
      }
      out += token;
      k = end;
      continue;
    }
    out += ch;
    ++k;
  }
  return out;
}

// Calls at(shape, path) on each shape's table of the initial soil and of the obstacles, path naming it
// ("obstacle[2]").
template <class At>
void for_each_shape(toml::table& root, At&& at) {
  auto each = [&](toml::array* shapes, const std::string& path) {
    if (!shapes) return;
    for (size_t k = 0; k < shapes->size(); ++k)
      if (toml::table* shape = shapes->get(k)->as_table()) at(*shape, fmt::format("{}[{}]", path, k));
  };
  if (toml::table* initial = root["initial"].as_table()) each((*initial)["soil"].as_array(), "initial.soil");
  each(root["obstacle"].as_array(), "obstacle");
}

// The file a shape's `FILE_KEY = "name"` names, for a shape of kind `kind`: a relative path is taken from
// the case file's directory. `what` says what the file holds.
std::filesystem::path shape_file(const toml::table& shape, const std::string& key, const std::string& kind,
                                 const char* what, const std::filesystem::path& source) {
  const auto name = shape.get(key.substr(key.rfind('.') + 1))->value<std::string>();
  if (!name) throw CaseError(fmt::format("{}: expected a string, the name of {}", key, what));
  if (name->empty()) throw CaseError(fmt::format("{}: empty; name {}", key, what));
  const auto given = shape.contains("shape") ? shape.get("shape")->value<std::string>() : std::nullopt;
  if (given != kind) throw CaseError(fmt::format("{}: used only with shape = \"{}\"", key, kind));
  std::filesystem::path file(*name);
  if (file.is_relative() && !source.parent_path().empty()) file = source.parent_path() / file;
  return file;
}

// Polygons whose outline is a file (`points_file`, io/points_file.hpp): the points are read into the
// tree as the shape's `points`, so that the case as run (granflow_case.toml) holds them and every
// reader after sees one kind of polygon.
void read_points_files(toml::table& root, const std::filesystem::path& source) {
  for_each_shape(root, [&](toml::table& shape, const std::string& path) {
    if (!shape.contains("points_file")) return;
    const std::string key = path + ".points_file";
    const auto file = shape_file(shape, key, "polygon", "a file of points (x and y in m, a point per line)", source);
    if (shape.contains("points"))
      throw CaseError(fmt::format("{}: give the polygon's points or its points_file, not both", path));
    const auto vertices = read_points_file(file, key);
    polygon_of(vertices, fmt::format("{} ('{}')", key, file.string()));  // its errors name the file
    toml::array points;
    for (const auto& [x, y] : vertices) points.push_back(toml::array{x, y});
    shape.erase("points_file");
    shape.insert("points", std::move(points));
  });
}

// Height maps whose nodes are a file (`heights_file`, io/height_map_file.hpp): read into the tree as the
// shape's `origin`, `spacing` and `heights`, as a polygon's points_file is.
void read_height_map_files(toml::table& root, const std::filesystem::path& source) {
  for_each_shape(root, [&](toml::table& shape, const std::string& path) {
    if (!shape.contains("heights_file")) return;
    const std::string key = path + ".heights_file";
    const auto file = shape_file(shape, key, "height_map", "an ESRI ASCII grid of heights (.asc)", source);
    for (const char* given : {"origin", "spacing", "heights"})
      if (shape.contains(given))
        throw CaseError(fmt::format("{}: give the height map's {} in its heights_file or here, not both", path, given));
    // Only the nodes over the domain are kept (read into the run's record, held by each rank): an
    // elevation model usually covers far more. The domain's x and z in the map's coordinates, where the
    // case gives its corners (the tables' own checks come after) and the shape's offset.
    interface::HeightMap map = read_height_map_file(file, key);
    auto three = [](const toml::node* n) -> std::optional<std::array<double, 3>> {
      const toml::array* a = n ? n->as_array() : nullptr;
      if (!a || a->size() != 3) return std::nullopt;
      std::array<double, 3> v{};
      for (size_t k = 0; k < 3; ++k) {
        const auto x = (*a)[k].value<double>();
        if (!x || !std::isfinite(*x)) return std::nullopt;
        v[k] = *x;
      }
      return v;
    };
    const auto lower = three(root.at_path("mesh.lower").node()), upper = three(root.at_path("mesh.upper").node());
    const auto offset = shape.contains("offset") ? three(shape.get("offset")) : std::array<double, 3>{};
    if (lower && upper && offset)
      map = interface::cropped(map, {(*lower)[0] - (*offset)[0], (*upper)[0] - (*offset)[0]},
                               {(*lower)[2] - (*offset)[2], (*upper)[2] - (*offset)[2]});
    toml::array heights;
    for (int r = 0; r < map.nz; ++r) {
      toml::array row;
      for (int i = 0; i < map.nx; ++i) row.push_back(map.heights[size_t(r) * map.nx + i]);
      heights.push_back(std::move(row));
    }
    shape.erase("heights_file");
    shape.insert("origin", toml::array{map.origin[0], map.origin[1]});
    shape.insert("spacing", toml::array{map.spacing[0], map.spacing[1]});
    shape.insert("heights", std::move(heights));
  });
}

CaseConfig parse_case_here(std::string_view text, const std::vector<std::string>& overrides,
                           const std::filesystem::path& source) {
  toml::table root;
  try {
    root = toml::parse(text, source.string());
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw CaseError(fmt::format("{}:{}:{}: {}", source.string(), where.line, where.column, e.description()));
  }
  for (const auto& o : overrides) apply_override(root, o);
  read_points_files(root, source);
  read_height_map_files(root, source);
  CaseConfig c = read_case(root, source);
  c.overrides = overrides;
  std::ostringstream as_run;
  as_run << toml::toml_formatter{root};
  c.as_run = shortest_floats(as_run.str());
  return c;
}

}  // namespace

// toml++ recurses once per level of nesting, each part of a dotted key a level, at some 300 bytes of
// stack a level: a key of 32 000 parts overflows the main thread's 8 MiB and kills the process. So the
// case is parsed and read on a thread whose stack is sized by the characters that can open a level.
CaseConfig parse_case(std::string_view text, const std::vector<std::string>& overrides,
                      const std::filesystem::path& source) {
  size_t openers = std::count_if(text.begin(), text.end(), [](char ch) { return ch == '.' || ch == '[' || ch == '{'; });
  for (const auto& o : overrides) openers += std::count_if(o.begin(), o.end(), [](char ch) { return ch == '.'; });
  struct Job {
    std::string_view text;
    const std::vector<std::string>& overrides;
    const std::filesystem::path& source;
    std::optional<CaseConfig> result;
    std::exception_ptr error;
  } job{text, overrides, source, std::nullopt, nullptr};
  auto body = [](void* arg) -> void* {
    auto* j = static_cast<Job*>(arg);
    try {
      j->result.emplace(parse_case_here(j->text, j->overrides, j->source));
    } catch (...) {
      j->error = std::current_exception();
    }
    return nullptr;
  };
  pthread_attr_t attr;
  pthread_attr_init(&attr);
  pthread_attr_setstacksize(&attr, (size_t(16) << 20) + 512 * openers);
  pthread_t thread;
  const int rc = pthread_create(&thread, &attr, body, &job);
  pthread_attr_destroy(&attr);
  if (rc != 0)
    throw CaseError(fmt::format("the case holds {} dots and brackets, too many to read ({})", openers,
                                std::strerror(rc)));
  pthread_join(thread, nullptr);
  if (job.error) std::rethrow_exception(job.error);
  return std::move(*job.result);
}

CaseConfig load_case(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw CaseError(fmt::format("{}: is a directory, not a case file", file.string()));
  const TextFile read = read_text_file(file, case_file_limit);
  switch (read.status) {
    case TextFile::Status::read: break;
    case TextFile::Status::cannot_open:
      throw CaseError(fmt::format("{}: cannot open the case file: {}", file.string(), read.reason));
    case TextFile::Status::cannot_read:
      throw CaseError(fmt::format("{}: cannot read the case file: {}", file.string(), read.reason));
    case TextFile::Status::too_long:
      throw CaseError(fmt::format("{}: longer than {} MiB, not a case file (a shape of many points reads them from a "
                                  "points_file)", file.string(), case_file_limit >> 20));
  }
  const std::string& text = read.text;
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw CaseError(fmt::format("{}: the case file is empty", file.string()));
  try {
    return parse_case(text, overrides, file);
  } catch (const CaseError& e) {
    const std::string what = e.what();
    if (what.starts_with(file.string())) throw;  // a TOML syntax error names its file and line already
    if (what.starts_with("--set ")) throw;        // an assignment that could not be applied names itself
    // A key (or an entry under it) that a --set assignment gave is named as the command line's, not
    // the file's, which may not even hold it.
    for (const auto& assignment : overrides)
      if (names_key_of(what, assignment)) throw CaseError(fmt::format("--set {}", what));
    throw CaseError(fmt::format("{}: {}", file.string(), what));
  }
}

}  // namespace granflow
