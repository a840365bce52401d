// A silo drained through a slot in its floor (cases/silo_discharge.toml, cases/silo_discharge_water.toml):
// the soil's discharge does not depend on how full the silo is (a granular hour-glass) and grows with
// the slot as L^(3/2) (Beverloo's law in two dimensions), while water's falls with the height left as
// sqrt(h) (Torricelli's clepsydra); Staron, Lagree & Popinet (2012) found the first two with a
// continuum of constant friction. Measured on the shipped 2.5 mm cells to t = 1.5 s
// (scripts/compare_silo.py, docs/validation.md): the soil's Q within 1.9 % as the fill falls from
// 0.28 to 0.13 m, Q ~ h^0.01; water's Q ~ h^0.49. Here 5 mm cells to t = 0.8 s: the soil's Q ~ h^0.046,
// water's h^0.49, and Q ~ L^1.46 between slots of 4 and 8 cm. And the energy budget of the open silo:
// over [0.2, 0.8] s the kinetic, potential and dissipated energy gained is what the sides brought in
// (history's boundary_work: the energy the outflow carries out), to a share of the potential energy
// released.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "solver/simulation.hpp"
#include "../verification/test_support.hpp"

namespace granflow {
namespace {

constexpr double silo_half_width = 0.15;  // m, the case's domain

// The whole silo's discharge (twice the half's) over [t0, t1], and the mean fill height then.
struct Discharge {
  double rate = 0.0;  // m^2/s per metre of slot
  double fill = 0.0;  // m
};

struct SiloRun {
  Discharge early, late;  // over [0.2, 0.5] s and [0.5, 0.8] s
  // (kinetic + potential + dissipated energy gained - brought in) / potential energy released, and the
  // share of that released which the outflow carries out, over [0.2, 0.8] s
  double energy_residual = 0.0, carried_out = 0.0;
};

SiloRun run_silo(const std::string& case_file, double half_slot) {
  const auto out = test::scratch("silo");
  const CaseConfig config = load_case(
      test::repo_path(case_file),
      {"mesh.cells=[30,80]", "time.end=0.8", "output.progress_seconds=0", "output.fields=false",
       fmt::format("obstacle=[{{shape = \"box\", lower = [{}, -0.01], upper = [0.16, 0.005]}}]", half_slot)});
  Simulation sim(PETSC_COMM_WORLD, config, out);
  sim.run();
  SiloRun r;
  if (test::is_root()) {
    const auto h = test::read_csv((out / "history.csv").string());
    const auto &t = h.at("time"), &outflow = h.at("soil_outflow"), &volume = h.at("soil_volume");
    auto window = [&](double t0, double t1) {
      return Discharge{2.0 * (test::interp(t, outflow, t1) - test::interp(t, outflow, t0)) / (t1 - t0),
                       0.5 * (test::interp(t, volume, t0) + test::interp(t, volume, t1)) / silo_half_width};
    };
    auto change = [&](const char* column) {
      return test::interp(t, h.at(column), 0.8) - test::interp(t, h.at(column), 0.2);
    };
    const double released = -change("potential_energy");
    r = SiloRun{window(0.2, 0.5), window(0.5, 0.8),
                (change("kinetic_energy") + change("dissipated_energy") - change("boundary_work")) / released - 1.0,
                -change("boundary_work") / released};
  }
  test::remove_scratch(out);
  return r;
}

// The exponent a of Q ~ h^a between the two windows.
double fill_exponent(const SiloRun& r) {
  return std::log(r.late.rate / r.early.rate) / std::log(r.late.fill / r.early.fill);
}

TEST(SiloDischarge, SoilDrainsAtARateOfItsSlotAloneAndWaterAsTheHeightLeft) {
  const SiloRun soil = run_silo("cases/silo_discharge.toml", 0.02);
  const SiloRun wide = run_silo("cases/silo_discharge.toml", 0.04);
  const SiloRun water = run_silo("cases/silo_discharge_water.toml", 0.02);
  if (!test::is_root()) return;
  const double g = 9.81;
  const double slot_exponent = std::log(wide.early.rate / soil.early.rate) / std::log(2.0);
  for (const auto& [name, r] : {std::pair{"soil, L = 4 cm", &soil}, std::pair{"soil, L = 8 cm", &wide},
                                std::pair{"water, L = 4 cm", &water}})
    std::printf("%s: Q = %.5f m^2/s at h = %.4f m, %.5f at h = %.4f m: Q ~ h^%.3f\n", name, r->early.rate,
                r->early.fill, r->late.rate, r->late.fill, fill_exponent(*r));
  std::printf("soil: Q ~ L^%.3f between L = 4 and 8 cm (Beverloo 1.5); Q / (g^0.5 L^1.5) = %.3f\n", slot_exponent,
              soil.early.rate / (std::sqrt(g) * std::pow(0.04, 1.5)));
  for (const auto& [name, r] : {std::pair{"soil, L = 4 cm", &soil}, std::pair{"water, L = 4 cm", &water}})
    std::printf("%s: of the potential energy released over t = 0.2-0.8 s the outflow carried out %.4f; budget "
                "residual %+.2e\n", name, r->carried_out, r->energy_residual);
  // The soil dissipates most of what it releases, and its budget closes (measured -0.15 % here). Water's
  // jet carries most of it out; what the jet loses to the convection scheme on these 5 mm cells (4
  // across the slot) is missing from its budget, -11 % here and -0.54 % on the shipped 2.5 mm cells;
  // a budget with more than was released would be energy from nowhere.
  EXPECT_LT(std::abs(soil.energy_residual), 0.02);
  EXPECT_GT(water.carried_out, 0.8);
  EXPECT_LT(water.energy_residual, 0.0);
  EXPECT_GT(water.energy_residual, -0.15);
  // Each drained far enough that the two laws part: water's sqrt(h) alone would change Q by 4 % or more.
  for (const SiloRun* r : {&soil, &water}) EXPECT_LT(r->late.fill, 0.92 * r->early.fill);
  EXPECT_LT(std::abs(fill_exponent(soil)), 0.1);  // 0.046 here, 0.012 on 2.5 mm cells
  EXPECT_NEAR(fill_exponent(water), 0.5, 0.1);
  // The wider slot over its first window only: by its second its fill falls to about L, where the
  // hour-glass ends (between the two windows its rate goes as h^0.19).
  EXPECT_NEAR(slot_exponent, 1.5, 0.15);
}

}  // namespace
}  // namespace granflow
