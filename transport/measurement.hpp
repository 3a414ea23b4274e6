#pragma once
// The transport stage's measurement plan: the fluid of a case at its state point in a periodic
// box (estimates with g = 1 and with the measured g(r); pressure, D, alpha, c_p - c_v measured),
// kappa and eta by the relaxation of sine modes, kappa instead by conduction between the
// scene's own thermal walls. Returns the results; the caller writes them.

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "io/json.hpp"
#include "particle/parameters.hpp"
#include "particle/run.hpp"
#include "scene/scene.hpp"
#include "transport/laws.hpp"
#include "transport/parameters.hpp"

namespace twinflow::transport {

// The bulk fluid of the measurement: the scene's fluid in a periodic box of at least ~4000
// particles, no walls, gravity, slabs or perturbations, started in equilibrium at the state
// point (Transport/Temperature, else the thermal walls' mean, else Scene/Temperature).
particle::ParticleParameters bulk_fluid(const scene::SceneParameters& scene,
                                        const particle::ParticleParameters& scene_fluid,
                                        const TransportParameters& t);

struct TransportMeasurement {
  io::Json results = io::Json::object(); // summary.json's "results"
  std::string coefficients_csv, rdf_csv;
};

// Everything the stage measures at the state point of `bulk` (from bulk_fluid).
// The states (n, T) where eta is also measured: each heated wall's temperature at its density
// on the isobar (Transport/Viscosity along the isobar); none without a heated direction.
std::vector<std::pair<double, double>> isobar_ends(const scene::SceneParameters& scene,
                                                   const TransportParameters& t);

TransportMeasurement measure_transport(const scene::SceneParameters& scene,
                                       const particle::ParticleParameters& scene_fluid,
                                       const particle::ParticleParameters& bulk,
                                       const TransportParameters& t);

// kappa by conduction between the scene's two thermal walls of its heated direction (their
// temperatures, slip and wall model), periodic across, no gravity, ~4000 particles: the walls'
// mean heat flux / |slope| of the central 60% of T_internal (Fourier's law over the scene's own
// temperature span). Throws io::InputError without such walls.
struct WallKappa {
  particle::Estimate kappa;
  io::Json json = io::Json::object();
};
WallKappa kappa_from_walls(const scene::SceneParameters& scene,
                           const particle::ParticleParameters& scene_fluid, double temperature,
                           long steps);

// kappa without walls at the scene's own scale: the bulk fluid in a periodic box twice the
// scene's heated length (the slab between two walls and its mirror image) and the scene's other
// lengths, heat slabs (seed 002 III.B) with a power that spans the scene's thermal walls'
// temperatures for a conductivity `kappa` (a guess), settled for 3 decay times of the slowest
// profile mode and sampled for the time that gives kappa's error ~1.5% (10 decay times of a
// 20 rc slab; at least 3 of its own); heat_capacity_p: per particle, for those times.
particle::ParticleParameters slab_fluid(const scene::SceneParameters& scene,
                                        const particle::ParticleParameters& bulk, double kappa,
                                        double heat_capacity_p);
// kappa = J0 / |dT/dx| over the slab run (the particle run's heat_slabs fit) and in windows
// along its profile, the pair part P measured in the same windows, and the law K (T/T0)^a + P
// (n/n0)^2 (T/T0)^b fitted to the windows with that P and b given (fit_law; a_fallback where the
// span is too small). pair_at_reference: theory's P, kept beside the measured one in the json.
struct SlabKappa {
  particle::Estimate kappa{NAN, NAN};
  std::vector<StatePoint> points;
  particle::Estimate pair{NAN, NAN}; // the law's P, measured (theory's: the json's "pair_part")
  CoefficientLaw law;
  io::Json json = io::Json::object();
};
SlabKappa kappa_from_slabs(const particle::ParticleParameters& slab, double n0, double T0,
                           double pair_at_reference, double pair_exponent, double a_fallback);

} // namespace twinflow::transport
