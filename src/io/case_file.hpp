#pragma once
// A granflow case: everything a run needs, read from a TOML file plus --set overrides.
#include <fmt/format.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "mesh/grid.hpp"
#include "solver/flow_settings.hpp"
#include "solver/soil_settings.hpp"

namespace granflow {

// Where the flow Courant number limits the step: everywhere, or only in and next to the soil (the
// interface Courant limit still applies everywhere; air far from the soil is integrated implicitly).
enum class CourantRegion { all, soil };

struct TimeSettings {
  double end = 1.0;
  double dt = 1e-3;          // initial step, or the fixed step when not adaptive
  bool adaptive = true;
  double courant = 0.5;      // largest flow Courant number
  CourantRegion courant_region = CourantRegion::all;
  double max_dt = 1e30;
  double max_growth = 1.2;   // largest ratio of successive steps
  // VoF sweeps one flow step may take: the step is limited to this many times the interface Courant
  // number of one sweep, and the advection sub-cycles. 1 sizes the step by one sweep.
  int interface_substeps = 1;
  double steady_tolerance = 0.0;  // > 0: stop when max|dv/dt| / max|v| falls below it (1/s)
  // > 0: stop once the soil, having moved (its displacement past a tenth of the smallest cell), is
  // slower than this everywhere (cells with c >= 0.5), m/s: a run to where a slide comes to rest.
  double rest_speed = 0.0;
  long max_steps = 100000000;
};

struct LineSample {
  std::string name;
  std::array<double, 3> start{0, 0, 0}, end{0, 0, 0};  // z = 0 on a planar mesh
  int points = 101;
};

struct OutputSettings {
  double interval = 0.0;       // simulated time between outputs; 0: only the start and the end
  std::vector<double> times;   // extra output times
  bool fields = true;          // ParaView series
  bool checkpoints = true;     // a checkpoint at each output time, to restart from (granflow run --restart)
  std::vector<LineSample> lines;
  double progress_seconds = 2.0;  // wall seconds between progress lines (0: none)
};

struct PhaseSettings {
  double density = 1.0;
  double viscosity = 1e-3;  // dynamic, Pa s
};

// The mesh's cell counts as text ("300 x 100", "40 x 20 x 10"), and the unit its volumes are in.
inline std::string cell_counts(const GridSpec& mesh) {
  return mesh.dimension() == 3 ? fmt::format("{} x {} x {}", mesh.cells[0], mesh.cells[1], mesh.cells[2])
                           : fmt::format("{} x {}", mesh.cells[0], mesh.cells[1]);
}
inline const char* volume_unit(const GridSpec& mesh) {
  return mesh.dimension() == 3 ? "m^3" : mesh.axisymmetric ? "m^3 per radian" : "m^2 per metre of depth";
}

struct CaseConfig {
  std::filesystem::path source;
  std::string title;
  GridSpec mesh;
  TimeSettings time;
  FlowSettings flow;
  PhaseSettings fluid;              // single-phase runs
  std::optional<SoilSettings> soil;  // two-phase soil and air runs
  OutputSettings output;
  // Obstacles and terrain ([[obstacle]]): a cell whose centre lies in any of these shapes is blocked,
  // and its faces to open cells are no-slip walls (mesh/obstacles.hpp). A planar mesh's shapes; on a
  // mesh of layers the solids, a planar shape extruded across the whole depth (and `obstacles` empty).
  std::vector<interface::Shape> obstacles;
  std::vector<interface::Shape3> obstacle_solids;
  bool has_obstacles() const { return !obstacles.empty() || !obstacle_solids.empty(); }
  // Each obstacle's own friction against the soil (friction_angle, adhesion), or none: its faces then
  // hold the soil as its own strength does, as the domain's walls (solver/boundary.hpp).
  std::vector<std::optional<rheology::WallFriction>> obstacle_friction;
  // Per obstacle: whether its ridges one cell wide are lowered to the mesh (a height map's
  // `thin_ridges = "lower"`, its default; mesh/thin_ridges.hpp), or refused as any such wall is.
  std::vector<bool> obstacle_lowers_thin_ridges;
  // Keys the case gives that its other choices make of no effect, each "KEY: why" (a warning, not an
  // error: a key kept for switching numerics with --set is legitimate; case_advice prints them).
  std::vector<std::string> keys_without_effect;
  // The --set assignments the case was read with, and the whole case with them applied as TOML text
  // (toml++'s layout, without the file's comments): what a run records as granflow_case.toml, which
  // reads back to the same case.
  std::vector<std::string> overrides;
  std::string as_run;
};

// "key.path=value" overrides; value is parsed as TOML (number, bool, array, quoted string) and
// taken as a bare string otherwise.
CaseConfig load_case(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
CaseConfig parse_case(std::string_view toml_text, const std::vector<std::string>& overrides = {},
                      const std::filesystem::path& source = "<string>");

}  // namespace granflow
