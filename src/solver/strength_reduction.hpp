#pragma once
// Factor of safety by strength reduction, as finite-element slope analysis finds it (Griffiths & Lane
// 1999, Geotechnique 49(3)): the case is run with the soil's strength divided by a factor F, the
// cohesion as C / F and the friction as tan(phi) / F, and F is bisected between the largest factor at
// which the soil stands and the smallest at which it fails. "Fails" means that some soil moves
// further than a limit (a tenth of a cell by default) within the case's time.end.
#include <mpi.h>

#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "io/case_file.hpp"

namespace granflow {

// The case with its soil's strength divided by `factor`: cohesion C / F and friction angle
// atan(tan(phi) / F), with the outer iterations converged (at least 10 per step, to a velocity change
// of 1e-6 or less), which the onset of failure needs (docs/validation.md, "A vertical cut"). The
// result is read anew from the case's text with these keys set, so that its record holds them.
// Throws CaseError for a case whose soil has no rheology of constant friction, or a factor <= 0.
CaseConfig reduced_strength(const CaseConfig& config, double factor);

struct StrengthTrial {
  double factor = 0.0;
  bool fails = false;
  bool diverged = false;              // the run stopped on divergence (counted as failing)
  std::string divergence;             // its message, when it diverged
  double largest_displacement = 0.0;  // m, of the soil (cells with c >= 0.5) when the trial ended
  double displacement_limit = 0.0;    // m, the displacement past which it counted as failing
  double time = 0.0;                  // s, when it ended: time.end, or earlier once the soil moved past the limit
  long steps = 0;
  // Steps whose outer iterations stopped at numerics.outer_iterations before outer_tolerance. Near its
  // limit a soil converges slowly, and a viscosity that lags makes it stand a little longer.
  long unconverged_steps = 0;
  double wall_seconds = 0.0;
  bool earlier = false;  // taken from an earlier analysis of the same case (stability --restart), not run again
};

struct StrengthReductionSettings {
  double first_factor = 1.0;
  double tolerance = 0.01;          // bisect until fails_at - stands_at <= tolerance
  // m; 0: a tenth of the mesh's smallest spacing. A soil that stands creeps by the regularisation's
  // rate, some H t / m ([VoF] Eq. 12: 1e-3 m for H = 10 m over 10 s at m = 1e5 s), far below it.
  double displacement_limit = 0.0;
  double smallest_factor = 0.01, largest_factor = 100.0;  // where the search gives up
};

struct StrengthReductionResult {
  double stands_at = 0.0;                                        // largest factor tried at which the soil stands
  double fails_at = std::numeric_limits<double>::infinity();     // smallest at which it fails
  std::vector<StrengthTrial> trials;
  bool bracketed() const { return stands_at > 0.0 && fails_at < std::numeric_limits<double>::infinity(); }
};

// One trial (collective on comm): the case at `factor` into trial_directory(out, factor) (no files if out
// is empty), failing when the soil moves further than displacement_limit (0: a tenth of the mesh's
// smallest spacing) within time.end, or diverges.
StrengthTrial strength_trial(MPI_Comm comm, const CaseConfig& config, const std::filesystem::path& out, double factor,
                             double displacement_limit = 0.0);

// Runs the trials (collective on comm), each into out/F_<factor> (no files if out is empty): from
// first_factor, doubling or halving until one stands and one fails, then bisecting. on_trial is
// called after each trial, on every rank. A factor that `earlier` holds a trial of (an analysis of the
// same case, continued) is not run again: that trial is taken, marked `earlier`. The search is the
// same either way, so an analysis stopped midway and continued tries the factors it would have.
StrengthReductionResult factor_of_safety(MPI_Comm comm, const CaseConfig& config, const std::filesystem::path& out,
                                         const StrengthReductionSettings& settings,
                                         const std::function<void(const StrengthTrial&)>& on_trial = {},
                                         const std::vector<StrengthTrial>& earlier = {});

// A trial's output directory under out.
std::filesystem::path trial_directory(const std::filesystem::path& out, double factor);

}  // namespace granflow
