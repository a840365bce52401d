#pragma once
// A manufactured steady flow, shared by the planar and the axisymmetric order tests: the case runs
// to steady state with density 1 and the exact viscosity and body force imposed, and the discrete
// velocity and pressure are measured against the exact ones on three meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "solver/simulation.hpp"
#include "test_support.hpp"

namespace granflow::test {

struct ManufacturedFlow {
  using Function = double (*)(double, double);
  Function viscosity, force_x, force_y;  // imposed
  Function u, v, p;                      // exact
};

struct VelocityPressureErrors {
  double u, v, p;  // L2 errors; the pressure's without its mean
  long steps = 0;  // time steps to the steady state
};

inline VelocityPressureErrors run_manufactured(const std::string& case_text, const ManufacturedFlow& flow_fields) {
  Simulation sim(PETSC_COMM_WORLD, parse_case(case_text), "");
  FlowSolver& flow = sim.flow();
  const Grid& g = sim.grid();
  flow.set_property_update([&g, mu = flow_fields.viscosity](FlowSolver& f) {
    VecSet(f.density().global(), 1.0);
    fill(g, f.viscosity(), mu);
  });
  flow.enable_body_force();
  fill(g, flow.body_force(0), flow_fields.force_x);
  fill(g, flow.body_force(1), flow_fields.force_y);
  const RunSummary s = sim.run();
  EXPECT_TRUE(s.reached_steady_state) << g.nx() << " cells: not steady after " << s.steps << " steps";
  return {l2_error(g, flow.velocity(0), flow_fields.u), l2_error(g, flow.velocity(1), flow_fields.v),
          l2_error(g, flow.pressure(), flow_fields.p, true), s.steps};
}

// Prints the errors and the observed orders between successive meshes, and expects at least 1.8 for
// both velocity components and 1.5 for the pressure; u_name and v_name label the components.
inline void expect_second_order(const char* label, const int (&sizes)[3], const VelocityPressureErrors (&e)[3],
                                const char* u_name, const char* v_name) {
  for (int k = 0; k < 3; ++k)
    std::printf("%s n = %3d: L2 error %s %.3e  %s %.3e  p %.3e\n", label, sizes[k], u_name, e[k].u, v_name, e[k].v,
                e[k].p);
  for (int k = 1; k < 3; ++k) {
    const double ou = std::log2(e[k - 1].u / e[k].u), ov = std::log2(e[k - 1].v / e[k].v),
                 op = std::log2(e[k - 1].p / e[k].p);
    std::printf("%s observed order %d -> %d: %s %.2f  %s %.2f  p %.2f\n", label, sizes[k - 1], sizes[k], u_name, ou,
                v_name, ov, op);
    EXPECT_GE(ou, 1.8);
    EXPECT_GE(ov, 1.8);
    EXPECT_GE(op, 1.5);
  }
}

}  // namespace granflow::test
