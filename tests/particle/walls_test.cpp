// Walls and gravity: nothing crosses a wall; the energy balance closes; thermal walls thermalise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "particle/run.hpp"
#include "particle/simulation.hpp"
#include "particle/wall_summary.hpp"
#include "particle/wall_weights.hpp"

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
struct WallCase {
  Integrator integrator;
  WallModel model;
  bool diffuse;
  const char* name;
};
const WallCase kWallCases[] = {
    {Integrator::Shardlow, WallModel::HalfSpace, true, "shardlow, half-space, diffuse"},
    {Integrator::Shardlow, WallModel::HalfSpace, false, "shardlow, half-space, bounce-back"},
    {Integrator::Shardlow, WallModel::Seed000, false, "shardlow, seed000"},
    {Integrator::EcVerlet, WallModel::HalfSpace, true, "ec-verlet, half-space, diffuse"},
    {Integrator::EcVerlet, WallModel::Seed000, false, "ec-verlet, seed000"},
    {Integrator::Euler, WallModel::HalfSpace, true, "euler, half-space, diffuse"},
    {Integrator::Euler, WallModel::Seed000, false, "euler, seed000"},
};
// Steps the simulation; returns the largest |E(t) - E(0) - energy in through the walls| / E(0).
double run_with_balance(Simulation<M>& sim, int steps) {
  const double e0 = sim.total_energy();
  double worst = 0;
  for (int s = 0; s < steps; ++s) {
    sim.step();
    double inflow = 0;
    for (const double q : sim.wall_energy_in()) inflow += q;
    worst = std::max(worst, std::fabs(sim.total_energy() - e0 - inflow) / e0);
  }
  return worst;
}
ParticleParameters with_walls(ParticleParameters p, const WallCase& c) {
  p.integrator = c.integrator;
  if (c.integrator != Integrator::Shardlow) { // explicit friction and noise: a particle's kick
    p.dt /= 4;                                // is paid from its own internal energy (the
    p.a0 = 3, p.sigma = 1.5, p.cv = 50;       // offset), so a milder, more capacious fluid
  }
  p.wall_diffuse = c.diffuse;
  for (auto& w : p.walls) w.model = {{c.model, c.model}};
  return p;
}
} // namespace

// Every particle stays in [0, L] after every step, at a large time step; crossings are
// reflected (counted), never lost; for every integrator and wall model.
TEST(Walls, NothingCrossesAWall) {
  for (const WallCase& c : kWallCases)
    for (const bool no_slip : {false, true}) {
      auto p = with_walls(cavity(0.04, no_slip), c);
      Simulation<M> sim(model(p), p);
      try {
        for (int s = 0; s < 500; ++s) {
          sim.step();
          const auto& st = sim.state();
          for (int d = 0; d < 2; ++d)
            for (const double x : st.x[d])
              ASSERT_TRUE(x >= 0 && x <= p.box[d]) << c.name << ", step " << s;
        }
      } catch (const std::exception& e) {
        ADD_FAILURE() << c.name << ": " << e.what();
        continue;
      }
      std::printf("%s, no-slip %d: %ld reflections in 500 steps\n", c.name, no_slip,
                  sim.wall_crossings());
      EXPECT_GT(sim.wall_crossings(), 0) << c.name; // the test exercised reflection
    }
}

// With the offset every integrator conserves energy exactly (shardlow and ec-verlet: 002
// Appendix A; euler: each particle's kinetic change taken from its internal energy), so
// E(t) - E(0) equals the energy that came in through the thermal walls, to round-off (relative
// 1e-12 of E over 1000 steps), for every wall model.
TEST(Walls, EnergyBalanceClosesForEveryIntegrator) {
  for (const WallCase& c : kWallCases) {
    auto p = with_walls(cavity(0.01, true), c);
    p.energy_offset = true;
    Simulation<M> sim(model(p), p);
    const double e0 = sim.total_energy();
    const double worst = run_with_balance(sim, 1000);
    double inflow = 0;
    for (const double q : sim.wall_energy_in()) inflow += q;
    std::printf("%s: energy through walls %.4f (E0 = %.1f); worst balance residual %.2e\n", c.name,
                inflow, e0, worst);
    EXPECT_GT(std::fabs(inflow), 1e-3) << c.name; // heat did flow
    EXPECT_LE(worst, 1e-12) << c.name;
  }
}

// Walls/Heat conduction is per wall: the hot wall's factor alone, 0 -> 10, raises the heat that
// enters through it (bounce-back walls: no re-emission, so the pair conduction is the wall's
// main heat path), leaves the cold wall's coupling alone, and the energy balance still closes.
TEST(Walls, ConductionFactorActsOnItsOwnWall) {
  auto inflows = [](std::array<double, 2> factor, double& residual) {
    auto p = with_walls(cavity(0.01, true), kWallCases[1]);
    p.energy_offset = true;
    p.kappa0 = 5;
    p.walls[0].conduction = factor;
    Simulation<M> sim(model(p), p);
    residual = run_with_balance(sim, 2000);
    return std::array<double, 2>{sim.wall_energy_in()[0], sim.wall_energy_in()[1]};
  };
  double r0, r10;
  const auto off = inflows({{0, 1}}, r0), ten = inflows({{10, 1}}, r10);
  std::printf("heat in through the hot / cold wall over 2000 steps: factors 0, 1: %.2f / %.2f; "
              "10, 1: %.2f / %.2f; balance residuals %.1e, %.1e\n",
              off[0], off[1], ten[0], ten[1], r0, r10);
  EXPECT_GT(ten[0], 2 * off[0]);
  EXPECT_LT(std::fabs(ten[1] - off[1]), 0.2 * std::fabs(off[1])); // measured: 3%
  EXPECT_LE(r10, 1e-12);
}

// The heat flow across a pair of thermal walls: the mean of the two walls' flows, its error
// from the blocks of the one series across the pair (wall_pairs); a summary without it (runs
// from before it) gives the same mean and the two walls' errors in quadrature.
TEST(Walls, HeatFlowAcrossAPairTakesItsErrorFromOneSeries) {
  ParticleParameters p = with_walls(cavity(0.01, true), kWallCases[0]);
  p.steps = 2000, p.sample_interval = 10, p.blocks = 8;
  const RunOutput out = run_particles(p);
  const auto& r = out.summary;
  const double lo = r.at("walls").at("x_lower").at("heat_flux_in").get<double>();
  const double up = r.at("walls").at("x_upper").at("heat_flux_in").get<double>();
  ASSERT_TRUE(r.at("wall_pairs").contains("x"));
  EXPECT_FALSE(r.at("wall_pairs").contains("y")); // adiabatic: nothing to carry
  const twinflow::statistics::Estimate across = wall_pair_heat_flux(r, 0);
  EXPECT_NEAR(across.mean, 0.5 * (lo - up), 1e-12 * std::fabs(lo - up));
  EXPECT_GT(across.stderr_, 0);
  const double correlation = r.at("wall_pairs").at("x").at("wall_block_correlation");
  EXPECT_LE(std::fabs(correlation), 1 + 1e-12);

  auto older = r;
  older.erase("wall_pairs");
  const twinflow::statistics::Estimate quadrature = wall_pair_heat_flux(older, 0);
  EXPECT_NEAR(quadrature.mean, across.mean, 1e-12 * std::fabs(lo - up));
  EXPECT_DOUBLE_EQ(quadrature.stderr_, 0.5 * std::hypot(wall_heat_flux_stderr(r, "x_lower"),
                                                        wall_heat_flux_stderr(r, "x_upper")));
  std::printf("heat flow across %.4g: +- %.3g from one series, +- %.3g in quadrature; walls' "
              "block correlation %.2f\n",
              across.mean, across.stderr_, quadrature.stderr_, correlation);
}

// The kinetic-slip twin's wall friction per area (references.md, "Kinetic slip at a particle wall")
// takes the half-space's tangential friction weight integrated over the distance from the
// plane in closed form; against the particle wall's own table (tanh-sinh integrals over the
// half-space at each h), integrated over h by Simpson's rule.
TEST(Walls, TangentFrictionMomentMatchesTheHalfSpaceTables) {
  for (const int dim : {2, 3})
    for (const double exponent : {0.5, 1.0, 2.0}) {
      ParticleParameters p;
      p.dim = dim;
      p.density = 3;
      p.dissipation = {1.3, exponent};
      const HalfSpaceWall wall = make_half_space_wall(p);
      const int intervals = 4000; // even
      const double step = p.dissipation.cutoff / intervals;
      double sum = 0;
      for (int k = 0; k <= intervals; ++k) {
        const double weight = (k == 0 || k == intervals) ? 1 : (k % 2 ? 4 : 2);
        sum += weight * wall.friction_tangent(k * step);
      }
      const double tables = sum * step / 3 / p.density;
      const double closed = tangent_friction_moment(dim, p.dissipation.cutoff, exponent);
      std::printf("I_%d, s = %.1f: closed form %.8f, tables %.8f\n", dim, exponent, closed, tables);
      EXPECT_NEAR(tables, closed, 1e-5 * closed) << "dim " << dim << ", s = " << exponent;
    }
  EXPECT_NEAR(tangent_friction_moment(2, 1, 2), 1.0 / 45, 1e-15);   // (2/3) B(3, 3)
  EXPECT_NEAR(tangent_friction_moment(3, 1, 2), M_PI / 240, 1e-15); // (pi/4) B(4, 3)
}
