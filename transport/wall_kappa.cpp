#include <chrono>
#include <cmath>
#include <cstdio>

#include "io/files.hpp"
#include "particle/run.hpp"
#include "particle/wall_summary.hpp"
#include "transport/measure.hpp"
#include "transport/measurement.hpp"

namespace twinflow::transport {

namespace {

// The scene's walls and fluid in a slab across the heated direction: no gravity, no slabs, the
// other directions periodic and just wide enough for ~4000 particles.
particle::ParticleParameters wall_slab(const particle::ParticleParameters& scene_fluid, int heated,
                                       double temperature, long steps) {
  particle::ParticleParameters w = scene_fluid;
  w.temperature = temperature;
  w.initial_velocities = particle::InitialVelocities::Maxwell;
  w.initial_internal_energy = particle::InitialInternalEnergy::Equilibrium;
  w.temperature_perturbation = 0, w.shear_perturbation = 0, w.poiseuille_force = 0;
  w.gravity = {{0, 0, 0}};
  w.heat_slabs.clear();
  const double length = w.box[heated];
  const double across = std::max(
      3 * w.largest_cutoff(), std::pow(4000 / (w.density * length), 1.0 / std::max(1, w.dim - 1)));
  for (int d = 0; d < w.dim; ++d) {
    w.bins[d] = 1;
    if (d == heated) continue;
    w.walls[d].present = false;
    w.box[d] = across;
  }
  w.bins[heated] = std::max(10, static_cast<int>(std::lround(2 * length / w.largest_cutoff())));
  w.steps = steps;
  w.equilibration_steps = steps / 5;
  w.seed = scene_fluid.seed + 7919;
  return w;
}

// Fourier's law from the run: the heat flow between the walls over the profile's slope.
WallKappa fourier_kappa(const particle::ParticleParameters& w, const io::Json& summary,
                        int heated) {
  const auto lower = scene::wall_name(heated, 0), upper = scene::wall_name(heated, 1);
  const double q_lo = io::number(summary, {"walls", lower.c_str(), "heat_flux_in"});
  const double q_up = io::number(summary, {"walls", upper.c_str(), "heat_flux_in"});
  const statistics::Estimate pair = particle::wall_pair_heat_flux(summary, heated);
  const double se_q = pair.stderr_;
  const double q = pair.mean; // from the lower wall to the upper one
  // Steady: both walls carry the same flow. Else the profile is still forming.
  const double imbalance = (q_lo + q_up) / (2 * se_q);
  if (std::fabs(imbalance) > 3)
    std::printf("transport: kappa from the walls: the walls' heat flows differ by %.1f standard "
                "errors (%.4g in, %.4g out): not yet steady; raise Transport/Wall steps\n",
                std::fabs(imbalance), q_lo, -q_up);
  const double slope = io::number(summary, {"wall_profile", "slope"}),
               se_slope = io::number(summary, {"wall_profile", "slope_stderr"});
  WallKappa r;
  r.kappa.mean = -q / slope; // Fourier: q = -kappa dT/dx
  r.kappa.stderr_ = std::fabs(r.kappa.mean) * std::hypot(se_q / q, se_slope / slope);
  r.json["method"] = "conduction between the scene's thermal walls (Fourier's law)";
  r.json["particles"] = w.particle_count();
  r.json["box"] = io::Json::array();
  for (int d = 0; d < w.dim; ++d) r.json["box"].push_back(w.box[d]);
  r.json["steps"] = w.steps;
  r.json["heat_flux"] = q, r.json["heat_flux_stderr"] = se_q;
  r.json["heat_flux_walls"] = io::Json::array();
  r.json["heat_flux_walls"].push_back(q_lo), r.json["heat_flux_walls"].push_back(-q_up);
  r.json["wall_imbalance_over_stderr"] = imbalance;
  r.json["slope"] = slope, r.json["slope_stderr"] = se_slope;
  r.json["conductivity"] = r.kappa.mean, r.json["conductivity_stderr"] = r.kappa.stderr_;
  r.json["T_internal"] = io::number(summary, {"T_internal"});
  if (const io::Json* profile = io::find(summary, {"wall_profile"}))
    r.json["wall_profile"] = *profile;
  return r;
}

} // namespace

WallKappa kappa_from_walls(const scene::SceneParameters& scene,
                           const particle::ParticleParameters& scene_fluid, double temperature,
                           long steps) {
  const int heated = scene.heated_direction();
  if (heated < 0)
    throw io::InputError("Transport/Kappa from walls = true needs two thermal walls at different "
                         "temperatures in one direction of the scene");
  const particle::ParticleParameters w = wall_slab(scene_fluid, heated, temperature, steps);
  const auto start = std::chrono::steady_clock::now();
  std::printf("transport: kappa from the walls: %ld particles, %ld + %ld steps\n",
              w.particle_count(), w.equilibration_steps, w.steps);
  std::fflush(stdout);
  particle::RunControl control;
  control.progress = particle::RunControl::progress_for_stderr();
  const particle::RunOutput out = run_on_every_rank(w, control);
  WallKappa r = fourier_kappa(w, out.summary, heated);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.json["seconds"] = seconds;
  std::printf("transport: kappa from the walls = %.4g +- %.2g (flux %.4g +- %.2g, slope %.4g +- "
              "%.2g); %.0f s\n",
              r.kappa.mean, r.kappa.stderr_, r.json["heat_flux"].get<double>(),
              r.json["heat_flux_stderr"].get<double>(), r.json["slope"].get<double>(),
              r.json["slope_stderr"].get<double>(), seconds);
  return r;
}

} // namespace twinflow::transport
