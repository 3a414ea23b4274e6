// Long physics validations (ctest label `validation`): seed 001 and seed 002 section III.A.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "helpers.hpp"
#include "particle/run.hpp"
#include "particle/simulation.hpp"
#include "particle/theory.hpp"

using namespace twinflow::particle;
using namespace twinflow::particle::testing;

// Seed 001: isothermal DPD, Euler update, 2D, range 4, gamma = sigma = 1 (so T = 1/2),
// w_R = 1 - r/4, w_D = w_R^2. Measured T against eq. (25) for three densities and a range of dt.
// Eq. (25) is mean field: expect agreement as dt -> 0 (within 1% at dt <= 0.01), a growing
// systematic deviation at larger dt. Tolerance at dt <= 0.01: 1% (the issue's) + 4 stderr.
TEST(Seed001, IsothermalEulerTemperatureAgainstEq25) {
  std::printf("# seed 001: rho, dt, T measured, stderr, T eq.(25), deviation, dt_c eq.(28)\n");
  for (const double rho : {1.0, 2.0, 3.0}) {
    for (const double dt : {0.0025, 0.005, 0.01, 0.02, 0.04, 0.06}) {
      ParticleParameters p;
      p.dim = 2;
      p.box = {{24, 24, 1}};
      p.density = rho;
      p.energy = EnergyModel::Isothermal;
      p.integrator = Integrator::Euler;
      p.temperature = 0.5;
      p.gamma = 1;
      p.dissipation = {4.0, 2.0};
      p.heat = HeatLaw::None;
      p.conservative = ConservativeForce::None;
      p.dt = dt;
      using M = Model<2, NoConservative, IsothermalFriction, NoHeat>;
      const M m{{}, IsothermalFriction{1.0, 1.0, Weight(4, 2)}, {}, 1, 1, 4};
      const double predicted = marsh_yeomans_temperature(p), dtc = marsh_yeomans_critical_dt(p);
      std::vector<double> t;
      try {
        Simulation<M> sim(m, p);
        const long relax = static_cast<long>(2 / dt) + 200, samples = 400, every = 5;
        for (long s = 0; s < relax; ++s) sim.step();
        for (long k = 0; k < samples; ++k) {
          for (int s = 0; s < every; ++s) sim.step();
          t.push_back(2 * sim.kinetic_energy() / (2 * (sim.state().size() - 1.0)));
        }
      } catch (const InstabilityError&) {
        std::printf("%4.1f %7.4f  unstable (dt_c = %.4f)\n", rho, dt, dtc);
        continue;
      }
      const Estimate e = block_average(t, 20);
      std::printf("%4.1f %7.4f %9.5f %8.5f %9.5f %+8.4f %8.4f\n", rho, dt, e.mean, e.stderr_,
                  predicted, e.mean / predicted - 1, dtc);
      if (dt <= 0.01) {
        EXPECT_NEAR(e.mean, predicted, 0.01 * predicted + 4 * e.stderr_) << rho << " " << dt;
      }
    }
  }
}

// Seed 002 section III.A: T_I vs T_K for ec-verlet at dt = 0.005 ... 0.05 (the paper: agreement
// at 0.01, ~50% apart at 0.05) and g(r) unchanged for dt <= 0.02. Reported as a table; asserts
// T_K = T_I within 4 stderr + 0.5% at dt <= 0.01, and g(r) within 4 stderr-equivalents of the
// dt = 0.005 curve (bin counts are Poisson: se = g / sqrt(count)) + 1% for dt <= 0.02.
TEST(Seed002, InternalAgainstKineticTemperatureAndRdf) {
  std::printf("# seed 002 III.A (ec-verlet, N = 6000, 10 tau + 20 tau): dt, T_K, se, T_I, se, "
              "T_K/T_I - 1, max|g - g(0.005)|\n");
  std::vector<double> g_ref;
  for (const double dt : {0.005, 0.01, 0.02, 0.05}) {
    auto p = seed002(Integrator::EcVerlet, dt);
    p.equilibration_steps = static_cast<long>(10 / dt);
    p.steps = static_cast<long>(20 / dt);
    p.sample_interval = std::max(1L, static_cast<long>(0.05 / dt));
    p.rdf_bins = 50;
    const RunOutput out = run_particles(p);
    const auto& r = out.summary;
    const double tk = twinflow::io::find(r, {"T_kinetic"})->get<double>(),
                 tks = twinflow::io::find(r, {"T_kinetic_stderr"})->get<double>();
    const double ti = twinflow::io::find(r, {"T_internal"})->get<double>(),
                 tis = twinflow::io::find(r, {"T_internal_stderr"})->get<double>();
    std::vector<double> g;
    std::istringstream rdf(out.rdf_csv);
    std::string line;
    while (std::getline(rdf, line))
      if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0])))
        g.push_back(std::stod(line.substr(line.find(',') + 1)));
    if (g_ref.empty()) g_ref = g;
    double worst = 0;
    const double samples = static_cast<double>(twinflow::io::find(r, {"samples"})->get<double>());
    bool g_ok = true;
    for (std::size_t b = 2; b < g.size(); ++b) { // first bins hold few pairs
      const double diff = std::fabs(g[b] - g_ref[b]);
      worst = std::max(worst, diff);
      // pairs in bin b per sample ~ N rho V_shell g / 2; Poisson error of the mean
      const double shell = 4 * M_PI * std::pow((b + 0.5) / g.size(), 2) / g.size();
      const double count = 0.5 * 6000 * 3 * shell * g_ref[b] * samples;
      const double se = g_ref[b] * std::sqrt(2.0 / count);
      if (dt <= 0.02 && diff > 4 * se * 3 + 0.01 * g_ref[b]) g_ok = false; // x3: correlated samples
    }
    std::printf("%6.3f %8.5f %8.5f %8.5f %8.5f %+8.4f %8.4f\n", dt, tk, tks, ti, tis, tk / ti - 1,
                worst);
    if (dt <= 0.01) {
      EXPECT_NEAR(tk, ti, 4 * std::hypot(tks, tis) + 0.005 * ti) << dt;
    }
    EXPECT_TRUE(g_ok) << "g(r) changed at dt = " << dt;
  }
}

// Shardlow + velocity-Verlet without the offset on LAMMPS's system (rho = 3, a0 = 15, sigma = 3,
// c_v = 200, inverse heat law kappa = 40, w = 1 - r for every term, N = 6000): total-energy
// change over 10 tau beside LAMMPS's measured drift (docs/performance.md): ours must
// not be worse. Median over 3 seeds, as the peer's script reports.
TEST(Shardlow, EnergyDriftBesideLammps) {
  const double lammps[] = {7.8e-8, 4.6e-7, 2.6e-6, 1.0e-4};
  const double dts[] = {0.005, 0.01, 0.02, 0.05};
  std::printf("# shardlow (no offset) |E(10 tau) - E(0)|/E(0), median of 3 seeds; LAMMPS\n");
  for (int k = 0; k < 4; ++k) {
    std::vector<double> drifts;
    for (const std::uint64_t seed : {2024u, 2025u, 2026u}) {
      ParticleParameters p;
      p.box = {{20, 10, 10}};
      p.dt = dts[k];
      p.seed = seed;
      p.integrator = Integrator::Shardlow;
      p.cv = 200;
      using Ml = Model<3, ConstantRepulsion, ConstantSigma, InverseConstantHeat>;
      const Ml m{ConstantRepulsion{15, 1, 1},
                 ConstantSigma{3, Weight(1, 2)},
                 InverseConstantHeat{40, Weight(1, 2)},
                 1,
                 200,
                 1};
      Simulation<Ml> sim(m, p);
      for (long s = 0; s < static_cast<long>(5 / p.dt); ++s) sim.step(); // 5 tau warm-up
      const double e0 = sim.total_energy();
      for (long s = 0; s < static_cast<long>(10 / p.dt); ++s) sim.step();
      drifts.push_back(std::fabs(sim.total_energy() - e0) / e0);
    }
    std::sort(drifts.begin(), drifts.end());
    std::printf("%6.3f %10.3e %10.3e\n", dts[k], drifts[1], lammps[k]);
    EXPECT_LE(drifts[1], lammps[k]) << "dt = " << dts[k];
  }
}

// Seed 002 section III.B (cases/slab_conduction_periodic.prm): hot slab 10 <= x < 10.5, cold
// 0 <= x < 0.5, J0 = 2.7, 200 tau to steady state then 150 tau sampled. The paper: T(x) ~ 0.91 +
// 0.018 x, kappa ~ 150; the issue asks for the slope within 5% and kappa within 5% of 150.
TEST(Seed002, SlabConductivity) {
  auto p = seed002(Integrator::EcVerlet, 0.005);
  p.heat_slabs = {{0, 10.0, 10.5, 540.0}, {0, 0.0, 0.5, -540.0}}; // Power = 2 J0 A
  p.equilibration_steps = 40000;
  p.steps = 30000;
  p.sample_interval = 20;
  p.bins = {{40, 1, 1}};
  const RunOutput out = run_particles(p);
  const auto& slab = *twinflow::io::find(out.summary, {"heat_slabs"});
  const double kappa = twinflow::io::find(slab, {"kappa"})->get<double>(),
               se = twinflow::io::find(slab, {"kappa_stderr"})->get<double>();
  const double slope = twinflow::io::find(slab, {"cold_to_hot", "slope"})->get<double>();
  std::printf("slab: kappa = %.1f +- %.1f, cold-to-hot slope %.5f\n", kappa, se, slope);
  EXPECT_NEAR(kappa, 150, 0.05 * 150 + 4 * se);
  EXPECT_NEAR(slope, 0.018, 0.05 * 0.018);
}
