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
// its error, and the pair conduction's flux (J_conductive: seed 002's kappa_ij term) with its.
struct Profile {
  std::vector<double> x, n, T, T_se, j_pair, j_pair_se;
};
Profile read_profile(const std::string& csv, int direction) {
  const io::CsvTable table = io::parse_csv(csv);
  const char* axes[3] = {"x", "y", "z"};
  const std::string flux = std::string("J_conductive_") + axes[direction];
  const char* file = "slab_profile.csv";
  const std::size_t x = table.column(axes[direction], file), n = table.column("density", file),
                    T = table.column("T_kinetic", file), T_se = table.column("T_kinetic_se", file),
                    j = table.column(flux, file), j_se = table.column(flux + "_se", file);
  Profile p;
  for (const auto& row : table.rows) {
    p.x.push_back(std::stod(row.at(x))), p.n.push_back(std::stod(row.at(n)));
    p.T.push_back(std::stod(row.at(T))), p.T_se.push_back(std::stod(row.at(T_se)));
    p.j_pair.push_back(std::stod(row.at(j))), p.j_pair_se.push_back(std::stod(row.at(j_se)));
  }
  return p;
}

// kappa = J0 / |dT/dx| in windows of width w along both halves between the slabs, a straight
// line through the bins of each (Fourier's law locally: the flux J0 is the same everywhere
// between the slabs in a steady state), and its pair-conduction part, the window's mean
// |J_conductive| / |dT/dx|. The slabs and a margin of 1.5 rc beside each are left out (the slabs'
// own layers).
struct Windows {
  std::vector<StatePoint> total, pair;
};
Windows local_conductivities(const Profile& p, double half, double width, double J0) {
  Windows out;
  const double margin = 1.5, inner = half - width - 2 * margin;
  const int windows = std::max(1, static_cast<int>(inner / 2.5));
  const double w = inner / windows;
  for (int side = 0; side < 2; ++side)
    for (int k = 0; k < windows; ++k) {
      const double lo = side * half + width + margin + k * w, hi = lo + w;
      statistics::LineFit line;
      double n = 0, j = 0, j_var = 0;
      int bins = 0;
      for (std::size_t i = 0; i < p.x.size(); ++i)
        if (p.x[i] > lo && p.x[i] < hi) {
          line.add(p.x[i], p.T[i], p.T_se[i]), n += p.n[i], ++bins;
          j += p.j_pair[i], j_var += p.j_pair_se[i] * p.j_pair_se[i];
        }
      if (bins < 3) continue;
      const double mid = 0.5 * (lo + hi), slope = std::fabs(line.slope());
      StatePoint s;
      s.n = n / bins, s.T = line.intercept() + line.slope() * mid;
      s.value = {J0 / slope, J0 / (slope * slope) * line.slope_stderr()};
      out.total.push_back(s);
      j = std::fabs(j / bins);
      const double j_relative = j > 0 ? std::sqrt(j_var) / bins / j : 0; // none: no heat law
      s.value = {j / slope, j / slope * std::hypot(j_relative, line.slope_stderr() / slope)};
      out.pair.push_back(s);
    }
  return out;
}

// The pair part's coefficient P of kappa's law, P (n/n0)^2 (T/T0)^b, measured: the windows'
// pair parts over their shape, weighted by their errors; the error widened by sqrt(chi^2 / dof)
// when the windows scatter more than their errors say. No pair conduction: P = 0.
particle::Estimate measured_pair_part(const std::vector<StatePoint>& pair, double n0, double T0,
                                      double b) {
  double sum_w = 0, sum = 0;
  std::vector<std::pair<double, double>> values; // P of each window and its error
  for (const StatePoint& s : pair) {
    const double shape = (s.n / n0) * (s.n / n0) * std::pow(s.T / T0, b);
    values.emplace_back(s.value.mean / shape, s.value.stderr_ / shape);
  }
  for (const auto& [P, se] : values)
    if (se > 0) sum_w += 1 / (se * se), sum += P / (se * se);
  if (sum_w == 0) return {0, 0};
  const double mean = sum / sum_w;
  double chi2 = 0;
  for (const auto& [P, se] : values)
    if (se > 0) chi2 += (P - mean) * (P - mean) / (se * se);
  const double dof = std::max<double>(1, static_cast<double>(values.size()) - 1);
  return {mean, std::sqrt(std::max(1.0, chi2 / dof) / sum_w)};
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

namespace {
// The slab run, a line a minute with its ETA (the stage's longest run).
particle::RunOutput run_slabs(const particle::ParticleParameters& slab) {
  particle::RunControl control;
  control.progress = particle::RunControl::Progress::log;
  control.progress_label = "transport: heat slabs: ";
  try {
    return run_on_every_rank(slab, control);
  } catch (const particle::InstabilityError& e) {
    // The power comes from a guess of kappa: a guess well above the fluid's drains the cold slab.
    throw particle::InstabilityError(
        std::string("the heat slabs for kappa went unstable (their power is set from a guess of "
                    "kappa; a fluid that conducts much less drains the cold slab): ") +
        e.what() + "; Transport/Kappa from slabs = false takes kappa from the relaxation runs");
  }
}

// The measurement's record: the run, its windows, the pair part beside theory's, the law.
io::Json slab_json(const particle::ParticleParameters& slab, const io::Json& heat_slabs,
                   const SlabKappa& r, const std::vector<StatePoint>& pair_windows,
                   double pair_theory) {
  io::Json j = io::Json::object();
  j["method"] = "periodic heat slabs (seed 002 III.B) at the scene's scale: kappa = J0 / |dT/dx| "
                "in windows along the profile";
  j["particles"] = slab.particle_count();
  j["box"] = io::Json::array();
  for (int d = 0; d < slab.dim; ++d) j["box"].push_back(slab.box[d]);
  j["steps"] = slab.steps, j["equilibration_steps"] = slab.equilibration_steps;
  j["J0"] = heat_slabs.at("J0");
  j["conductivity"] = r.kappa.mean, j["conductivity_stderr"] = r.kappa.stderr_;
  j["heat_slabs"] = heat_slabs;
  j["profile"] = io::Json::array();
  for (const StatePoint& p : r.points)
    j["profile"].push_back(
        {{"n", p.n}, {"T", p.T}, {"kappa", p.value.mean}, {"kappa_stderr", p.value.stderr_}});
  j["pair_part"] = {{"measured", r.pair.mean},
                    {"measured_stderr", r.pair.stderr_},
                    {"theory", pair_theory},
                    {"windows", io::Json::array()}};
  for (const StatePoint& p : pair_windows)
    j["pair_part"]["windows"].push_back({{"n", p.n},
                                         {"T", p.T},
                                         {"kappa_pair", p.value.mean},
                                         {"kappa_pair_stderr", p.value.stderr_}});
  j["law"] = r.law.json();
  return j;
}
} // namespace

SlabKappa kappa_from_slabs(const particle::ParticleParameters& slab, double n0, double T0,
                           double pair_at_reference, double pair_exponent, double a_fallback) {
  const int heated = slab.heat_slabs.front().direction;
  const double half = 0.5 * slab.box[heated];
  const double width = slab.heat_slabs.front().upper - slab.heat_slabs.front().lower;
  const particle::RunOutput out = run_slabs(slab);
  const io::Json& h = *io::find(out.summary, {"heat_slabs"});
  const double J0 = io::number(h, {"J0"});
  SlabKappa r;
  r.kappa = {io::number(h, {"kappa"}), io::number(h, {"kappa_stderr"})};
  const Windows windows =
      local_conductivities(read_profile(out.slab_profile_csv, heated), half, width, J0);
  r.points = windows.total;
  // The pair part measured, not theory's: the mean-field pair term leaves out the particles'
  // temperature fluctuations (25% low at c_v = 10 in the default fluid; docs/theory.md,
  // "Coefficients against n and T"), and the pair part alone sets how kappa grows with n beyond the
  // slabs' isobar.
  r.pair = measured_pair_part(windows.pair, n0, T0, pair_exponent);
  r.law = fit_law(r.points, n0, T0, r.pair.mean, pair_exponent, a_fallback);
  r.law.P_stderr = r.pair.stderr_;
  // The windows' errors are the bins' block errors, which see less of the profile's slow modes
  // than the whole run's blockings: K's error is at least the slab's kappa error, relatively.
  r.law.K_stderr = std::max(r.law.K_stderr, r.law.K * r.kappa.stderr_ / r.kappa.mean);
  r.json = slab_json(slab, h, r, windows.pair, pair_at_reference);
  return r;
}

} // namespace twinflow::transport
