#pragma once
// The plug-ins make_diagnostics chooses from. Each is a class in its own file, seen from outside
// only through the Diagnostic interface: here are the functions that make them, and the fits
// (Fit plug-ins of make_diagnostics) that read the binned fields after the run.

#include "io/json.hpp"
#include "particle/diagnostics/diagnostic.hpp"
#include "particle/fields.hpp"

namespace twinflow::particle {

// thermo.cpp: the thermodynamic state over time: thermo.csv (every sample) and the
// block-averaged temperatures and pressure of the summary (sampled steps).
template <int D> DiagnosticPtr<D> make_thermo(const ParticleParameters& p, const RunFacts& m);

// correlations.cpp: the velocity autocorrelation <v(0).v(t)> and the mean-square displacement of
// up to 1000 tracked particles (ids 0..), averaged over time origins within a window of samples
// (correlations.csv; the transport stage takes the diffusion coefficient from the MSD).
template <int D> DiagnosticPtr<D> make_correlations(const ParticleParameters& p, const RunFacts& m);

// distributions.cpp, over the sampled steps: velocity components and internal energies
// (histograms.csv), and the pair distribution function g(r) (rdf.csv) from the pair pass.
template <int D> DiagnosticPtr<D> make_histograms(const ParticleParameters& p, const RunFacts& m);
template <int D>
DiagnosticPtr<D> make_pair_distribution(const ParticleParameters& p, const RunFacts& m);

// relaxation.cpp, relaxation scenes (seed 004's method): the Fourier amplitudes of an initial
// sine perturbation along x, sampled from the start, and the diffusivities of their exponential
// decay: the heat mode (chi, kappa) and the transverse momentum mode (nu, eta). relaxation.csv
// holds both.
template <int D>
DiagnosticPtr<D> make_relaxation_modes(const ParticleParameters& p, const RunFacts& m, bool heat,
                                       bool shear);

// walls.cpp, walled scenes: each wall's pressure and heat flux over the interval since the last
// sample and its energy in since the start ("walls" of the summary); the density and velocity in
// thin slices along each wall (wall_layers.csv) and each wall's effective position and, for
// no-slip walls, its friction.
template <int D> DiagnosticPtr<D> make_wall_fluxes(const ParticleParameters& p);
template <int D> DiagnosticPtr<D> make_wall_layers(const ParticleParameters& p, const RunFacts& m);

// A diagnostic of binned fields and where its fields are once it has finished (the fits read
// them).
template <int D> struct BinnedDiagnostic {
  // From a diagnostic with result(): the fields it holds after finish.
  template <class Binned>
  explicit BinnedDiagnostic(std::unique_ptr<Binned> binned)
      : fields(binned->result()), diagnostic(std::move(binned)) {}
  const BinnedFields& fields;
  DiagnosticPtr<D> diagnostic;
};

// binned_fields.cpp: the fields on the scene's bins (fields.csv, blocks.csv, and cumulative
// snapshots for fields.h5).
template <int D> BinnedDiagnostic<D> make_fields(const ParticleParameters& p, const RunFacts& m);

// slabs.cpp, heat-slab scenes (seed 002 section III.B): the profile along the slab direction in
// 0.5 rc bins (slab_profile.csv).
template <int D>
BinnedDiagnostic<D> make_slab_profile(const ParticleParameters& p, const RunFacts& m);

// Reverse Poiseuille flow ("poiseuille" of the summary): in each half the steady v_x(y) is a
// parabola with v'' = -n F / eta (n F the force density). A weighted quadratic fit per half over
// the bins away from the two planes where the force flips (the central 80% of each half); eta
// combined over both halves.
io::Json poiseuille_fit(const ParticleParameters& p, const BinnedFields& fields);

// Thermal walls at different temperatures along `direction`, fields binned along it only
// ("wall_profile"): parabolas through T_internal (kappa(T) bends the profile): the slope at the
// centre from the central 60%, and the jump T_wall - T_bulk(wall) at each wall (Kapitza), the
// bulk fitted beyond one cutoff from the walls.
io::Json wall_profile_fit(const ParticleParameters& p, int direction, const BinnedFields& fields);
// The direction such a fit applies to, or -1.
int wall_profile_direction(const ParticleParameters& p);

// A hot and a cold slab ("heat_slabs"): linear fits of T_internal in the central 60% of both
// halves between the slabs, kappa = J0 / |dT/dx| with J0 = power / (2 A), and the flux parts at
// x = 2 and 8.
io::Json slab_kappa_fit(const ParticleParameters& p, const BinnedFields& profile);

} // namespace twinflow::particle
