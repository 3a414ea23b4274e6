// Long physics validations (ctest label `validation`): seed 001 and seed 002 section III.A.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

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
// at 0.01, ~50% apart at 0.05). Reported as a table; asserts agreement within 4 stderr + 0.5% at
// dt <= 0.01 only.
TEST(Seed002, InternalAgainstKineticTemperature) {
  std::printf(
      "# seed 002 III.A (ec-verlet, N = 6000): dt, T_K, stderr, T_I, stderr, T_K/T_I - 1\n");
  for (const double dt : {0.005, 0.01, 0.02, 0.05}) {
    auto p = seed002(Integrator::EcVerlet, dt);
    using Mt = Model<3, TemperatureRepulsion, ConstantSigma, InverseSeed002Heat>;
    const Mt m{TemperatureRepulsion{15, 1, 1, 0.5},
               ConstantSigma{3, Weight(1, 0.5)},
               InverseSeed002Heat{0.001, 200, Weight(1, 0.5)},
               1,
               200,
               1};
    Simulation<Mt> sim(m, p);
    const long relax = static_cast<long>(10 / dt), samples = 200,
               every = std::max(1L, static_cast<long>(0.05 / dt));
    for (long s = 0; s < relax; ++s) sim.step();
    std::vector<double> tk, ti;
    const double n = sim.state().size();
    for (long k = 0; k < samples; ++k) {
      for (long s = 0; s < every; ++s) sim.step();
      tk.push_back(2 * sim.kinetic_energy() / (3 * (n - 1)));
      double inv = 0;
      for (const double u : sim.state().u) inv += 200 / u;
      ti.push_back(n / inv);
    }
    const Estimate a = block_average(tk, 20), b = block_average(ti, 20);
    std::printf("%6.3f %8.5f %8.5f %8.5f %8.5f %+8.4f\n", dt, a.mean, a.stderr_, b.mean, b.stderr_,
                a.mean / b.mean - 1);
    if (dt <= 0.01) {
      EXPECT_NEAR(a.mean, b.mean, 4 * std::hypot(a.stderr_, b.stderr_) + 0.005 * b.mean);
    }
  }
}
