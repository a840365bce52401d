#include "io/case_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "io/case_error.hpp"
#include "io/table_reader.hpp"

namespace granflow {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

void apply_override(toml::table& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw CaseError(fmt::format("--set '{}': expected KEY=VALUE", assignment));
  const std::string key = assignment.substr(0, eq);
  const std::string value = assignment.substr(eq + 1);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    parsed = toml::table{{"v", value}};  // a bare word is a string
  }
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
    if (!n->is_table()) throw CaseError(fmt::format("--set '{}': '{}' is not a table", assignment, part));
    t = n->as_table();
    rest = rest.substr(dot + 1);
  }
}

LinearSolverSettings read_linear_solver(TableReader r, LinearSolverSettings d) {
  d.ksp_type = r.string("ksp_type", d.ksp_type);
  d.pc_type = r.string("pc_type", d.pc_type);
  d.rtol = r.number("rtol", d.rtol);
  r.require_range("rtol", d.rtol, 0.0, 1.0);
  d.atol = r.number("atol", d.atol);
  r.require_range("atol", d.atol, 0.0, inf);
  d.max_iterations = int(r.integer("max_iterations", d.max_iterations));
  r.require_range("max_iterations", d.max_iterations, 1, 1e9);
  r.finish();
  return d;
}

BoundaryCondition read_boundary(TableReader r) {
  if (!r.present()) throw CaseError(fmt::format("{}: missing (every side needs a boundary type)", r.path()));
  BoundaryCondition bc;
  const std::string type = r.choice("type", "", {"wall", "slip", "atmosphere"});
  if (type == "wall") {
    bc.kind = BoundaryKind::wall;
    bc.wall_velocity = r.pair("velocity", {0.0, 0.0});
  } else if (type == "slip") {
    bc.kind = BoundaryKind::slip;
  } else {
    bc.kind = BoundaryKind::atmosphere;
    bc.pressure = r.number("pressure", 0.0);
    bc.total_pressure = r.choice("pressure_kind", "total", {"total", "static"}) == "total";
  }
  r.finish();
  return bc;
}

CaseConfig read_case(const toml::table& root, const std::filesystem::path& source) {
  CaseConfig c;
  c.source = source;
  TableReader top(&root, "");
  c.title = top.string("title", source.stem().string());

  {
    TableReader m = top.table("mesh");
    if (!m.present()) throw CaseError("mesh: missing table [mesh]");
    auto cells = m.numbers("cells", {}, 2);
    if (cells.size() != 2) throw CaseError("mesh.cells: expected two integers [nx, ny]");
    for (double n : cells)
      if (n < 1 || n != std::floor(n) || n > 1e8)
        throw CaseError(fmt::format("mesh.cells: {} is not a positive whole number of cells", n));
    c.mesh.cells = {int(cells[0]), int(cells[1])};
    c.mesh.lower = m.pair("lower", {0.0, 0.0});
    c.mesh.upper = m.required_pair("upper");
    for (int a = 0; a < 2; ++a)
      if (!(c.mesh.upper[a] > c.mesh.lower[a]))
        throw CaseError(fmt::format("mesh.upper: the domain is empty along {} (upper {} <= lower {})",
                                    a == 0 ? "x" : "y", c.mesh.upper[a], c.mesh.lower[a]));
    c.mesh.grading = m.pair("grading", {1.0, 1.0});
    for (double g : c.mesh.grading) m.require_range("grading", g, 1e-3, 1e3);
    m.finish();
  }
  {
    TableReader t = top.table("time");
    if (!t.present()) throw CaseError("time: missing table [time]");
    c.time.end = t.required_number("end");
    t.require_range("end", c.time.end, 0.0, inf, "positive");
    if (c.time.end <= 0) throw CaseError("time.end: must be positive");
    c.time.dt = t.number("dt", std::min(1e-3, c.time.end));
    if (!(c.time.dt > 0)) throw CaseError(fmt::format("time.dt: {} is invalid, must be positive", c.time.dt));
    c.time.adaptive = t.boolean("adaptive", true);
    c.time.courant = t.number("courant", 0.5);
    t.require_range("courant", c.time.courant, 1e-6, 1e3);
    c.time.max_dt = t.number("max_dt", inf);
    if (!(c.time.max_dt > 0)) throw CaseError("time.max_dt: must be positive");
    c.time.max_growth = t.number("max_growth", 1.2);
    t.require_range("max_growth", c.time.max_growth, 1.0, 10.0);
    c.time.steady_tolerance = t.number("steady_tolerance", 0.0);
    t.require_range("steady_tolerance", c.time.steady_tolerance, 0.0, inf);
    c.time.max_steps = t.integer("max_steps", c.time.max_steps);
    t.require_range("max_steps", double(c.time.max_steps), 1, 1e12);
    t.finish();
  }
  {
    TableReader p = top.table("physics");
    c.flow.gravity = p.pair("gravity", {0.0, 0.0});
    p.finish();
  }
  {
    TableReader f = top.table("fluid");
    if (!f.present()) throw CaseError("fluid: missing table [fluid] (density and viscosity)");
    c.fluid.density = f.required_number("density");
    f.require_range("density", c.fluid.density, 1e-300, inf, "positive");
    c.fluid.viscosity = f.required_number("viscosity");
    f.require_range("viscosity", c.fluid.viscosity, 0.0, inf, "zero or positive");
    f.finish();
  }
  {
    TableReader b = top.table("boundary");
    if (!b.present()) throw CaseError("boundary: missing table [boundary] (west, east, south, north)");
    for (Side s : all_sides) c.flow.boundaries[int(s)] = read_boundary(b.table(side_name(s)));
    b.finish();
    for (Side s : all_sides) {
      const auto& bc = c.flow.boundaries[int(s)];
      if (bc.kind == BoundaryKind::wall && bc.wall_velocity[normal_axis(s)] != 0.0)
        throw CaseError(fmt::format("boundary.{}.velocity: a wall cannot move through itself (normal component must be 0)",
                                    side_name(s)));
    }
  }
  {
    TableReader n = top.table("numerics");
    auto& num = c.flow.numerics;
    const std::string conv = n.choice("convection", "quick", {"upwind", "central", "blended", "quick"});
    parse_convection_scheme(conv, num.convection);
    num.pressure_coupling = n.choice("pressure_coupling", "projection", {"projection", "piso"}) == "projection"
                                ? PressureCoupling::projection
                                : PressureCoupling::piso;
    num.rotational_coefficient = n.number("rotational_coefficient", num.rotational_coefficient);
    n.require_range("rotational_coefficient", num.rotational_coefficient, 0.0, 2.0);
    num.blending = n.number("blending", num.blending);
    n.require_range("blending", num.blending, 0.0, 1.0);
    num.outer_iterations = int(n.integer("outer_iterations", num.outer_iterations));
    n.require_range("outer_iterations", num.outer_iterations, 1, 1000);
    num.outer_tolerance = n.number("outer_tolerance", num.outer_tolerance);
    n.require_range("outer_tolerance", num.outer_tolerance, 0.0, 1.0);
    num.pressure_correctors = int(n.integer("pressure_correctors", num.pressure_correctors));
    n.require_range("pressure_correctors", num.pressure_correctors, 1, 100);
    num.momentum_predictor = n.boolean("momentum_predictor", num.momentum_predictor);
    num.transpose_stress = n.boolean("transpose_stress", num.transpose_stress);
    const std::string fv = n.choice("face_viscosity", "harmonic", {"harmonic", "arithmetic"});
    num.face_viscosity = fv == "harmonic" ? FaceViscosity::harmonic : FaceViscosity::arithmetic;
    n.finish();
  }
  {
    TableReader s = top.table("solver");
    c.flow.momentum_solver = read_linear_solver(s.table("momentum"), c.flow.momentum_solver);
    c.flow.pressure_solver = read_linear_solver(s.table("pressure"), c.flow.pressure_solver);
    s.finish();
  }
  {
    TableReader o = top.table("output");
    c.output.interval = o.number("interval", 0.0);
    o.require_range("interval", c.output.interval, 0.0, inf);
    c.output.times = o.numbers("times", {});
    for (double t : c.output.times) o.require_range("times", t, 0.0, c.time.end, "within [0, time.end]");
    c.output.fields = o.boolean("fields", true);
    c.output.progress_seconds = o.number("progress_seconds", 2.0);
    for (TableReader l : o.tables("line")) {
      LineSample s;
      s.name = l.required_string("name");
      for (char ch : s.name)
        if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-'))
          throw CaseError(fmt::format("{}.name: '{}' may hold only letters, digits, '_' and '-'", l.path(), s.name));
      s.start = l.required_pair("start");
      s.end = l.required_pair("end");
      s.points = int(l.integer("points", 101));
      l.require_range("points", s.points, 2, 1e7);
      l.finish();
      c.output.lines.push_back(s);
    }
    o.finish();
  }
  top.finish();
  return c;
}

}  // namespace

CaseConfig parse_case(std::string_view text, const std::vector<std::string>& overrides,
                      const std::filesystem::path& source) {
  toml::table root;
  try {
    root = toml::parse(text, source.string());
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw CaseError(fmt::format("{}:{}:{}: {}", source.string(), where.line, where.column, e.description()));
  }
  for (const auto& o : overrides) apply_override(root, o);
  return read_case(root, source);
}

CaseConfig load_case(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  std::ifstream in(file);
  if (!in) throw CaseError(fmt::format("{}: cannot open the case file", file.string()));
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_case(ss.str(), overrides, file);
}

}  // namespace granflow
