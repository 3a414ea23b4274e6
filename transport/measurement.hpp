#pragma once
// The transport stage's measurement plan: the fluid of a case at its state point in a periodic
// box (estimates with g = 1 and with the measured g(r); pressure, D, alpha, c_p - c_v measured),
// kappa and eta by the relaxation of sine modes, kappa instead by conduction between the
// scene's own thermal walls. Returns the results; the caller writes them.

#include <string>

#include "io/json.hpp"
#include "particle/parameters.hpp"
#include "particle/run.hpp"
#include "scene/scene.hpp"
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

} // namespace twinflow::transport
