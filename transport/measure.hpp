#pragma once
// Coefficients measured by short periodic particle runs at the case's state point.

#include <Eigen/Core>

#include <cmath>

#include <functional>
#include <vector>

#include "io/json.hpp"
#include "particle/parameters.hpp"
#include "particle/run.hpp"
#include "transport/estimates.hpp"

namespace twinflow::transport {

// particle::run_particles, with rank 0's results (summary and tables, not the field snapshots)
// on every rank under mpirun: each run is split over the ranks and only rank 0 assembles its
// results, but every rank must take the same next steps (a relaxation run's length comes from
// the g(r) measured before it). On one process: run_particles.
particle::RunOutput run_on_every_rank(const particle::ParticleParameters& p,
                                      const particle::RunControl& control = {});

// The excess pressure p - n k T = n^2 (b0 + b1 k T + b2 (n - n_ref)) fitted to bulk runs at a
// few densities and temperatures around n_ref (weighted least squares in y = (p - n T) / n^2,
// y's error p's over n^2: an upper bound, as p - n T_kinetic sheds the kinetic part's
// fluctuation, so chi^2 / dof comes out below 1): the compressible twin's equation of state
// (continuum/compressible_eos.hpp). A soft repulsion's B = y grows with n (3D, a0 = 25, n = 3:
// ~4% over +-5% in n, against errors of 0.05%), barely with T. Errors scaled by
// sqrt(chi^2 / dof) when that exceeds 1 (the points scatter more than stated).
struct PressurePoint {
  double density = 0, temperature = 0; // n, and the run's measured kinetic T
  particle::Estimate pressure;
};
struct ExcessPressureFit {
  double reference_density = 0;
  double b0 = 0, b1 = 0, b2 = 0, b0_stderr = 0, b1_stderr = 0, b2_stderr = 0;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero(); // of (b0, b1, b2)
  double chi2_per_dof = 0;
  int dof = 0;
  std::vector<PressurePoint> points;
  io::Json json() const;
};
ExcessPressureFit fit_excess_pressure(const std::vector<PressurePoint>& points,
                                      double reference_density);

struct Measured {
  particle::Estimate pressure, temperature;
  particle::Estimate diffusion; // from the MSD slope, 2 d D, over independent repeats
  particle::Estimate diffusion_exponent{NAN, NAN}; // a_D in D ~ T^a_D (diffusion_spread > 0)
  int diffusion_dof = 0;                           // its error's degrees of freedom (repeats - 1)
  particle::Estimate expansion;                    // alpha = (dp/dT)_rho / (rho (dp/drho)_T)
  particle::Estimate dp_dt, dp_drho;               // equation-of-state derivatives
  particle::Estimate cp_minus_cv;                  // per particle, k = 1: 1 for the ideal gas
  ExcessPressureFit excess_pressure;               // over the five state points' runs
  std::string rdf_csv;
  std::vector<particle::Estimate> diffusion_repeats; // each run's D and its groups' error
  io::Json json() const;
};

// Periodic box at the state point of `p` (its density and temperature); `steps` sampled steps per
// run. Five runs: the state point, T (1 +- h), rho (1 +- h) (the pressure's derivatives and its
// excess fit); D from `diffusion_repeats` independent runs at the state point (the first of them
// the state point's run); with diffusion_spread s > 0 also D at T (1 +- s), D's power of T. The
// runs are spread over the cores (jobs.hpp).
Measured measure(const particle::ParticleParameters& p, long steps, int diffusion_repeats,
                 double h = 0.05, double diffusion_spread = 0);

// A coefficient measured by independent repeats (different seeds): the mean, and the standard
// error of that mean by one of two rules.
struct Repeated {
  particle::Estimate value;
  std::vector<particle::Estimate> repeats;  // each run's fit
  double spread_stderr = 0, fit_stderr = 0; // sd / sqrt(M), and the fits' rms error / sqrt(M)
  int failed = 0;                           // repeats whose fit failed (left out)
  // Degrees of freedom of value.stderr_: M - 1 when it is the spread's; 0 when it is (or may be)
  // the fits' own errors, whose degrees of freedom are not known here.
  int dof = 0;
  io::Json json() const;
};

enum class RepeatError {
  // The larger of the spread's and the fits' (a spread of few repeats can come out small by
  // chance; right when the fits' errors are themselves honest: the relaxation runs).
  LargerOfSpreadAndFits,
  // The spread's alone, M - 1 degrees of freedom (the fits' errors miss what the repeats see;
  // one run: its fit's error, dof 0). For D: the groups' error understates the scatter of runs
  // by 1.3x (docs/notebook/2026-11-25-seed-errors.md), so a floor from it only biases.
  Spread,
};

Repeated summarise_repeats(const std::vector<particle::Estimate>& runs,
                           RepeatError rule = RepeatError::LargerOfSpreadAndFits);

// D by `repeats` independent runs at p's state point (repeat r's seed derived_seed(p.seed,
// DiffusionRepeat, r), repeat 0's p.seed itself), each `steps` sampled steps after steps / 2 to
// settle; `first_correlations`, when given, is repeat 0's correlations.csv (a run already made
// with p.seed). D the mean, its error the repeats' spread (RepeatError::Spread, repeats - 1
// degrees of freedom). Why repeats: one run's MSD window is one sample of the box's slow
// collective flows, which move all tracked particles together (in 2D they are the long-time
// tail: D(t) grows with the window), so its particle groups cannot see them.
Repeated measure_diffusion(const particle::ParticleParameters& p, long steps, int repeats,
                           const std::string& first_correlations = "");

struct RelaxationCoefficients {
  Repeated conductivity, viscosity;
  Repeated temperature;          // the runs' mean internal temperatures 1/<1/theta>
  long particles = 0, steps = 0; // of each run
};

// kappa and eta by seed 004's relaxation method: a sine heat mode and a sine transverse
// momentum mode along x in a periodic box twice as long as `p`'s, run for about three decay
// times of the slower mode's estimate; kappa = rho c_p chi with c_p per particle given (the ideal
// fluid's, or from the measured equation of state), eta = rho m nu. `repeats` runs with
// different seeds, spread over the cores (jobs.hpp); `report` is told after each ends: how many
// have, the summary of those, and which repeat ended.
RelaxationCoefficients measure_relaxation(
    particle::ParticleParameters p, const Estimates& estimate, double cp, int repeats,
    const std::function<void(int done, const RelaxationCoefficients&, int repeat)>& report = {});

// coefficient(T) = value (T / T_ref)^exponent through measured points, weighted least squares in
// logs; errors from the points' errors (chi2_per_dof says whether they describe the scatter).
struct PowerLawFit {
  double value = 0, value_stderr = 0, exponent = 0, exponent_stderr = 0, chi2_per_dof = 0;
};
PowerLawFit fit_power_law(const std::vector<double>& temperatures,
                          const std::vector<particle::Estimate>& values, double reference);

// D from an MSD table (correlations.csv): least squares over the second half of the window; its
// error from the same fit to each group of tracked particles (msd_group_g columns).
particle::Estimate diffusion_from_msd(const std::string& correlations_csv, int dim);

} // namespace twinflow::transport
