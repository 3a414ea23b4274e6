#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "io/csv.hpp"
#include "io/files.hpp"
#include "particle/simulation.hpp"
#include "statistics/line_fit.hpp"
#include "transport/measure.hpp"
#include "transport/measurement.hpp"

namespace twinflow::transport {

namespace {
// The binned profile of slab_profile.csv along the slabs' direction: position, n, T_kinetic and
// its error.
struct Profile {
  std::vector<double> x, n, T, T_se;
};
Profile read_profile(const std::string& csv, int direction) {
  const io::CsvTable table = io::parse_csv(csv);
  const char* axes[3] = {"x", "y", "z"};
  const std::size_t x = table.column(axes[direction], "slab_profile.csv"),
                    n = table.column("density", "slab_profile.csv"),
                    T = table.column("T_kinetic", "slab_profile.csv"),
                    T_se = table.column("T_kinetic_se", "slab_profile.csv");
  Profile p;
  for (const auto& row : table.rows) {
    p.x.push_back(std::stod(row.at(x))), p.n.push_back(std::stod(row.at(n)));
    p.T.push_back(std::stod(row.at(T))), p.T_se.push_back(std::stod(row.at(T_se)));
  }
  return p;
}

// kappa = J0 / |dT/dx| in windows of width w along both halves between the slabs, a straight
// line through the bins of each (Fourier's law locally: the flux J0 is the same everywhere
// between the slabs in a steady state). The slabs and a margin of 1.5 rc beside each are left
// out (the slabs' own layers).
std::vector<StatePoint> local_conductivities(const Profile& p, double half, double width,
                                             double J0) {
  std::vector<StatePoint> points;
  const double margin = 1.5, inner = half - width - 2 * margin;
  const int windows = std::max(1, static_cast<int>(inner / 2.5));
  const double w = inner / windows;
  for (int side = 0; side < 2; ++side)
    for (int k = 0; k < windows; ++k) {
      const double lo = side * half + width + margin + k * w, hi = lo + w;
      statistics::LineFit line;
      double n = 0;
      int bins = 0;
      for (std::size_t i = 0; i < p.x.size(); ++i)
        if (p.x[i] > lo && p.x[i] < hi) line.add(p.x[i], p.T[i], p.T_se[i]), n += p.n[i], ++bins;
      if (bins < 3) continue;
      const double mid = 0.5 * (lo + hi), slope = line.slope();
      StatePoint s;
      s.n = n / bins, s.T = line.intercept() + slope * mid;
      s.value = {J0 / std::fabs(slope), J0 / (slope * slope) * line.slope_stderr()};
      points.push_back(s);
    }
  return points;
}
} // namespace

particle::ParticleParameters slab_fluid(const scene::SceneParameters& scene,
                                        const particle::ParticleParameters& bulk, double kappa,
                                        double heat_capacity_p) {
  const int heated = scene.heated_direction();
  particle::ParticleParameters s = bulk;
  const double half = scene.box[heated]; // the slabs' distance: the walls' mirror image
  double area = 1;
  for (int d = 0; d < s.dim; ++d) {
    s.box[d] = d == heated ? 2 * half : scene.box[d];
    s.bins[d] = d == heated ? static_cast<int>(std::lround(4 * half)) : 1;
    if (d != heated) area *= s.box[d];
  }
  const auto& walls = scene.boundary[heated];
  const double span = std::fabs(walls.temperature[0] - walls.temperature[1]);
  // Power = 2 J0 A (the heat leaves the hot slab both ways), J0 = kappa span / half
  const double power = 2 * area * kappa * span / half;
  // Slabs of at least 0.5 rc holding at least ~50 particles each, so that no particle loses a
  // large share of its energy to the cold slab in a step (a small box's would run dry).
  const double width = std::min(0.25 * half, std::max(0.5, 50 / (s.density * area)));
  s.heat_slabs = {{heated, half, half + width, power}, {heated, 0, width, -power}};
  // Steady after 3 decay times of the slowest mode, sin(pi x / half): half^2 / (pi^2 chi). The
  // error of kappa goes as 1 / sqrt(N t / decay) ~ 1 / sqrt(t): the sampled time that gave the
  // default cavity's slab (half 20) 1.3-1.5% gives it at any size; at least 3 decay times so that
  // the merged blocks outlast the slowest mode.
  const double chi = kappa / (s.density * heat_capacity_p);
  const double decay = half * half / (M_PI * M_PI * chi);
  const double sampled = std::max(3 * decay, 10 * 20.0 * 20.0 / (M_PI * M_PI * chi));
  s.equilibration_steps = static_cast<long>(std::ceil(3 * decay / s.dt));
  s.steps = static_cast<long>(std::ceil(sampled / s.dt));
  s.sample_interval = std::max(1L, s.steps / 2000);
  return s;
}

SlabKappa kappa_from_slabs(const particle::ParticleParameters& slab, double n0, double T0,
                           double pair_at_reference, double pair_exponent, double a_fallback) {
  const int heated = slab.heat_slabs.front().direction;
  const double half = 0.5 * slab.box[heated];
  const double width = slab.heat_slabs.front().upper - slab.heat_slabs.front().lower;
  // The longest run of the stage: a line a minute with its ETA.
  particle::RunControl control;
  control.progress = particle::RunControl::Progress::log;
  control.progress_label = "transport: heat slabs: ";
  particle::RunOutput out;
  try {
    out = run_on_every_rank(slab, control);
  } catch (const particle::InstabilityError& e) {
    // The power comes from a guess of kappa: a guess well above the fluid's drains the cold slab.
    throw particle::InstabilityError(
        std::string("the heat slabs for kappa went unstable (their power is set from a guess of "
                    "kappa; a fluid that conducts much less drains the cold slab): ") +
        e.what() + "; Transport/Kappa from slabs = false takes kappa from the relaxation runs");
  }
  const io::Json& h = *io::find(out.summary, {"heat_slabs"});
  const double J0 = io::number(h, {"J0"});
  SlabKappa r;
  r.kappa = {io::number(h, {"kappa"}), io::number(h, {"kappa_stderr"})};
  r.points = local_conductivities(read_profile(out.slab_profile_csv, heated), half, width, J0);
  r.law = fit_law(r.points, n0, T0, pair_at_reference, pair_exponent, a_fallback);
  // The windows' errors are the bins' block errors, which see less of the profile's slow modes
  // than the whole run's blockings: K's error is at least the slab's kappa error, relatively.
  r.law.K_stderr = std::max(r.law.K_stderr, r.law.K * r.kappa.stderr_ / r.kappa.mean);
  io::Json& j = r.json;
  j["method"] = "periodic heat slabs (seed 002 III.B) at the scene's scale: kappa = J0 / |dT/dx| "
                "in windows along the profile";
  j["particles"] = slab.particle_count();
  j["box"] = io::Json::array();
  for (int d = 0; d < slab.dim; ++d) j["box"].push_back(slab.box[d]);
  j["steps"] = slab.steps, j["equilibration_steps"] = slab.equilibration_steps;
  j["J0"] = J0;
  j["conductivity"] = r.kappa.mean, j["conductivity_stderr"] = r.kappa.stderr_;
  j["heat_slabs"] = h;
  j["profile"] = io::Json::array();
  for (const StatePoint& p : r.points)
    j["profile"].push_back(
        {{"n", p.n}, {"T", p.T}, {"kappa", p.value.mean}, {"kappa_stderr", p.value.stderr_}});
  j["law"] = r.law.json();
  return r;
}

} // namespace twinflow::transport
