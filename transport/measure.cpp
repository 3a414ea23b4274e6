#include "transport/measure.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include <Eigen/Dense>

#include "particle/decomposition.hpp"
#include "particle/seeds.hpp"
#include "statistics/blocking.hpp"
#include "statistics/line_fit.hpp"
#include "transport/jobs.hpp"

namespace twinflow::transport {

namespace {
void share_from_rank_zero(std::string& text) {
  unsigned long size = text.size();
  MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG, 0, MPI_COMM_WORLD);
  text.resize(size);
  MPI_Bcast(text.data(), static_cast<int>(size), MPI_CHAR, 0, MPI_COMM_WORLD);
}
} // namespace

particle::RunOutput run_on_every_rank(const particle::ParticleParameters& p,
                                      const particle::RunControl& control) {
  particle::RunOutput out = particle::run_particles(p, control);
  if (particle::Slabs::world_size() == 1) return out;
  // Rank 0 keeps its own values (a NaN is null in the text: number() reads both as NaN).
  std::string summary = out.summary.dump();
  share_from_rank_zero(summary);
  if (particle::Slabs::world_rank() != 0) out.summary = io::Json::parse(summary);
  for (std::string* table :
       {&out.thermo_csv, &out.histograms_csv, &out.rdf_csv, &out.correlations_csv, &out.fields_csv,
        &out.blocks_csv, &out.wall_layers_csv, &out.slab_profile_csv, &out.relaxation_csv})
    share_from_rank_zero(*table);
  return out;
}

using particle::Estimate;

particle::Estimate diffusion_from_msd(const std::string& csv, int dim) {
  std::vector<double> t;
  std::vector<std::vector<double>> msd; // [column][row]: the whole MSD, then each group's
  std::istringstream in(csv);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || !std::isdigit(static_cast<unsigned char>(line[0]))) continue;
    std::istringstream row(line);
    std::string field;
    std::vector<double> values;
    while (std::getline(row, field, ',')) values.push_back(std::stod(field));
    if (values.size() < 3) continue;
    if (msd.empty()) msd.resize(values.size() - 2);
    t.push_back(values[0]);
    for (std::size_t c = 0; c < msd.size() && c + 2 < values.size(); ++c)
      msd[c].push_back(values[c + 2]);
  }
  Estimate e;
  const std::size_t n = t.size(), first = n / 2;
  if (n - first < 6) return e;
  // Least-squares slope of msd(t) over [from, to)
  auto fit = [&](const std::vector<double>& m, std::size_t from, std::size_t to) {
    double st = 0, sm = 0, stt = 0, stm = 0;
    const double k = static_cast<double>(to - from);
    for (std::size_t i = from; i < to; ++i)
      st += t[i], sm += m[i], stt += t[i] * t[i], stm += t[i] * m[i];
    return (k * stm - st * sm) / (k * stt - st * st);
  };
  e.mean = fit(msd[0], first, n) / (2 * dim); // Einstein relation: MSD = 2 d D t
  // The error from the groups of tracked particles: each group's D by the same fit, and the
  // standard error of their mean. The groups share no particle and each sees all the run's
  // time origins, so their scatter holds the few independent windows a run has (the MSD points
  // of one run are strongly correlated, and a window is one sample in time).
  std::vector<double> per_group;
  for (std::size_t c = 1; c < msd.size(); ++c)
    if (msd[c].size() == n) per_group.push_back(fit(msd[c], first, n) / (2 * dim));
  if (per_group.size() >= 2) {
    e.stderr_ = statistics::block_estimate(per_group).stderr_;
    return e;
  }
  // A table without groups: the difference between the slopes of the window's two halves (too
  // small, by up to 20x over seeds: docs/notebook/2026-11-25-seed-errors.md).
  const std::size_t mid = (first + n) / 2;
  e.stderr_ = std::fabs(fit(msd[0], first, mid) - fit(msd[0], mid, n)) / (2 * dim) / 2;
  return e;
}

namespace {
struct Point {
  Estimate p, t;
  std::string rdf, corr;
};
Point run_at(particle::ParticleParameters p, double density, double temperature, long steps) {
  p.density = density;
  p.temperature = temperature;
  p.steps = steps;
  p.equilibration_steps = steps / 2;
  const auto out = run_on_every_rank(p);
  const auto& r = out.summary;
  Point pt;
  pt.p = {io::number(r, {"pressure"}), io::number(r, {"pressure_stderr"})};
  pt.t = {io::number(r, {"T_kinetic"}), io::number(r, {"T_kinetic_stderr"})};
  pt.rdf = out.rdf_csv;
  pt.corr = out.correlations_csv;
  return pt;
}
} // namespace

Repeated measure_diffusion(const particle::ParticleParameters& p, long steps, int repeats,
                           const std::string& first_correlations) {
  std::vector<Estimate> d(static_cast<std::size_t>(repeats));
  std::vector<Job> jobs;
  for (int r = 0; r < repeats; ++r) {
    if (r == 0 && !first_correlations.empty()) {
      d[0] = diffusion_from_msd(first_correlations, p.dim);
      continue;
    }
    jobs.push_back(
        {1, [&, r] {
           particle::ParticleParameters q = p;
           q.seed = particle::derived_seed(p.seed, particle::SeedPurpose::DiffusionRepeat,
                                           static_cast<std::uint64_t>(r));
           d[r] = diffusion_from_msd(run_at(q, p.density, p.temperature, steps).corr, p.dim);
         }});
  }
  run_jobs(std::move(jobs));
  return summarise_repeats(d, RepeatError::Spread);
}

namespace {
// The bulk runs of `measure`, each independent: the state point c, T (1 +- h), rho (1 +- h), D's
// repeats and D at T (1 +- diffusion_spread), spread over the cores (jobs.hpp).
struct BulkRuns {
  Point c, tp, tm, rp, rm, dp, dm;
  std::vector<Estimate> d; // D's repeats; [0] is the state point's
};

BulkRuns run_bulk(const particle::ParticleParameters& p, long steps, int diffusion_repeats,
                  double h, double diffusion_spread) {
  const double rho = p.density, T = p.temperature;
  BulkRuns b;
  b.d.resize(static_cast<std::size_t>(std::max(diffusion_repeats, 1)));
  std::vector<Job> jobs{{1, [&] { b.c = run_at(p, rho, T, steps); }},
                        {1, [&] { b.tp = run_at(p, rho, T * (1 + h), steps); }},
                        {1, [&] { b.tm = run_at(p, rho, T * (1 - h), steps); }},
                        {1, [&] { b.rp = run_at(p, rho * (1 + h), T, steps); }},
                        {1, [&] { b.rm = run_at(p, rho * (1 - h), T, steps); }}};
  for (int r = 1; r < diffusion_repeats; ++r)
    jobs.push_back({1, [&, r] {
                      particle::ParticleParameters q = p;
                      q.seed =
                          particle::derived_seed(p.seed, particle::SeedPurpose::DiffusionRepeat,
                                                 static_cast<std::uint64_t>(r));
                      b.d[r] = diffusion_from_msd(run_at(q, rho, T, steps).corr, p.dim);
                    }});
  if (diffusion_spread > 0) {
    jobs.push_back({1, [&] { b.dp = run_at(p, rho, T * (1 + diffusion_spread), steps); }});
    jobs.push_back({1, [&] { b.dm = run_at(p, rho, T * (1 - diffusion_spread), steps); }});
  }
  run_jobs(std::move(jobs));
  return b;
}

// D's error from independent runs: within one run the groups of tracked particles share the box's
// collective flows (in 2D runs scattered 1.3x wider over seeds than the groups said,
// docs/notebook/2026-11-25-seed-errors.md). With the spread runs, D(T) ~ T^a_D through the three
// temperatures (the runs' own).
void take_diffusion(Measured& m, BulkRuns& b, int dim, bool spread) {
  b.d[0] = diffusion_from_msd(b.c.corr, dim);
  const Repeated dr = summarise_repeats(b.d, RepeatError::Spread);
  m.diffusion = dr.value;
  m.diffusion_dof = dr.dof;
  m.diffusion_repeats = dr.repeats;
  if (!spread) return;
  const Estimate d_plus = diffusion_from_msd(b.dp.corr, dim),
                 d_minus = diffusion_from_msd(b.dm.corr, dim);
  const PowerLawFit law = fit_power_law({b.dm.t.mean, b.c.t.mean, b.dp.t.mean},
                                        {d_minus, m.diffusion, d_plus}, b.c.t.mean);
  m.diffusion_exponent = {law.exponent, law.exponent_stderr};
}

// dp/dT, dp/drho, alpha_p, c_p - c_v and the excess pressure's fit from the five state points.
void take_thermodynamics(Measured& m, const BulkRuns& b, double rho, double h) {
  // Central differences against the measured temperatures (an NVE run's T is an outcome).
  const double dtemp = b.tp.t.mean - b.tm.t.mean;
  m.dp_dt = {(b.tp.p.mean - b.tm.p.mean) / dtemp,
             std::hypot(b.tp.p.stderr_, b.tm.p.stderr_) / std::fabs(dtemp)};
  m.dp_drho = {(b.rp.p.mean - b.rm.p.mean) / (2 * h * rho),
               std::hypot(b.rp.p.stderr_, b.rm.p.stderr_) / (2 * h * rho)};
  const double alpha = m.dp_dt.mean / (rho * m.dp_drho.mean); // docs/theory.md
  m.expansion = {alpha, std::fabs(alpha) * std::hypot(m.dp_dt.stderr_ / m.dp_dt.mean,
                                                      m.dp_drho.stderr_ / m.dp_drho.mean)};
  // c_p - c_v = T V alpha_p^2 / (N kappa_T) = T (dp/dT)^2 / (rho^2 (dp/drho)) per particle
  // (thermodynamic identity; 1 k for the ideal gas).
  const double gap =
      m.temperature.mean * m.dp_dt.mean * m.dp_dt.mean / (rho * rho * m.dp_drho.mean);
  m.cp_minus_cv = {gap, std::fabs(gap) * std::hypot(2 * m.dp_dt.stderr_ / m.dp_dt.mean,
                                                    m.dp_drho.stderr_ / m.dp_drho.mean)};
  m.excess_pressure = fit_excess_pressure({{rho, b.c.t.mean, b.c.p},
                                           {rho, b.tp.t.mean, b.tp.p},
                                           {rho, b.tm.t.mean, b.tm.p},
                                           {rho * (1 + h), b.rp.t.mean, b.rp.p},
                                           {rho * (1 - h), b.rm.t.mean, b.rm.p}},
                                          rho);
}
} // namespace

Measured measure(const particle::ParticleParameters& p, long steps, int diffusion_repeats, double h,
                 double diffusion_spread) {
  BulkRuns runs = run_bulk(p, steps, diffusion_repeats, h, diffusion_spread);
  Measured m;
  m.pressure = runs.c.p;
  m.temperature = runs.c.t;
  m.rdf_csv = runs.c.rdf;
  take_diffusion(m, runs, p.dim, diffusion_spread > 0);
  take_thermodynamics(m, runs, p.density, h);
  return m;
}

ExcessPressureFit fit_excess_pressure(const std::vector<PressurePoint>& points,
                                      double reference_density) {
  ExcessPressureFit f;
  f.points = points;
  f.reference_density = reference_density;
  // Weighted least squares of y = b0 + b1 T + b2 (n - n_ref), y = (p - n T) / n^2, by the normal
  // equations (Numerical Recipes, 3rd ed., sec. 15.4): the rows scaled by 1 / sigma_y.
  const int k = static_cast<int>(points.size());
  Eigen::MatrixXd A(k, 3);
  Eigen::VectorXd y(k);
  for (int i = 0; i < k; ++i) {
    const auto& pt = points[i];
    const double n2 = pt.density * pt.density, sigma = pt.pressure.stderr_ / n2;
    A.row(i) << 1 / sigma, pt.temperature / sigma, (pt.density - reference_density) / sigma;
    y(i) = (pt.pressure.mean - pt.density * pt.temperature) / n2 / sigma; // p = n T + n^2 B
  }
  f.dof = k - 3;
  const Eigen::Matrix3d normal = A.transpose() * A;
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(normal);
  if (f.dof < 0 || !lu.isInvertible()) {
    f.b0 = f.b1 = f.b2 = f.b0_stderr = f.b1_stderr = f.b2_stderr = std::nan("");
    return f;
  }
  const Eigen::Vector3d b = lu.solve(A.transpose() * y);
  f.b0 = b(0), f.b1 = b(1), f.b2 = b(2);
  const double chi2 = (A * b - y).squaredNorm();
  f.chi2_per_dof = f.dof > 0 ? chi2 / f.dof : std::nan("");
  const double scale = f.dof > 0 ? std::max(1.0, f.chi2_per_dof) : 1.0;
  f.covariance = scale * lu.inverse();
  f.b0_stderr = std::sqrt(f.covariance(0, 0));
  f.b1_stderr = std::sqrt(f.covariance(1, 1));
  f.b2_stderr = std::sqrt(f.covariance(2, 2));
  return f;
}

io::Json ExcessPressureFit::json() const {
  io::Json j = io::Json::object();
  j["form"] = "p = n k T + n^2 (b0 + b1 k T + b2 (n - n_ref))";
  j["n_ref"] = reference_density;
  j["b0"] = b0, j["b0_stderr"] = b0_stderr;
  j["b1"] = b1, j["b1_stderr"] = b1_stderr;
  j["b2"] = b2, j["b2_stderr"] = b2_stderr;
  j["covariance"] = io::Json::array();
  for (int i = 0; i < 3; ++i)
    j["covariance"].push_back({covariance(i, 0), covariance(i, 1), covariance(i, 2)});
  j["chi2_per_dof"] = chi2_per_dof, j["dof"] = dof;
  j["points"] = io::Json::array();
  for (const auto& pt : points) {
    io::Json q = io::Json::object();
    q["density"] = pt.density, q["temperature"] = pt.temperature;
    q["pressure"] = pt.pressure.mean, q["pressure_stderr"] = pt.pressure.stderr_;
    j["points"].push_back(q);
  }
  return j;
}

io::Json Measured::json() const {
  io::Json j = io::Json::object();
  auto put = [&](const char* k, const Estimate& e) {
    j[k] = e.mean;
    j[std::string(k) + "_stderr"] = e.stderr_;
  };
  put("pressure", pressure);
  put("temperature_kinetic", temperature);
  put("self_diffusion", diffusion);
  j["self_diffusion_stderr_dof"] = diffusion_dof;
  if (std::isfinite(diffusion_exponent.mean)) put("self_diffusion_exponent", diffusion_exponent);
  j["self_diffusion_repeats"] = io::Json::array();
  for (const auto& e : diffusion_repeats) {
    io::Json r = io::Json::object();
    r["value"] = e.mean, r["groups_stderr"] = e.stderr_;
    j["self_diffusion_repeats"].push_back(r);
  }
  put("thermal_expansion", expansion);
  put("dp_dT", dp_dt);
  put("dp_drho", dp_drho);
  put("heat_capacity_cp_minus_cv", cp_minus_cv);
  j["excess_pressure"] = excess_pressure.json();
  return j;
}

Repeated summarise_repeats(const std::vector<Estimate>& all, RepeatError rule) {
  Repeated r;
  r.repeats = all;
  std::vector<Estimate> runs; // a failed fit (NaN) is dropped, and counted
  for (const auto& e : all)
    if (std::isfinite(e.mean) && std::isfinite(e.stderr_)) runs.push_back(e);
  r.failed = static_cast<int>(all.size() - runs.size());
  if (runs.empty()) {
    r.value = {std::nan(""), std::nan("")};
    return r;
  }
  const double m = static_cast<double>(runs.size());
  double sum = 0, var_fits = 0;
  for (const auto& e : runs) sum += e.mean, var_fits += e.stderr_ * e.stderr_;
  const double mean = sum / m;
  double ss = 0;
  for (const auto& e : runs) ss += (e.mean - mean) * (e.mean - mean);
  // Standard error of a mean of m independent runs: sample sd / sqrt(m), or sqrt(sum se^2) / m.
  r.spread_stderr = runs.size() > 1 ? std::sqrt(ss / (m - 1) / m) : std::nan("");
  r.fit_stderr = std::sqrt(var_fits / m / m);
  if (runs.size() < 2)
    r.value = {mean, r.fit_stderr};
  else if (rule == RepeatError::Spread)
    r.value = {mean, r.spread_stderr}, r.dof = static_cast<int>(runs.size()) - 1;
  else
    r.value = {mean, std::max(r.spread_stderr, r.fit_stderr)};
  return r;
}

io::Json Repeated::json() const {
  io::Json j = io::Json::object();
  j["mean"] = value.mean;
  j["stderr"] = value.stderr_;
  j["spread_stderr"] = spread_stderr;
  j["fit_stderr"] = fit_stderr;
  j["failed_fits"] = failed;
  j["stderr_dof"] = dof;
  io::Json runs = io::Json::array();
  for (const auto& e : repeats) {
    io::Json r = io::Json::object();
    r["value"] = e.mean, r["fit_stderr"] = e.stderr_;
    runs.push_back(r);
  }
  j["repeats"] = runs;
  return j;
}

PowerLawFit fit_power_law(const std::vector<double>& temperatures,
                          const std::vector<Estimate>& values, double reference) {
  // ln c = ln c_ref + n ln(T / T_ref), a straight line in logs weighted by (c / stderr)^2.
  statistics::LineFit line;
  std::vector<std::size_t> used;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i].mean) || !(values[i].stderr_ > 0)) continue;
    line.add(std::log(temperatures[i] / reference), std::log(values[i].mean),
             values[i].stderr_ / values[i].mean);
    used.push_back(i);
  }
  const double nan = std::nan("");
  if (used.size() < 2) return {nan, nan, nan, nan, nan};
  PowerLawFit f;
  f.exponent = line.slope();
  f.exponent_stderr = line.slope_stderr();
  f.value = std::exp(line.intercept());
  f.value_stderr = f.value * line.value_stderr(0);
  double chi2 = 0;
  for (const std::size_t i : used) {
    const double x = std::log(temperatures[i] / reference);
    const double r = (std::log(values[i].mean) - line.intercept() - f.exponent * x) *
                     values[i].mean / values[i].stderr_;
    chi2 += r * r;
  }
  f.chi2_per_dof = used.size() > 2 ? chi2 / static_cast<double>(used.size() - 2) : nan;
  return f;
}

namespace {
// The relaxation runs' box and length: a box doubled along x holding a heat mode and a shear mode
// of its longest wavelength, sampled over three decays of the slower.
particle::ParticleParameters relaxation_scene(particle::ParticleParameters p,
                                              const Estimates& estimate) {
  p.box[0] *= 2;
  p.temperature_perturbation = 0.2;
  // One thermal speed: the mode stands above its thermal noise down to ~10% (seed 002's fluid:
  // eta 1.66 +- 0.02, against 1.75 +- 0.08 at half the amplitude). Its viscous heating goes into
  // the 2k mode and the mean, not into the heat mode's sin(kx).
  p.shear_perturbation = 1.0;
  p.heat_slabs.clear();
  const double k = 2 * M_PI / p.box[0];
  const double chi = estimate.conductivity / (p.density * estimate.heat_capacity_p);
  const double nu = estimate.kinematic_viscosity;
  p.equilibration_steps = 0;
  p.steps = static_cast<long>(std::ceil(3 / (std::min(chi, nu) * k * k) / p.dt)); // 3 decays
  p.sample_interval = std::max(1L, p.steps / 1000);
  p.bins = {{1, 1, 1}};
  return p;
}

// kappa, eta and the mean temperature of each repeat, as they end.
struct RelaxationRepeats {
  std::vector<Estimate> kappa, eta, temperature;
  std::vector<char> done;
  explicit RelaxationRepeats(std::size_t n) : kappa(n), eta(n), temperature(n), done(n, 0) {}

  // One repeat's run and its fits.
  void run(const particle::ParticleParameters& q, double cp, std::size_t r) {
    const auto out = run_on_every_rank(q);
    auto fitted = [&](const char* fit, const char* key, double scale) -> Estimate {
      const std::string stderr_key = std::string(key) + "_stderr";
      return {scale * io::number(out.summary, {fit, key}),
              scale * io::number(out.summary, {fit, stderr_key})};
    };
    kappa[r] = fitted("relaxation", "chi", q.density * cp); // kappa = rho c_p chi
    eta[r] = fitted("shear_relaxation", "viscosity", 1);    // eta = n m nu, by the fit
    // The run's own mean temperature: the decaying shear mode's kinetic energy, U^2 k T / 4 per
    // particle, ends as heat (+2% of T at c_v = 10 in 2D), and an NVE start settles on its own.
    // T_internal = 1/<1/theta> leaves the flow's kinetic energy out (the heat mode biases it low
    // by ~A^2/2 at the start, ~0.3% over the run).
    temperature[r] = {io::number(out.summary, {"T_internal"}),
                      io::number(out.summary, {"T_internal_stderr"})};
  }

  // The repeats that have ended, in repeat order, summarised into a copy of `base`; their count.
  int so_far(RelaxationCoefficients& base) const {
    std::vector<Estimate> k, e, t;
    for (std::size_t i = 0; i < done.size(); ++i)
      if (done[i]) k.push_back(kappa[i]), e.push_back(eta[i]), t.push_back(temperature[i]);
    base.conductivity = summarise_repeats(k);
    base.viscosity = summarise_repeats(e);
    base.temperature = summarise_repeats(t);
    return static_cast<int>(k.size());
  }
};
} // namespace

RelaxationCoefficients
measure_relaxation(particle::ParticleParameters p, const Estimates& estimate, double cp,
                   int repeats,
                   const std::function<void(int, const RelaxationCoefficients&, int)>& report) {
  p = relaxation_scene(p, estimate);
  RelaxationCoefficients out;
  out.particles = p.particle_count();
  out.steps = p.steps;
  RelaxationRepeats repeat(static_cast<std::size_t>(repeats));
  std::vector<Job> jobs;
  for (int r = 0; r < repeats; ++r)
    jobs.push_back({1, [&, r] {
                      particle::ParticleParameters q = p;
                      q.seed = p.seed + 7919 * static_cast<std::uint64_t>(r);
                      repeat.run(q, cp, static_cast<std::size_t>(r));
#pragma omp critical(relaxation_report)
                      {
                        repeat.done[static_cast<std::size_t>(r)] = 1;
                        RelaxationCoefficients so_far = out;
                        const int ended = repeat.so_far(so_far);
                        if (report) report(ended, so_far, r); // what has ended so far
                      }
                    }});
  run_jobs(std::move(jobs));
  repeat.so_far(out);
  return out;
}

} // namespace twinflow::transport
