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

// D and its error from an MSD table (correlations.csv): least squares over the second half.
particle::Estimate diffusion_from_msd(const std::string& correlations_csv, int dim);

} // namespace twinflow::transport
