#pragma once
// Coefficients measured by short periodic particle runs at the case's state point.

#include "io/json.hpp"
#include "particle/parameters.hpp"
#include "particle/run.hpp"
#include "transport/estimates.hpp"

namespace twinflow::transport {

struct Measured {
  particle::Estimate pressure, temperature;
  particle::Estimate diffusion;      // from the MSD slope, 2 d D
  particle::Estimate expansion;      // alpha = (dp/dT)_rho / (rho (dp/drho)_T)
  particle::Estimate dp_dt, dp_drho; // equation-of-state derivatives
  std::string rdf_csv;
  io::Json json() const;
};

// Periodic box at the state point of `p` (its density and temperature); `steps` sampled steps per
// run. Five runs: the state point, T (1 +- h), rho (1 +- h).
Measured measure(const particle::ParticleParameters& p, long steps, double h = 0.05);

// kappa by seed 004's relaxation method: a sine heat mode along x in a periodic box twice as long
// as `p`'s, run for about three decay times of the estimate; kappa = rho c_p chi with c_p per
// particle given (the ideal fluid's, or from the measured equation of state).
particle::Estimate measure_conductivity_relaxation(particle::ParticleParameters p,
                                                   const Estimates& estimate, double cp);
// eta by reverse Poiseuille flow: opposite body forces in the halves of a periodic box twice as
// tall as `p`'s, sized for a peak speed ~0.1 of the thermal speed, run for five decay times of
// the slowest start-up mode (half^2 / (pi^2 nu)) to steady state, and as long again sampled.
particle::Estimate measure_viscosity_poiseuille(particle::ParticleParameters p,
                                                const Estimates& estimate);

// D and its error from an MSD table (correlations.csv): least squares over the second half.
particle::Estimate diffusion_from_msd(const std::string& correlations_csv, int dim);

} // namespace twinflow::transport
