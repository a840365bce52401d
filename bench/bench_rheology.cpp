// Viscosity evaluations per second of each granular model, on random 3D strain rates.
//   build/bench_rheology --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

#include "models/rheology/granular_rheology.hpp"

namespace {

using granflow::rheology::FrictionSource;
using granflow::rheology::GranularRheology;
using granflow::rheology::Model;
using granflow::rheology::Regularisation;
using granflow::rheology::RheologyParameters;
using granflow::rheology::StrainRate;

// Pre-generated once, so the loop times the rheology and not the random number generator.
// 4096 points (160 kB) stay in L2, like a block of cells in a solver sweep.
struct Samples {
  std::vector<StrainRate> strain_rates;
  std::vector<double> pressures;
};

const Samples& samples() {
  static const Samples data = [] {
    constexpr std::size_t count = 4096;
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::uniform_real_distribution<double> decade(-4.0, 2.0);
    std::uniform_real_distribution<double> pressure(0.0, 5e3);
    Samples s;
    s.strain_rates.reserve(count);
    s.pressures.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
      const double scale = std::pow(10.0, decade(rng));
      StrainRate d{unit(rng), unit(rng), unit(rng), unit(rng), unit(rng), unit(rng)};
      const double mean = (d.xx + d.yy + d.zz) / 3.0;  // incompressible, as in the solver
      d.xx -= mean;
      d.yy -= mean;
      d.zz -= mean;
      s.strain_rates.push_back(scale * d);
      s.pressures.push_back(pressure(rng));
    }
    return s;
  }();
  return data;
}

void run(benchmark::State& state, const RheologyParameters& parameters) {
  const GranularRheology rheology(parameters);
  const Samples& s = samples();
  const std::size_t n = s.strain_rates.size();
  for (auto _ : state) {
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      sum += rheology.dynamic_viscosity(s.strain_rates[i], s.pressures[i]);
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(n));
}

RheologyParameters ys_model(Model model) {  // [YS] Sec. 4 settings
  RheologyParameters p;
  p.model = model;
  p.regularisation = Regularisation::clip;
  p.friction_angle_deg = 36.5;
  p.density = 1430.0;
  return p;
}

void BM_DruckerPrager(benchmark::State& state) { run(state, ys_model(Model::drucker_prager)); }
void BM_MohrCoulomb(benchmark::State& state) { run(state, ys_model(Model::mohr_coulomb)); }
void BM_MatsuokaNakai(benchmark::State& state) { run(state, ys_model(Model::matsuoka_nakai)); }

void BM_DruckerPragerBingham(benchmark::State& state) {  // [VoF] Sec. 4.1 settings
  RheologyParameters p;
  p.model = Model::drucker_prager_bingham;
  p.regularisation = Regularisation::exponential;
  p.friction_angle_deg = 19.8;
  p.regularisation_time = 1e5;
  p.density = 2650.0;
  run(state, p);
}

void BM_MuOfIDruckerPrager(benchmark::State& state) {
  RheologyParameters p = ys_model(Model::drucker_prager);
  p.friction = FrictionSource::mu_of_I;
  run(state, p);
}

BENCHMARK(BM_DruckerPrager);
BENCHMARK(BM_MohrCoulomb);
BENCHMARK(BM_MatsuokaNakai);
BENCHMARK(BM_DruckerPragerBingham);
BENCHMARK(BM_MuOfIDruckerPrager);

}  // namespace

BENCHMARK_MAIN();
