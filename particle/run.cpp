#include "particle/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <sstream>

#include "particle/archive.hpp"
#include "particle/decay_fit.hpp"
#include "particle/fields.hpp"
#include "particle/line_fit.hpp"
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

std::vector<double> blocking_errors(const std::vector<double>& x, int blocks) {
  std::vector<double> errors;
  for (int merge = 1; merge <= 4 && blocks / merge >= 2; merge *= 2)
    errors.push_back(block_average(x, blocks / merge).stderr_);
  return errors;
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
  add("flux_conductive", f.flux_conductive, f.dim);
  add("flux_internal", f.flux_internal, f.dim);
  add("flux_kinetic", f.flux_kinetic, f.dim);
  add("flux_potential", f.flux_potential, f.dim);
  return s;
}

// Thermal walls at different temperatures along d, fields binned along d only: a line through
// T_internal in the central 60% and the jump T_wall - T_line(wall) at each wall (Kapitza).
io::Json wall_profile_fit(const ParticleParameters& p, const BinnedFields& f) {
  for (int d = 0; d < p.dim; ++d) {
    const WallPair& w = p.walls[d];
    if (!w.present || !w.thermal[0] || !w.thermal[1] || f.bins[d] < 5) continue;
    bool one_d = true;
    for (int e = 0; e < p.dim; ++e) one_d &= e == d || f.bins[e] == 1;
    if (!one_d) continue;
    const double length = p.box[d], lo = 0.2 * length, hi = 0.8 * length;
    const auto line = [&](const std::vector<double>& temperature) {
      LineFit fit;
      for (int bin = 0; bin < f.bin_count(); ++bin) {
        const double x = f.centre(bin, d);
        if (x >= lo && x <= hi) fit.add(x, temperature[bin], f.temperature_internal.stderr_[bin]);
      }
      return fit;
    };
    const LineFit fit = line(f.temperature_internal.mean);
    // The slope's error from the blocks' own slopes (the same weights, so their mean is the
    // slope): the bins share the profile's slow fluctuations, which the fit's error, over
    // independent bins, leaves out. With 2 and 4 blocks merged too; the largest is stated.
    std::vector<double> block_slopes;
    for (const auto& block : f.temperature_internal_blocks)
      block_slopes.push_back(line(block).slope());
    const std::vector<double> blocking =
        blocking_errors(block_slopes, static_cast<int>(block_slopes.size()));
    double slope_stderr = fit.slope_stderr();
    for (const double se : blocking) slope_stderr = std::max(slope_stderr, se);
    io::Json j = io::Json::object();
    j["direction"] = d;
    j["fit_from"] = lo, j["fit_to"] = hi;
    j["slope"] = fit.slope(), j["slope_stderr"] = slope_stderr;
    j["slope_stderr_fit"] = fit.slope_stderr(), j["slope_stderr_blocking"] = blocking;
    j["intercept"] = fit.intercept();
    j["jump_lower"] = w.temperature[0] - fit.intercept();
    j["jump_upper"] = w.temperature[1] - (fit.intercept() + fit.slope() * length);
    j["jump_lower_stderr"] = fit.value_stderr(0);
    j["jump_upper_stderr"] = fit.value_stderr(length);
    return j;
  }
  return io::Json();
}

// Reverse Poiseuille flow: in each half the steady v_x(y) is a parabola with v'' = -n F / eta
// (n F the force density). A weighted quadratic fit per half over the bins away from the two
// planes where the force flips (the central 80% of each half); eta combined over both halves.
io::Json poiseuille_fit(const ParticleParameters& p, const BinnedFields& f) {
  io::Json j = io::Json::object();
  if (f.bins[1] < 8) {
    j["note"] = "needs at least 8 bins along y";
    return j;
  }
  const double ly = p.box[1];
  double wsum = 0, esum = 0;
  const char* names[2] = {"lower_half", "upper_half"};
  for (int half = 0; half < 2; ++half) {
    const double lo = half * 0.5 * ly + 0.05 * ly, hi = (half + 1) * 0.5 * ly - 0.05 * ly;
    double s[5] = {0, 0, 0, 0, 0}, t[3] = {0, 0, 0}; // sums of w y^k and w v y^k
    for (int bin = 0; bin < f.bin_count(); ++bin) {
      const double y = f.centre(bin, 1);
      if (y < lo || y > hi) continue;
      const double v = f.velocity.mean[bin * f.dim], se = f.velocity.stderr_[bin * f.dim];
      const double w = se > 0 ? 1 / (se * se) : 1;
      for (int k = 0; k < 5; ++k) s[k] += w * std::pow(y, k);
      for (int k = 0; k < 3; ++k) t[k] += w * v * std::pow(y, k);
    }
    // Normal equations for v = c0 + c1 y + c2 y^2; c2 and its variance by Cramer's rule.
    const double m[3][3] = {{s[0], s[1], s[2]}, {s[1], s[2], s[3]}, {s[2], s[3], s[4]}};
    auto det3 = [](const double a[3][3]) {
      return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
             a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
             a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    };
    const double det = det3(m);
    double mc[3][3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) mc[r][c] = c == 2 ? t[r] : m[r][c];
    const double c2 = det3(mc) / det;
    const double c2_var = (s[0] * s[2] - s[1] * s[1]) / det; // (M^-1)_22
    const double force = half == 0 ? p.poiseuille_force : -p.poiseuille_force;
    const double eta = -p.density * force / (2 * c2); // v'' = 2 c2 = -n F / eta
    const double eta_se = std::fabs(eta) * std::sqrt(c2_var) / std::fabs(c2);
    io::Json h = io::Json::object();
    h["curvature"] = 2 * c2, h["viscosity"] = eta, h["viscosity_stderr"] = eta_se;
    j[names[half]] = h;
    wsum += 1 / (eta_se * eta_se), esum += eta / (eta_se * eta_se);
  }
  j["viscosity"] = esum / wsum;
  j["viscosity_stderr"] = 1 / std::sqrt(wsum);
  return j;
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
    LineFit fit;
    for (int bin = 0; bin < f.bin_count(); ++bin) {
      double x = f.centre(bin, dir);
      if (x < a) x += length;
      if (x >= lo && x <= hi)
        fit.add(x, f.temperature_internal.mean[bin], f.temperature_internal.stderr_[bin]);
    }
    const double slope = fit.slope(), intercept = fit.intercept(), slope_se = fit.slope_stderr();
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

io::Json heat_relaxation_fit(const ParticleParameters& p, const std::vector<double>& t,
                             const std::vector<double>& a) {
  io::Json j = decay_fit(2 * M_PI / p.box[0], t, a, "chi");
  if (!j.contains("chi")) return j;
  // kappa = rho c_p chi with the ideal DPDE fluid's c_p = c_v + k + (d/2) k + k per particle
  // (physics.md); the transport stage converts chi itself, with the c_p of its estimate.
  const double scale = p.density * (p.cv + 2 + 0.5 * p.dim);
  j["kappa_ideal_cp"] = scale * j["chi"].get<double>();
  j["kappa_ideal_cp_stderr"] = scale * j["chi_stderr"].get<double>();
  return j;
}

io::Json shear_relaxation_fit(const ParticleParameters& p, const std::vector<double>& t,
                              const std::vector<double>& a) {
  io::Json j = decay_fit(2 * M_PI / p.box[0], t, a, "nu");
  if (!j.contains("nu")) return j;
  const double scale = p.density * p.mass; // eta = rho m nu
  j["viscosity"] = scale * j["nu"].get<double>();
  j["viscosity_stderr"] = scale * j["nu_stderr"].get<double>();
  return j;
}

// Energy-flux decomposition through the planes x = x_plane of a slab scene, from the binned
// profile (the two bins beside the plane), normalised by J0 and signed so that positive means
// from the hot slab towards the cold one (002 Figs. 5-6).
io::Json flux_at_planes(const ParticleParameters& p, const BinnedFields& f, double j0) {
  const int dir = p.heat_slabs[0].direction;
  const HeatSlab& hot = p.heat_slabs[0];
  const HeatSlab& cold = p.heat_slabs[1];
  io::Json out = io::Json::array();
  for (const double plane : {2.0, 8.0}) {
    if (plane >= p.box[dir]) continue;
    // Between the cold slab's upper edge and the hot slab's lower edge heat flows towards -dir.
    const bool lower_half = plane > cold.upper && plane < hot.lower;
    const double sign = lower_half ? -1.0 : 1.0;
    const int n = f.bins[dir];
    const double width = p.box[dir] / n;
    const int right = std::min(n - 1, static_cast<int>(std::lround(plane / width)));
    const int left = std::max(0, right - 1);
    io::Json j = io::Json::object();
    j["x"] = plane;
    double total = 0, total_var = 0;
    const std::pair<const char*, const FieldEstimate*> parts[4] = {
        {"J_conductive", &f.flux_conductive},
        {"J_internal", &f.flux_internal},
        {"J_kinetic", &f.flux_kinetic},
        {"J_potential", &f.flux_potential}};
    for (const auto& [name, e] : parts) {
      const std::size_t a = static_cast<std::size_t>(left) * f.dim + dir;
      const std::size_t b = static_cast<std::size_t>(right) * f.dim + dir;
      const double mean = sign * 0.5 * (e->mean[a] + e->mean[b]) / j0;
      const double se = 0.5 * std::hypot(e->stderr_[a], e->stderr_[b]) / j0;
      j[std::string(name) + "_over_J0"] = mean;
      j[std::string(name) + "_over_J0_stderr"] = se;
      total += mean, total_var += se * se;
    }
    j["sum_over_J0"] = total;
    j["sum_over_J0_stderr"] = std::sqrt(total_var);
    out.push_back(j);
  }
  return out;
}

// Cumulative averages at a sequence of times, saved with the run (they cannot be recomputed).
template <class A> void archive_snapshots(A& a, std::vector<io::Snapshot>& snapshots) {
  long count = static_cast<long>(snapshots.size());
  a("count", count);
  if constexpr (A::loading) snapshots.assign(static_cast<std::size_t>(count), io::Snapshot{});
  for (long k = 0; k < count; ++k) {
    auto s = a.nested(std::to_string(k));
    io::Snapshot& snap = snapshots[k];
    long steps = snap.particle_steps, fields = static_cast<long>(snap.fields.size());
    s("time", snap.time), s("wall_seconds", snap.wall_seconds), s("particle_steps", steps);
    s("fields", fields);
    if constexpr (A::loading) snap.particle_steps = steps, snap.fields.resize(fields);
    for (long i = 0; i < fields; ++i) {
      io::Field& f = snap.fields[i];
      long components = f.components;
      auto fs = s.nested("field" + std::to_string(i));
      fs("name", f.name), fs("components", components);
      fs("values", f.values), fs("standard_error", f.standard_error);
      f.components = static_cast<int>(components);
    }
  }
}

// One particle run: set-up, the step loop with its samples, and the results. Everything that
// changes during the loop is listed once in archive(): a checkpoint holds exactly that.
template <class M> class ParticleRun {
public:
  static constexpr int D = M::D;
  using clock = std::chrono::steady_clock;

  ParticleRun(const M& model, const ParticleParameters& p)
      : model_(model), p_(p), sim_(model, p), n_(sim_.state().size()),
        hv_(-5 * std::sqrt(p.temperature / p.mass), 5 * std::sqrt(p.temperature / p.mass),
            p.histogram_bins),
        hu_(0, 3 * p.cv * p.temperature, p.histogram_bins), rdf_(p.rdf_bins, 0.0),
        tracked_(std::min<std::size_t>(n_, 1000)), vacf_(p.correlation_samples, 0.0),
        msd_(p.correlation_samples, 0.0), corr_count_(p.correlation_samples, 0.0),
        unwrapped_(tracked_ * D), last_wrapped_(tracked_ * D), index_of_(n_),
        total_steps_(p.equilibration_steps + p.steps),
        fields_(box3(), p.bins, p.blocks, sampled_rows(), p.mass, p.cv) {
    volume_ = 1;
    for (int d = 0; d < D; ++d) volume_ *= p.box[d];
    e0_ = sim_.total_energy();
    thermo_ = "# particle thermo: one row per sample. Units: m = k = rc = T0 = 1 (energies in k "
              "T0, time in tau)\n"
              "step,time,sampled,E_total,E_kinetic,E_internal,E_potential,T_kinetic,"
              "T_internal_harmonic,T_internal_mean,pressure,momentum_x,momentum_y,momentum_z\n";
    if (!p.heat_slabs.empty()) { // 0.5 rc bins along the slab direction
      std::array<int, 3> bins{{1, 1, 1}};
      const int dir = p.heat_slabs[0].direction;
      bins[dir] = std::max(4, static_cast<int>(std::lround(p.box[dir] / 0.5)));
      slab_profile_ =
          std::make_unique<FieldSampler<D>>(box3(), bins, p.blocks, sampled_rows(), p.mass, p.cv);
    }
    if constexpr (M::Heat::active)
      for (int d = 0; d < D; ++d) conduction_[d].assign(n_, 0.0);
    if (p.has_walls()) {
      std::array<bool, 3> walls{};
      for (int d = 0; d < D; ++d) walls[d] = p.walls[d].present;
      wall_layers_ = std::make_unique<WallLayerSampler<D>>(box3(), walls, p.wall_range, 20,
                                                           p.blocks, sampled_rows(), p.mass);
    }
  }

  template <class A> void archive(A& a) {
    auto s = a.nested("simulation");
    sim_.archive(s);
    a("step", step_), a("wall_seconds", wall_before_), a("e0", e0_), a("drift_max", drift_max_);
    a("thermo", thermo_);
    a("T_kinetic", s_tk_), a("T_internal", s_ti_), a("T_internal_mean", s_tm_);
    a("pressure", s_p_), a("energy", s_e_);
    a("hist_velocity", hv_.counts), a("hist_velocity_total", hv_.total);
    a("hist_energy", hu_.counts), a("hist_energy_total", hu_.total);
    a("rdf", rdf_), a("rdf_samples", rdf_samples_);
    a("vbuf", vbuf_), a("xbuf", xbuf_), a("vacf", vacf_), a("msd", msd_);
    a("corr_count", corr_count_), a("unwrapped", unwrapped_), a("last_wrapped", last_wrapped_);
    a("sample_count", sample_count_), a("fields_taken", fields_taken_);
    a("wall_last_momentum", wall_last_momentum_), a("wall_last_energy", wall_last_energy_);
    a("wall_last_step", wall_last_step_);
    a("wall_pressure", wall_pressure_), a("wall_heat_flux", wall_heat_flux_);
    a("relax_time", relax_time_), a("relax_amplitude", relax_amplitude_);
    a("shear_time", shear_time_), a("shear_amplitude", shear_amplitude_);
    auto f = a.nested("fields");
    fields_.archive(f);
    if (slab_profile_) {
      auto sp = a.nested("slab_profile");
      slab_profile_->archive(sp);
    }
    if (wall_layers_) {
      auto wl = a.nested("wall_layers");
      wall_layers_->archive(wl);
    }
    auto snaps = a.nested("snapshots");
    archive_snapshots(snaps, out_.field_snapshots);
  }

  RunOutput run(const RunControl& control) {
    if (control.resume) {
      LoadArchive a(*control.resume, "");
      archive(a);
    }
    t0_ = clock::now() -
          std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(wall_before_));
    auto last_progress = clock::now(), last_checkpoint = clock::now();
    while (step_ < total_steps_) {
      sim_.step();
      ++step_;
      if (step_ % p_.sample_interval == 0 || step_ == total_steps_) sample();
      if (control.progress && clock::now() - last_progress > std::chrono::seconds(2)) {
        last_progress = clock::now();
        progress_line();
      }
      const bool stop = control.stop_requested && control.stop_requested();
      const bool periodic = control.checkpoint_every_seconds > 0 &&
                            clock::now() - last_checkpoint >
                                std::chrono::duration<double>(control.checkpoint_every_seconds);
      if ((stop || periodic) && control.write_checkpoint && step_ < total_steps_) {
        wall_before_ = elapsed();
        io::Checkpoint c;
        SaveArchive a(c, "");
        archive(a);
        control.write_checkpoint(c);
        last_checkpoint = clock::now();
        if (stop) {
          if (control.progress) std::fprintf(stderr, "\n");
          out_.interrupted = true;
          out_.steps_done = step_;
          return std::move(out_);
        }
      }
    }
    if (control.progress) std::fprintf(stderr, "\n");
    finish();
    out_.steps_done = step_;
    return std::move(out_);
  }

private:
  std::array<double, 3> box3() const { return {{p_.box[0], p_.box[1], D == 3 ? p_.box[2] : 1.0}}; }
  long sampled_rows() const {
    long rows = 0;
    for (long step = p_.equilibration_steps + 1; step <= total_steps_; ++step)
      rows += step % p_.sample_interval == 0 || step == total_steps_;
    return rows;
  }
  double elapsed() const { return std::chrono::duration<double>(clock::now() - t0_).count(); }

  void progress_line() const {
    const double secs = elapsed();
    const double rate = step_ / std::max(secs, 1e-9); // includes earlier parts of a restart
    std::fprintf(stderr,
                 "\rstep %ld/%ld  t = %.2f  %.0f steps/s  ETA %.0f s  T = %.4f  dE/E = %.1e   ",
                 step_, total_steps_, step_ * p_.dt, rate, (total_steps_ - step_) / rate,
                 last_t_kinetic_, drift_max_);
  }

  void sample() {
    const auto& s = sim_.state();
    const double k = sim_.kinetic_energy(), u = sim_.internal_energy(),
                 pot = sim_.potential_energy();
    const double e = k + u + pot;
    double inflow = 0; // energy in through thermal walls: E(t) - E(0) - inflow is the error
    for (const double q : sim_.wall_energy_in()) inflow += q;
    drift_max_ = std::max(drift_max_, std::fabs(e - e0_ - inflow) / std::fabs(e0_));
    const double t_kin = 2 * k / (D * (n_ - 1.0)); // total momentum is conserved: d(N-1) dof
    last_t_kinetic_ = t_kin;
    double inv_theta = 0, mean_theta = 0;
    for (const double ui : s.u) inv_theta += model_.cv / ui, mean_theta += ui / model_.cv;
    const double t_int = s.u.empty() ? p_.temperature : n_ / inv_theta;
    mean_theta = s.u.empty() ? p_.temperature : mean_theta / n_;
    const bool sampled = step_ > p_.equilibration_steps;
    // One serial pass: virial pressure, g(r), and each particle's share of the conductive flux.
    double virial = 0;
    if constexpr (M::Heat::active)
      if (sampled)
        for (auto& c : conduction_) std::fill(c.begin(), c.end(), 0.0);
    sim_.grid().for_each_pair_serial(
        s, model_.rc, [&](std::size_t i, std::size_t j, const double* dx, double r2) {
          const double r = std::sqrt(r2);
          double th_i = 1, th_j = 1;
          if constexpr (M::has_energy) th_i = s.u[i] / model_.cv, th_j = s.u[j] / model_.cv;
          if constexpr (M::Conservative::active) {
            if (r < model_.conservative.rc) {
              double fc, phi;
              model_.conservative.eval(r, th_i, th_j, fc, phi);
              virial += r * fc; // r_ij . F^C_ij
            }
          }
          if (!sampled) return;
          const int b = static_cast<int>(r / model_.rc * rdf_.size());
          if (b < static_cast<int>(rdf_.size())) rdf_[b] += 1;
          if constexpr (M::Heat::active) {
            if (r < model_.heat.w.rc) { // the mean heat rate into i: its flux runs from j to i
              double rate, amplitude;
              model_.heat.eval(r, th_i, th_j, rate, amplitude);
              for (int d = 0; d < D; ++d) {
                conduction_[d][i] += 0.5 * rate * dx[d]; // Irving-Kirkwood, half to each end
                conduction_[d][j] += 0.5 * rate * dx[d];
              }
            }
          }
        });
    const double pressure = (2 * k + virial) / (D * volume_); // virial theorem, 000:(3.9)
    if (p_.has_walls()) wall_sample(sampled);
    if (M::has_energy && p_.temperature_perturbation != 0) {
      // The heat mode: the Fourier amplitude of the heat density e - h n (h = (E + p V)/N, the
      // enthalpy per particle), which decouples from sound and decays as exp(-chi k^2 t) in
      // linear hydrodynamics; the temperature mode alone rides on sound waves.
      const double h = e / n_ + pressure * volume_ / n_;
      const auto& phi = sim_.carried().potential;
      double a = 0;
      for (std::size_t i = 0; i < n_; ++i) {
        double ei = s.u[i] + phi[i];
        for (int d = 0; d < D; ++d) ei += 0.5 * model_.mass * s.v[d][i] * s.v[d][i];
        a += (ei - h) * std::sin(2 * M_PI * s.x[0][i] / p_.box[0]);
      }
      relax_time_.push_back(step_ * p_.dt), relax_amplitude_.push_back(2 * a / n_);
    }
    if (p_.shear_perturbation != 0) {
      // The transverse momentum mode: decoupled from sound and heat, it decays as exp(-nu k^2 t).
      double b = 0;
      for (std::size_t i = 0; i < n_; ++i)
        b += model_.mass * s.v[1][i] * std::sin(2 * M_PI * s.x[0][i] / p_.box[0]);
      shear_time_.push_back(step_ * p_.dt), shear_amplitude_.push_back(2 * b / n_);
    }
    std::array<double, 3> mom{0, 0, 0};
    for (int d = 0; d < D; ++d)
      for (const double v : s.v[d]) mom[d] += model_.mass * v;
    char row[512];
    std::snprintf(row, sizeof row,
                  "%ld,%.6f,%d,%.17g,%.17g,%.17g,%.17g,%.10g,%.10g,%.10g,%.10g,%.3e,%.3e,%.3e\n",
                  step_, step_ * p_.dt, sampled ? 1 : 0, e, k, u, pot, t_kin, t_int, mean_theta,
                  pressure, mom[0], mom[1], mom[2]);
    thermo_ += row;
    if (!sampled) return;
    const auto& potential = sim_.carried().potential;
    fields_.sample(s, potential, conduction_);
    if (slab_profile_) slab_profile_->sample(s, potential, conduction_);
    if (wall_layers_) wall_layers_->sample(s);
    ++fields_taken_;
    const long rows = fields_.total_samples();
    if (fields_taken_ == rows || fields_taken_ % std::max(1L, rows / 10) == 0)
      out_.field_snapshots.push_back(
          snapshot(fields_.result(), step_ * p_.dt, elapsed(), static_cast<long>(n_) * step_));
    s_tk_.push_back(t_kin), s_ti_.push_back(t_int), s_tm_.push_back(mean_theta);
    s_p_.push_back(pressure), s_e_.push_back(e);
    ++rdf_samples_;
    for (int d = 0; d < D; ++d)
      for (const double v : s.v[d]) hv_.add(v);
    for (const double ui : s.u) hu_.add(ui);
    correlations();
  }

  // Per wall, over the interval since the last sample: pressure (momentum in per time and area)
  // and heat flux density in.
  void wall_sample(bool sampled) {
    const double interval = (step_ - wall_last_step_) * p_.dt;
    for (int w = 0; w < 2 * D; ++w) {
      if (!p_.walls[w / 2].present) continue;
      double area = 1;
      for (int d = 0; d < D; ++d)
        if (d != w / 2) area *= p_.box[d];
      const double dp = sim_.wall_momentum_in()[w] - wall_last_momentum_[w];
      const double dq = sim_.wall_energy_in()[w] - wall_last_energy_[w];
      if (sampled) {
        wall_pressure_[w].push_back(dp / (interval * area));
        wall_heat_flux_[w].push_back(dq / (interval * area));
      }
      wall_last_momentum_[w] = sim_.wall_momentum_in()[w];
      wall_last_energy_[w] = sim_.wall_energy_in()[w];
    }
    wall_last_step_ = step_;
  }

  // VACF / MSD of up to 1000 tracked particles (ids 0..), over a window of samples.
  void correlations() {
    const auto& s = sim_.state();
    const int window = p_.correlation_samples;
    for (std::size_t i = 0; i < n_; ++i) index_of_[s.id[i]] = i;
    std::vector<double> vs(tracked_ * D), xs(tracked_ * D);
    for (std::size_t t = 0; t < tracked_; ++t) {
      const std::size_t i = index_of_[t];
      for (int d = 0; d < D; ++d) {
        vs[t * D + d] = s.v[d][i];
        double dx = s.x[d][i] - last_wrapped_[t * D + d];
        if (sample_count_ > 0)
          dx = sim_.grid().minimum_image(dx, d);
        else
          dx = 0, unwrapped_[t * D + d] = s.x[d][i];
        unwrapped_[t * D + d] += dx;
        last_wrapped_[t * D + d] = s.x[d][i];
        xs[t * D + d] = unwrapped_[t * D + d];
      }
    }
    vbuf_.push_back(std::move(vs)), xbuf_.push_back(std::move(xs));
    if (static_cast<int>(vbuf_.size()) > window)
      vbuf_.erase(vbuf_.begin()), xbuf_.erase(xbuf_.begin());
    const std::size_t last = vbuf_.size() - 1;
    for (std::size_t lag = 0; lag <= last; ++lag) {
      const auto &v0 = vbuf_[last - lag], &v1 = vbuf_[last], &x0 = xbuf_[last - lag],
                 &x1 = xbuf_[last];
      double cv = 0, dr = 0;
      for (std::size_t k = 0; k < tracked_ * D; ++k) {
        cv += v0[k] * v1[k];
        dr += (x1[k] - x0[k]) * (x1[k] - x0[k]);
      }
      vacf_[lag] += cv / tracked_, msd_[lag] += dr / tracked_, corr_count_[lag] += 1;
    }
    ++sample_count_;
  }

  void finish() {
    const double wall = elapsed();
    io::Json& j = out_.summary;
    j = io::Json::object();
    j["N"] = static_cast<long>(n_);
    j["dim"] = D;
    j["steps"] = p_.steps;
    j["equilibration_steps"] = p_.equilibration_steps;
    j["dt"] = p_.dt;
    j["integrator"] = to_string(p_.integrator);
    j["energy_offset"] = p_.energy_offset;
    j["wall_seconds"] = wall;
    j["particle_steps_per_second"] = n_ * static_cast<double>(total_steps_) / wall;
    // |E(t) - E(0) - energy in through walls| / E(0): the integrator's energy error
    j["energy_relative_drift_max"] = drift_max_;
    auto put = [&](const std::string& key, const std::vector<double>& series) {
      const Estimate e = block_average(series, p_.blocks);
      j[key] = e.mean;
      j[key + "_stderr"] = e.stderr_;
    };
    put("T_kinetic", s_tk_);
    put("T_internal", s_ti_);
    put("T_internal_mean_theta", s_tm_);
    put("pressure", s_p_);
    if (M::has_energy && !M::Conservative::active && !p_.has_walls())
      j["T_energy_equation_of_state"] = ideal_dpde_temperature(p_, e0_ / n_); // 000:(3.21)
    if (p_.has_walls()) {
      io::Json walls = io::Json::object();
      const char* names[6] = {"x_lower", "x_upper", "y_lower", "y_upper", "z_lower", "z_upper"};
      const double time = total_steps_ * p_.dt;
      for (int w = 0; w < 2 * D; ++w) {
        if (!p_.walls[w / 2].present) continue;
        walls[names[w]]["energy_in"] = sim_.wall_energy_in()[w];
        walls[names[w]]["mean_heat_flow_in"] = sim_.wall_energy_in()[w] / time; // per time
        // Over the sampled steps, with block errors:
        const Estimate pw = block_average(wall_pressure_[w], p_.blocks);
        const Estimate jw = block_average(wall_heat_flux_[w], p_.blocks);
        walls[names[w]]["pressure"] = pw.mean, walls[names[w]]["pressure_stderr"] = pw.stderr_;
        walls[names[w]]["heat_flux_in"] = jw.mean;
        walls[names[w]]["heat_flux_in_stderr"] = jw.stderr_;
        // The same with 2 and 4 blocks merged: equal errors say the blocks are long enough.
        walls[names[w]]["heat_flux_in_stderr_blocking"] =
            blocking_errors(wall_heat_flux_[w], p_.blocks);
      }
      if (wall_layers_) {
        // A no-slip wall's friction on a particle's tangential velocity, gamma w_D(h), as the
        // wall sweep applies it: the run's friction law against a wall particle at the wall's
        // temperature (adiabatic: the particle's own), with the wall's weight.
        auto wall_friction = model_.friction;
        wall_friction.w = Weight(p_.wall_range, p_.dissipation.exponent);
        const auto friction = [&](int wall, double T, double h) {
          const WallPair& pair = p_.walls[wall / 2];
          if (!pair.no_slip || !(T > 0)) return 0.0;
          double w, sqrt_w;
          wall_friction.w.eval(h, w, sqrt_w);
          const double Tw = pair.thermal[wall % 2] ? pair.temperature[wall % 2] : T;
          return wall_friction.ito_gamma(T, Tw) * w; // 000:(2.37), 003
        };
        const auto layers = wall_layers_->result(friction);
        for (const auto& l : layers) {
          io::Json& w = walls[names[l.wall]];
          w["effective_position"] = l.effective_position; // Gibbs depth from the wall plane
          w["effective_position_stderr"] = l.effective_position_stderr;
          w["layer_reference_density"] = l.reference;
          w["layer_reference_density_stderr"] = l.reference_stderr;
          if (p_.walls[l.wall / 2].no_slip) {
            w["friction_per_area"] = l.friction; // tangential force / (area x slip velocity)
            w["friction_per_area_stderr"] = l.friction_stderr;
            w["friction_depth"] = l.friction_depth;
          }
        }
        out_.wall_layers_csv = WallLayerSampler<D>::csv(layers, D);
      }
      j["walls"] = walls;
      j["wall_reflections"] = sim_.wall_crossings();
    }
    j["samples"] = static_cast<long>(s_tk_.size());
    j["blocks"] = p_.blocks;
    j["stability_hint"] = stability_hint(p_);

    std::ostringstream h;
    h << "# histograms over sampled steps; velocity in sqrt(k T0/m), internal energy in k T0\n"
         "quantity,bin_centre,probability_density\n";
    for (int b = 0; b < p_.histogram_bins; ++b)
      h << "velocity_component," << hv_.lo + (b + 0.5) * hv_.width() << "," << hv_.density(b)
        << "\n";
    if (M::has_energy)
      for (int b = 0; b < p_.histogram_bins; ++b)
        h << "internal_energy," << hu_.lo + (b + 0.5) * hu_.width() << "," << hu_.density(b)
          << "\n";
    out_.histograms_csv = h.str();

    std::ostringstream g;
    g << "# pair distribution function g(r) for r < the largest cutoff; r in rc\nr,g\n";
    const double dr = model_.rc / rdf_.size();
    for (std::size_t b = 0; b < rdf_.size(); ++b) {
      const double r0 = b * dr, r1 = r0 + dr;
      const double shell =
          D == 3 ? 4.0 / 3.0 * M_PI * (r1 * r1 * r1 - r0 * r0 * r0) : M_PI * (r1 * r1 - r0 * r0);
      const double ideal = 0.5 * n_ * (n_ / volume_) * shell * std::max<long>(rdf_samples_, 1);
      g << r0 + 0.5 * dr << "," << rdf_[b] / ideal << "\n";
    }
    out_.rdf_csv = g.str();

    std::ostringstream c;
    c << "# velocity autocorrelation <v(0).v(t)> (k T0/m) and mean-square displacement (rc^2), "
         "averaged over time origins and "
      << tracked_ << " particles\ntime,vacf,msd\n";
    for (int lag = 0; lag < p_.correlation_samples; ++lag)
      if (corr_count_[lag] > 0)
        c << lag * p_.sample_interval * p_.dt << "," << vacf_[lag] / corr_count_[lag] << ","
          << msd_[lag] / corr_count_[lag] << "\n";
    out_.correlations_csv = c.str();
    out_.thermo_csv = thermo_;
    if (!relax_time_.empty())
      j["relaxation"] = heat_relaxation_fit(p_, relax_time_, relax_amplitude_);
    if (!shear_time_.empty())
      j["shear_relaxation"] = shear_relaxation_fit(p_, shear_time_, shear_amplitude_);
    if (!relax_time_.empty() || !shear_time_.empty()) {
      // Both modes are sampled at the same steps; a column is empty when its mode is absent.
      std::ostringstream r;
      r << "# heat mode: (2/N) sum (e_i - h) sin(2 pi x_i / Lx), e_i = u_i + K_i + phi_i, h = (E + "
           "p V)/N; shear mode: (2/N) sum m v_y,i sin(2 pi x_i / Lx)\n"
           "time,amplitude,shear_amplitude\n";
      const std::vector<double>& time = relax_time_.empty() ? shear_time_ : relax_time_;
      for (std::size_t k = 0; k < time.size(); ++k) {
        r << time[k] << ",";
        if (k < relax_amplitude_.size()) r << relax_amplitude_[k];
        r << ",";
        if (k < shear_amplitude_.size()) r << shear_amplitude_[k];
        r << "\n";
      }
      out_.relaxation_csv = r.str();
    }
    const BinnedFields final_fields = fields_.result(); // reduced over the blocks once
    out_.fields_csv = final_fields.csv();
    out_.blocks_csv = final_fields.blocks_csv();
    out_.field_grid.dim = D;
    for (int d = 0; d < D; ++d) {
      out_.field_grid.counts[d] = p_.bins[d];
      out_.field_grid.spacing[d] = p_.box[d] / p_.bins[d];
    }
    if (p_.poiseuille_force != 0) j["poiseuille"] = poiseuille_fit(p_, final_fields);
    if (p_.has_walls()) {
      const io::Json profile = wall_profile_fit(p_, final_fields);
      if (!profile.is_null()) j["wall_profile"] = profile;
    }
    if (slab_profile_) {
      const BinnedFields profile = slab_profile_->result();
      out_.slab_profile_csv = profile.csv();
      if (M::has_energy && p_.heat_slabs.size() == 2) {
        j["heat_slabs"] = slab_fit(p_, profile);
        const double j0 = j["heat_slabs"]["J0"].get<double>();
        j["heat_slabs"]["flux_decomposition"] = flux_at_planes(p_, profile, j0);
      }
    }
  }

  M model_;
  ParticleParameters p_;
  Simulation<M> sim_;
  std::size_t n_;
  double volume_ = 1, e0_ = 0, drift_max_ = 0, last_t_kinetic_ = 0, wall_before_ = 0;
  std::string thermo_;
  std::vector<double> s_tk_, s_ti_, s_tm_, s_p_, s_e_;
  Histogram hv_, hu_;
  std::vector<double> rdf_;
  long rdf_samples_ = 0;
  std::size_t tracked_;
  std::vector<std::vector<double>> vbuf_, xbuf_; // ring buffers [sample][tracked * D]
  std::vector<double> vacf_, msd_, corr_count_, unwrapped_, last_wrapped_;
  std::vector<std::size_t> index_of_;
  long sample_count_ = 0, fields_taken_ = 0, step_ = 0, total_steps_;
  FieldSampler<D> fields_;
  std::unique_ptr<FieldSampler<D>> slab_profile_;
  std::unique_ptr<WallLayerSampler<D>> wall_layers_; // walled scenes
  std::array<std::vector<double>, D> conduction_;    // per particle, at the current sample
  std::array<double, 6> wall_last_momentum_{}, wall_last_energy_{};
  long wall_last_step_ = 0;
  std::vector<double> relax_time_, relax_amplitude_;
  std::vector<double> shear_time_, shear_amplitude_;
  std::vector<std::vector<double>> wall_pressure_ = std::vector<std::vector<double>>(6),
                                   wall_heat_flux_ = std::vector<std::vector<double>>(6);
  clock::time_point t0_;
  RunOutput out_;
};

template <class M>
RunOutput drive(const M& model, const ParticleParameters& p, const RunControl& control) {
  return ParticleRun<M>(model, p).run(control);
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
    const long builds = sim.pair_list_builds();
    const auto t0 = std::chrono::steady_clock::now();
    for (long s = 0; s < steps; ++s) sim.step();
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    BenchResult r;
    r.particles = static_cast<long>(sim.state().size());
    r.seconds = secs;
    r.particle_steps_per_second = r.particles * static_cast<double>(steps) / secs;
    r.steps_per_list = static_cast<double>(steps) / std::max(1L, sim.pair_list_builds() - builds);
    // Resident per-particle arrays: state (x, v, u, id), carried (f, q, potential), the sort's
    // cell index and permutation, and the sort's temporary copy of the largest array.
    r.bytes_per_particle =
        (2 * M::D + (M::has_energy ? 1 : 0)) * 8 + 4 + (M::D + 2) * 8 + 4 + 4 + 8;
    return r;
  });
}

} // namespace twinflow::particle
