#include "particle/run.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <sstream>

#include "particle/fields.hpp"
#include "particle/simulation.hpp"
#include "particle/theory.hpp"

namespace twinflow::particle {

Estimate block_average(const std::vector<double>& x, int blocks) {
  Estimate e;
  if (x.empty()) return e;
  e.mean = std::accumulate(x.begin(), x.end(), 0.0) / x.size();
  const std::size_t per = x.size() / blocks;
  if (per == 0) return e;
  std::vector<double> means(blocks, 0.0);
  for (int b = 0; b < blocks; ++b) {
    for (std::size_t k = 0; k < per; ++k) means[b] += x[b * per + k];
    means[b] /= per;
  }
  const double m = std::accumulate(means.begin(), means.end(), 0.0) / blocks;
  double var = 0;
  for (const double b : means) var += (b - m) * (b - m);
  e.stderr_ = std::sqrt(var / (blocks - 1) / blocks); // standard error of the mean of block means
  return e;
}

namespace {

struct Histogram {
  double lo, hi;
  std::vector<double> counts;
  double total = 0;
  Histogram(double lo_, double hi_, int bins) : lo(lo_), hi(hi_), counts(bins, 0.0) {}
  void add(double x) {
    total += 1;
    const int b = static_cast<int>((x - lo) / (hi - lo) * counts.size());
    if (b >= 0 && b < static_cast<int>(counts.size())) counts[b] += 1;
  }
  double width() const { return (hi - lo) / counts.size(); }
  double density(int b) const { return total > 0 ? counts[b] / (total * width()) : 0; }
};

io::Snapshot snapshot(const BinnedFields& f, double time, double wall, long particle_steps) {
  io::Snapshot s;
  s.time = time;
  s.wall_seconds = wall;
  s.particle_steps = particle_steps;
  auto add = [&](const char* name, const FieldEstimate& e, int components) {
    s.fields.push_back(io::Field{name, components, e.mean, e.stderr_});
  };
  add("density", f.density, 1);
  add("temperature_kinetic", f.temperature_kinetic, 1);
  add("temperature_internal", f.temperature_internal, 1);
  add("internal_energy", f.internal_energy, 1);
  add("velocity", f.velocity, f.dim);
  return s;
}

// Seed 002 section III.B: linear fits of T_internal(x) in the central 60% of both halves between
// the slabs; kappa = J0 / |dT/dx| with J0 = power / (2 A).
io::Json slab_fit(const ParticleParameters& p, const BinnedFields& f) {
  const HeatSlab& hot = p.heat_slabs[0];
  const HeatSlab& cold = p.heat_slabs[1];
  const int dir = hot.direction;
  const double length = p.box[dir];
  double area = 1;
  for (int d = 0; d < p.dim; ++d)
    if (d != dir) area *= p.box[d];
  const double j0 = std::fabs(hot.power) / (2 * area);
  io::Json out = io::Json::object();
  out["J0"] = j0;
  double wsum = 0, ksum = 0;
  const char* names[2] = {"hot_to_cold", "cold_to_hot"};
  const double starts[2] = {hot.upper, cold.upper}, ends[2] = {cold.lower, hot.lower};
  for (int half = 0; half < 2; ++half) {
    double a = starts[half], b = ends[half];
    if (b <= a) b += length; // the half wraps around the periodic box
    const double lo = a + 0.2 * (b - a), hi = b - 0.2 * (b - a);
    double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int bin = 0; bin < f.bin_count(); ++bin) {
      double x = f.centre(bin, dir);
      if (x < a) x += length;
      if (x < lo || x > hi) continue;
      const double y = f.temperature_internal.mean[bin], se = f.temperature_internal.stderr_[bin];
      const double w = se > 0 ? 1 / (se * se) : 1;
      sw += w, sx += w * x, sy += w * y, sxx += w * x * x, sxy += w * x * y;
    }
    const double det = sw * sxx - sx * sx;
    const double slope = (sw * sxy - sx * sy) / det, intercept = (sxx * sy - sx * sxy) / det;
    const double slope_se = std::sqrt(sw / det);
    const double kappa = j0 / std::fabs(slope), kappa_se = kappa * slope_se / std::fabs(slope);
    io::Json h = io::Json::object();
    h["fit_from"] = lo, h["fit_to"] = hi;
    h["slope"] = slope, h["slope_stderr"] = slope_se, h["intercept"] = intercept;
    h["kappa"] = kappa, h["kappa_stderr"] = kappa_se;
    out[names[half]] = h;
    wsum += 1 / (kappa_se * kappa_se), ksum += kappa / (kappa_se * kappa_se);
  }
  out["kappa"] = ksum / wsum;
  out["kappa_stderr"] = 1 / std::sqrt(wsum);
  return out;
}

template <class M>
RunOutput drive(const M& model, const ParticleParameters& p, const RunControl& control) {
  constexpr int D = M::D;
  using clock = std::chrono::steady_clock;
  const auto t0 = clock::now();
  Simulation<M> sim(model, p);
  const std::size_t n = sim.state().size();
  const double volume = [&] {
    double v = 1;
    for (int d = 0; d < D; ++d) v *= p.box[d];
    return v;
  }();
  const double e0 = sim.total_energy();
  double drift_max = 0;

  std::ostringstream thermo;
  thermo << "# particle thermo: one row per sample. Units: m = k = rc = T0 = 1 (energies in k T0, "
            "time in tau)\n"
            "step,time,sampled,E_total,E_kinetic,E_internal,E_potential,T_kinetic,"
            "T_internal_harmonic,T_internal_mean,pressure,momentum_x,momentum_y,momentum_z\n";
  std::vector<double> s_tk, s_ti, s_tm, s_p, s_e;
  const double vmax = 5 * std::sqrt(p.temperature / p.mass);
  Histogram hv(-vmax, vmax, p.histogram_bins);
  Histogram hu(0, 3 * p.cv * p.temperature, p.histogram_bins);
  const double r_max = model.rc;
  std::vector<double> rdf(p.rdf_bins, 0.0);
  long rdf_samples = 0;
  // VACF / MSD of up to 1000 tracked particles (ids 0..), over a window of W samples.
  const std::size_t tracked = std::min<std::size_t>(n, 1000);
  const int window = p.correlation_samples;
  std::vector<std::vector<double>> vbuf, xbuf; // ring buffers [sample][tracked*D]
  std::vector<double> vacf(window, 0.0), msd(window, 0.0), corr_count(window, 0.0);
  std::vector<double> unwrapped(tracked * D), last_wrapped(tracked * D);
  std::vector<std::size_t> index_of(n);
  long sample_count = 0;

  const long total_steps = p.equilibration_steps + p.steps;
  long sampled_rows = 0;
  for (long step = p.equilibration_steps + 1; step <= total_steps; ++step)
    sampled_rows += step % p.sample_interval == 0 || step == total_steps;
  std::array<double, 3> box3{{p.box[0], p.box[1], D == 3 ? p.box[2] : 1.0}};
  FieldSampler<D> fields(box3, p.bins, p.blocks, sampled_rows, p.mass, p.cv);
  std::unique_ptr<FieldSampler<D>> slab_profile;
  if (!p.heat_slabs.empty()) { // 0.5 rc bins along the slab direction
    std::array<int, 3> bins{{1, 1, 1}};
    const int dir = p.heat_slabs[0].direction;
    bins[dir] = std::max(4, static_cast<int>(std::lround(p.box[dir] / 0.5)));
    slab_profile =
        std::make_unique<FieldSampler<D>>(box3, bins, p.blocks, sampled_rows, p.mass, p.cv);
  }
  long fields_taken = 0;
  RunOutput out;
  out.field_grid.dim = D;
  for (int d = 0; d < D; ++d) {
    out.field_grid.counts[d] = p.bins[d];
    out.field_grid.spacing[d] = p.box[d] / p.bins[d];
  }
  auto last_progress = clock::now();
  for (long step = 1; step <= total_steps; ++step) {
    sim.step();
    if (step % p.sample_interval != 0 && step != total_steps) continue;
    const auto& s = sim.state();
    const double k = sim.kinetic_energy(), u = sim.internal_energy(), pot = sim.potential_energy();
    const double e = k + u + pot;
    double inflow = 0; // energy in through thermal walls: E(t) - E(0) - inflow is the error
    for (const double q : sim.wall_energy_in()) inflow += q;
    drift_max = std::max(drift_max, std::fabs(e - e0 - inflow) / std::fabs(e0));
    const double t_kin = 2 * k / (D * (n - 1.0)); // total momentum is conserved: d(N-1) dof
    double inv_theta = 0, mean_theta = 0;
    for (const double ui : s.u) inv_theta += model.cv / ui, mean_theta += ui / model.cv;
    const double t_int = s.u.empty() ? p.temperature : n / inv_theta;
    mean_theta = s.u.empty() ? p.temperature : mean_theta / n;
    // Virial pressure from the conservative force; g(r) from the same pass.
    double virial = 0;
    const bool sampled = step > p.equilibration_steps;
    sim.grid().for_each_pair_serial(s, model.rc,
                                    [&](std::size_t i, std::size_t j, const double*, double r2) {
                                      const double r = std::sqrt(r2);
                                      if constexpr (M::Conservative::active) {
                                        if (r < model.conservative.rc) {
                                          double th_i = 1, th_j = 1, fc, phi;
                                          if constexpr (M::has_energy)
                                            th_i = s.u[i] / model.cv, th_j = s.u[j] / model.cv;
                                          model.conservative.eval(r, th_i, th_j, fc, phi);
                                          virial += r * fc; // r_ij . F^C_ij
                                        }
                                      }
                                      if (sampled) {
                                        const int b = static_cast<int>(r / r_max * rdf.size());
                                        if (b < static_cast<int>(rdf.size())) rdf[b] += 1;
                                      }
                                    });
    const double pressure = (2 * k + virial) / (D * volume); // virial theorem, 000:(3.9)
    std::array<double, 3> mom{0, 0, 0};
    for (int d = 0; d < D; ++d)
      for (const double v : s.v[d]) mom[d] += model.mass * v;
    char row[512];
    std::snprintf(row, sizeof row,
                  "%ld,%.6f,%d,%.17g,%.17g,%.17g,%.17g,%.10g,%.10g,%.10g,%.10g,%.3e,%.3e,%.3e\n",
                  step, step * p.dt, sampled ? 1 : 0, e, k, u, pot, t_kin, t_int, mean_theta,
                  pressure, mom[0], mom[1], mom[2]);
    thermo << row;
    if (sampled) {
      fields.sample(s);
      ++fields_taken;
      if (fields_taken == sampled_rows || fields_taken % std::max(1L, sampled_rows / 10) == 0) {
        const double wall_now = std::chrono::duration<double>(clock::now() - t0).count();
        out.field_snapshots.push_back(
            snapshot(fields.result(), step * p.dt, wall_now, static_cast<long>(n) * step));
      }
      if (slab_profile) slab_profile->sample(s);
      s_tk.push_back(t_kin), s_ti.push_back(t_int), s_tm.push_back(mean_theta);
      s_p.push_back(pressure), s_e.push_back(e);
      ++rdf_samples;
      for (int d = 0; d < D; ++d)
        for (const double v : s.v[d]) hv.add(v);
      for (const double ui : s.u) hu.add(ui);
      // correlations
      for (std::size_t i = 0; i < n; ++i) index_of[s.id[i]] = i;
      std::vector<double> vs(tracked * D), xs(tracked * D);
      for (std::size_t t = 0; t < tracked; ++t) {
        const std::size_t i = index_of[t];
        for (int d = 0; d < D; ++d) {
          vs[t * D + d] = s.v[d][i];
          double dx = s.x[d][i] - last_wrapped[t * D + d];
          if (sample_count > 0)
            dx -= p.box[d] * std::nearbyint(dx / p.box[d]);
          else
            dx = 0, unwrapped[t * D + d] = s.x[d][i];
          unwrapped[t * D + d] += dx;
          last_wrapped[t * D + d] = s.x[d][i];
          xs[t * D + d] = unwrapped[t * D + d];
        }
      }
      vbuf.push_back(std::move(vs)), xbuf.push_back(std::move(xs));
      if (static_cast<int>(vbuf.size()) > window)
        vbuf.erase(vbuf.begin()), xbuf.erase(xbuf.begin());
      const std::size_t last = vbuf.size() - 1;
      for (std::size_t lag = 0; lag <= last; ++lag) {
        const auto &v0 = vbuf[last - lag], &v1 = vbuf[last], &x0 = xbuf[last - lag],
                   &x1 = xbuf[last];
        double cv = 0, dr = 0;
        for (std::size_t k2 = 0; k2 < tracked * D; ++k2) {
          cv += v0[k2] * v1[k2];
          dr += (x1[k2] - x0[k2]) * (x1[k2] - x0[k2]);
        }
        vacf[lag] += cv / tracked, msd[lag] += dr / tracked, corr_count[lag] += 1;
      }
      ++sample_count;
    }
    if (control.progress && clock::now() - last_progress > std::chrono::seconds(2)) {
      last_progress = clock::now();
      const double secs = std::chrono::duration<double>(clock::now() - t0).count();
      const double rate = step / secs;
      std::fprintf(
          stderr, "\rstep %ld/%ld  t = %.2f  %.0f steps/s  ETA %.0f s  T = %.4f  dE/E = %.1e   ",
          step, total_steps, step * p.dt, rate, (total_steps - step) / rate, t_kin, drift_max);
    }
  }
  if (control.progress) std::fprintf(stderr, "\n");
  const double wall = std::chrono::duration<double>(clock::now() - t0).count();

  io::Json& j = out.summary;
  j = io::Json::object();
  j["N"] = static_cast<long>(n);
  j["dim"] = D;
  j["steps"] = p.steps;
  j["equilibration_steps"] = p.equilibration_steps;
  j["dt"] = p.dt;
  j["integrator"] = to_string(p.integrator);
  j["energy_offset"] = p.energy_offset;
  j["wall_seconds"] = wall;
  j["particle_steps_per_second"] = n * static_cast<double>(total_steps) / wall;
  // |E(t) - E(0) - energy in through walls| / E(0): the integrator's energy error
  j["energy_relative_drift_max"] = drift_max;
  auto put = [&](const std::string& key, const std::vector<double>& series) {
    const Estimate e = block_average(series, p.blocks);
    j[key] = e.mean;
    j[key + "_stderr"] = e.stderr_;
  };
  put("T_kinetic", s_tk);
  put("T_internal", s_ti);
  put("T_internal_mean_theta", s_tm);
  put("pressure", s_p);
  if (M::has_energy && !M::Conservative::active && !p.has_walls())
    j["T_energy_equation_of_state"] = ideal_dpde_temperature(p, e0 / n); // 000:(3.21)
  if (p.has_walls()) {
    io::Json walls = io::Json::object();
    const char* names[6] = {"x_lower", "x_upper", "y_lower", "y_upper", "z_lower", "z_upper"};
    const double time = total_steps * p.dt;
    for (int w = 0; w < 2 * D; ++w) {
      if (!p.walls[w / 2].present) continue;
      walls[names[w]]["energy_in"] = sim.wall_energy_in()[w];
      walls[names[w]]["mean_heat_flow_in"] = sim.wall_energy_in()[w] / time; // energy per time
    }
    j["walls"] = walls;
    j["wall_reflections"] = sim.wall_crossings();
  }
  j["samples"] = static_cast<long>(s_tk.size());
  j["blocks"] = p.blocks;
  j["stability_hint"] = stability_hint(p);

  std::ostringstream h;
  h << "# histograms over sampled steps; velocity in sqrt(k T0/m), internal energy in k T0\n"
       "quantity,bin_centre,probability_density\n";
  for (int b = 0; b < p.histogram_bins; ++b)
    h << "velocity_component," << hv.lo + (b + 0.5) * hv.width() << "," << hv.density(b) << "\n";
  if (M::has_energy)
    for (int b = 0; b < p.histogram_bins; ++b)
      h << "internal_energy," << hu.lo + (b + 0.5) * hu.width() << "," << hu.density(b) << "\n";
  out.histograms_csv = h.str();

  std::ostringstream g;
  g << "# pair distribution function g(r) for r < the largest cutoff; r in rc\nr,g\n";
  const double dr = r_max / rdf.size();
  for (std::size_t b = 0; b < rdf.size(); ++b) {
    const double r0 = b * dr, r1 = r0 + dr;
    const double shell =
        D == 3 ? 4.0 / 3.0 * M_PI * (r1 * r1 * r1 - r0 * r0 * r0) : M_PI * (r1 * r1 - r0 * r0);
    const double ideal = 0.5 * n * (n / volume) * shell * std::max<long>(rdf_samples, 1);
    g << r0 + 0.5 * dr << "," << rdf[b] / ideal << "\n";
  }
  out.rdf_csv = g.str();

  std::ostringstream c;
  c << "# velocity autocorrelation <v(0).v(t)> (k T0/m) and mean-square displacement (rc^2), "
       "averaged over time origins and "
    << tracked << " particles\ntime,vacf,msd\n";
  for (int lag = 0; lag < window; ++lag)
    if (corr_count[lag] > 0)
      c << lag * p.sample_interval * p.dt << "," << vacf[lag] / corr_count[lag] << ","
        << msd[lag] / corr_count[lag] << "\n";
  out.correlations_csv = c.str();
  out.thermo_csv = thermo.str();
  out.fields_csv = fields.result().csv();
  if (slab_profile) {
    const BinnedFields profile = slab_profile->result();
    out.slab_profile_csv = profile.csv();
    if (M::has_energy && p.heat_slabs.size() == 2) j["heat_slabs"] = slab_fit(p, profile);
  }
  return out;
}

// ---- resolving the case into a compiled combination (the only place that branches on physics)

template <int D, class C, class F, class V>
auto with_heat(const ParticleParameters& p, const C& c, const F& f, V&& visit) {
  const Weight w(p.heat_weight.cutoff, p.heat_weight.exponent);
  auto model = [&](const auto& h) {
    return visit(
        Model<D, C, F, std::decay_t<decltype(h)>>{c, f, h, p.mass, p.cv, p.largest_cutoff()});
  };
  if constexpr (!F::isothermal) {
    if (p.heat == HeatLaw::Inverse && p.heat_coefficient == HeatCoefficient::Constant)
      return model(InverseConstantHeat{p.kappa0, w});
    if (p.heat == HeatLaw::Inverse) return model(InverseSeed002Heat{p.kappa0, p.cv, w});
    if (p.heat == HeatLaw::Linear)
      return model(LinearHeat{p.cv * p.kappa0, p.cv, p.linear_noise_factor, w});
  }
  return model(NoHeat{});
}

template <int D, class C, class V>
auto with_friction(const ParticleParameters& p, const C& c, V&& visit) {
  const Weight w(p.dissipation.cutoff, p.dissipation.exponent);
  if (p.energy == EnergyModel::Isothermal)
    return with_heat<D>(
        p, c, IsothermalFriction{p.gamma, std::sqrt(2 * p.temperature * p.gamma), w}, visit);
  if (p.friction == Friction::ConstantGamma)
    return with_heat<D>(p, c, ConstantGamma{p.gamma, p.cv, w}, visit);
  return with_heat<D>(p, c, ConstantSigma{p.sigma, w}, visit);
}

template <int D, class V> auto with_conservative(const ParticleParameters& p, V&& visit) {
  const double rc = p.conservative_cutoff;
  switch (p.conservative) {
  case ConservativeForce::Constant:
    return with_friction<D>(p, ConstantRepulsion{p.a0, rc, 1 / rc}, visit);
  case ConservativeForce::TemperatureDependent:
    return with_friction<D>(
        p, TemperatureRepulsion{p.a0, rc, 1 / rc, 0.5 / p.reference_temperature}, visit);
  default:
    return with_friction<D>(p, NoConservative{}, visit);
  }
}

// Calls visit(model) with the compiled model the parameters describe.
template <class V> auto dispatch(const ParticleParameters& p, V&& visit) {
  return p.dim == 2 ? with_conservative<2>(p, visit) : with_conservative<3>(p, visit);
}

} // namespace

RunOutput run_particles(const ParticleParameters& p, const RunControl& control) {
  return dispatch(p, [&](const auto& model) { return drive(model, p, control); });
}

BenchResult bench_particles(const ParticleParameters& p, long steps) {
  return dispatch(p, [&](const auto& model) {
    using M = std::decay_t<decltype(model)>;
    Simulation<M> sim(model, p);
    sim.step(); // warm caches and thread pool
    const auto t0 = std::chrono::steady_clock::now();
    for (long s = 0; s < steps; ++s) sim.step();
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    BenchResult r;
    r.particles = static_cast<long>(sim.state().size());
    r.seconds = secs;
    r.particle_steps_per_second = r.particles * static_cast<double>(steps) / secs;
    // Resident per-particle arrays: state (x, v, u, id), carried (f, q, potential), the sort's
    // cell index and permutation, and the sort's temporary copy of the largest array.
    r.bytes_per_particle =
        (2 * M::D + (M::has_energy ? 1 : 0)) * 8 + 4 + (M::D + 2) * 8 + 4 + 4 + 8;
    return r;
  });
}

} // namespace twinflow::particle
