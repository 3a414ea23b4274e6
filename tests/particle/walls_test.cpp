// Walls and gravity: nothing crosses a wall; the energy balance closes; thermal walls thermalise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "particle/run.hpp"
#include "particle/simulation.hpp"

using namespace twinflow::particle;

namespace {
// A small 2D heated cavity: hot wall x = 0, cold x = L, adiabatic y walls, gravity -y.
ParticleParameters cavity(double dt, bool no_slip) {
  ParticleParameters p;
  p.dim = 2;
  p.box = {{12, 12, 1}};
  p.density = 4;
  p.integrator = Integrator::Shardlow;
  p.dt = dt;
  p.cv = 10;
  p.sigma = 3;
  p.dissipation = {1.0, 2.0};
  p.heat = HeatLaw::Inverse;
  p.heat_coefficient = HeatCoefficient::Constant;
  p.kappa0 = 1;
  p.heat_weight = {1.0, 2.0};
  p.conservative = ConservativeForce::Constant;
  p.a0 = 15;
  p.walls[0] = WallPair{true, {{true, true}}, {{1.5, 0.5}}, no_slip};
  p.walls[1] = WallPair{true, {{false, false}}, {{1, 1}}, no_slip};
  p.gravity = {{0, -0.05, 0}};
  return p;
}
using M = Model<2, ConstantRepulsion, ConstantSigma, InverseConstantHeat>;
M model(const ParticleParameters& p) {
  return {ConstantRepulsion{p.a0, 1, 1},
          ConstantSigma{p.sigma, Weight(1, 2)},
          InverseConstantHeat{p.kappa0, Weight(1, 2)},
          1,
          p.cv,
          1};
}
} // namespace

// Every particle stays in [0, L] after every step, at a large time step; crossings are
// reflected (counted), never lost.
TEST(Walls, NothingCrossesAWall) {
  for (const bool no_slip : {false, true}) {
    auto p = cavity(0.04, no_slip);
    Simulation<M> sim(model(p), p);
    for (int s = 0; s < 1500; ++s) {
      sim.step();
      const auto& st = sim.state();
      for (int d = 0; d < 2; ++d)
        for (const double x : st.x[d]) ASSERT_TRUE(x >= 0 && x <= p.box[d]) << "step " << s;
    }
    std::printf("no-slip %d: %ld reflections in 1500 steps\n", no_slip, sim.wall_crossings());
    EXPECT_GT(sim.wall_crossings(), 0); // the test exercised reflection
  }
}

// With the offset, shardlow conserves energy exactly, so E(t) - E(0) equals the energy that came
// in through the thermal walls, to round-off (relative 1e-12 of E over 2000 steps).
TEST(Walls, EnergyBalanceClosesWithAnExactIntegrator) {
  auto p = cavity(0.01, true);
  p.energy_offset = true;
  Simulation<M> sim(model(p), p);
  const double e0 = sim.total_energy();
  double worst = 0, inflow = 0;
  for (int s = 0; s < 2000; ++s) {
    sim.step();
    inflow = 0;
    for (const double q : sim.wall_energy_in()) inflow += q;
    worst = std::max(worst, std::fabs(sim.total_energy() - e0 - inflow) / e0);
  }
  std::printf("energy through walls %.4f (E0 = %.1f); worst balance residual %.2e\n", inflow, e0,
              worst);
  EXPECT_GT(std::fabs(inflow), 1e-3); // heat did flow
  EXPECT_LE(worst, 1e-12);
}
