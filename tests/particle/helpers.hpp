#pragma once
// Shared set-ups for particle tests: the seed 002 case and the ideal DPDE fluid.

#include "particle/parameters.hpp"
#include "particle/simulation.hpp"

namespace twinflow::particle::testing {

// Seed 002's defaults (section II.C): rho = 3, a_T, sigma = 3, c_v = 200, inverse heat law with
// kappa0 = 0.001 in 002's form, w_D = w_H = (1 - r)^0.5, box 20 x 10 x 10.
inline ParticleParameters seed002(Integrator integrator, double dt) {
  ParticleParameters p;
  p.dim = 3;
  p.box = {{20, 10, 10}};
  p.density = 3;
  p.integrator = integrator;
  p.dt = dt;
  p.conservative = ConservativeForce::TemperatureDependent;
  p.a0 = 15;
  p.friction = Friction::ConstantSigma;
  p.sigma = 3;
  p.dissipation = {1.0, 0.5};
  p.cv = 200;
  p.heat = HeatLaw::Inverse;
  p.heat_coefficient = HeatCoefficient::Seed002;
  p.kappa0 = 0.001;
  p.heat_weight = {1.0, 0.5};
  return p;
}

// The compiled model of seed 002's defaults (a_T, constant sigma, 002's inverse heat law).
using Seed002Model = Model<3, TemperatureRepulsion, ConstantSigma, InverseSeed002Heat>;
inline Seed002Model seed002_model(const ParticleParameters& p) {
  return {TemperatureRepulsion{p.a0, 1, 1, 0.5},
          ConstantSigma{p.sigma, Weight(1, 0.5)},
          InverseSeed002Heat{p.kappa0, p.cv, Weight(1, 0.5)},
          1,
          p.cv,
          1};
}

// Ideal DPDE fluid (no conservative force) with LAMMPS-like weights.
inline ParticleParameters ideal(int dim, Integrator integrator, double cv) {
  ParticleParameters p;
  p.dim = dim;
  p.box = dim == 3 ? std::array<double, 3>{{6, 6, 6}} : std::array<double, 3>{{16, 16, 1}};
  p.density = 3;
  p.integrator = integrator;
  p.dt = 0.005;
  p.conservative = ConservativeForce::None;
  p.friction = Friction::ConstantSigma;
  p.sigma = 3;
  p.gamma = 4.5;
  p.dissipation = {1.0, 2.0};
  p.cv = cv;
  p.heat = HeatLaw::Inverse;
  p.heat_coefficient = HeatCoefficient::Constant;
  p.kappa0 = 5;
  p.heat_weight = {1.0, 2.0};
  return p;
}

} // namespace twinflow::particle::testing
