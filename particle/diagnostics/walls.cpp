// Walled scenes: each wall's pressure and heat flux (WallFluxes), the fluid layer along it
// (WallLayers: effective position, friction), and the Kapitza fit of a conducting pair of thermal
// walls (wall_profile_fit, from the binned fields).
#include "particle/diagnostics/plugins.hpp"

#include <algorithm>

#include "statistics/blocking.hpp"
#include "statistics/line_fit.hpp"

namespace twinflow::particle {

namespace {

// "x_lower", "x_upper", "y_lower", ... for wall 2 d + side.
const char* wall_name(int wall) {
  static const char* names[6] = {"x_lower", "x_upper", "y_lower", "y_upper", "z_lower", "z_upper"};
  return names[wall];
}

// Per wall, over the interval since the last sample: pressure (momentum in per time and area) and
// heat flux density in; the energy in since the start.
template <int D> class WallFluxes : public Archived<D, WallFluxes<D>> {
public:
  explicit WallFluxes(const ParticleParameters& p)
      : Archived<D, WallFluxes<D>>("wall_fluxes"), p_(p) {}
  void sample(const Sample<D>& s) override {
    const double interval = (s.step - last_step_) * p_.dt;
    for (int w = 0; w < 2 * D; ++w) {
      if (!p_.walls[w / 2].present) continue;
      double area = 1;
      for (int d = 0; d < D; ++d)
        if (d != w / 2) area *= p_.box[d];
      const double dp = s.wall_momentum_in[w] - last_momentum_[w];
      const double dq = s.wall_energy_in[w] - last_energy_[w];
      if (s.sampled) {
        pressure_[w].push_back(dp / (interval * area));
        heat_flux_[w].push_back(dq / (interval * area));
      }
      last_momentum_[w] = s.wall_momentum_in[w];
      last_energy_[w] = s.wall_energy_in[w];
    }
    last_step_ = s.step;
    crossings_ = s.wall_crossings;
    heat_moves_ = s.wall_heat_moves;
  }
  void finish(RunOutput& out) override {
    io::Json walls = io::Json::object();
    const double time = (p_.equilibration_steps + p_.steps) * p_.dt;
    for (int w = 0; w < 2 * D; ++w) {
      if (!p_.walls[w / 2].present) continue;
      io::Json& j = walls[wall_name(w)];
      // The last sample is the last step: its totals are the run's.
      j["energy_in"] = last_energy_[w];
      j["mean_heat_flow_in"] = last_energy_[w] / time; // per time
      // Over the sampled steps, with block errors:
      const statistics::Estimate pw = statistics::block_average(pressure_[w], p_.blocks);
      const statistics::Estimate jw = statistics::block_average(heat_flux_[w], p_.blocks);
      j["pressure"] = pw.mean, j["pressure_stderr"] = pw.stderr_;
      j["heat_flux_in"] = jw.mean;
      j["heat_flux_in_stderr"] = jw.stderr_;
      // The same with 2 and 4 blocks merged: equal errors say the blocks are long enough.
      j["heat_flux_in_stderr_blocking"] = statistics::blocking_errors(heat_flux_[w], p_.blocks);
      // The wall's heat exchange (a thermal half-space wall): its Metropolis moves accepted.
      if (heat_moves_[w] > 0) {
        j["heat_moves_proposed"] = heat_moves_[w];
        j["heat_moves_acceptance"] = heat_moves_[6 + w] / heat_moves_[w];
      }
    }
    out.summary["walls"] = walls;
    // The heat flow across each pair of walls with a thermal one, from lower to upper. Its
    // error comes from the block means of the one series: the two walls' block fluxes are
    // correlated (a stronger roll feeds both), so adding their errors in quadrature is wrong.
    io::Json pairs = io::Json::object();
    for (int d = 0; d < D; ++d) {
      const WallPair& pair = p_.walls[d];
      if (!pair.present || !(pair.thermal[0] || pair.thermal[1])) continue;
      const std::vector<double>&lo = heat_flux_[2 * d], &up = heat_flux_[2 * d + 1];
      std::vector<double> across(lo.size());
      for (std::size_t k = 0; k < lo.size(); ++k) across[k] = 0.5 * (lo[k] - up[k]);
      const statistics::Estimate e = statistics::block_average(across, p_.blocks);
      const std::vector<double> levels = statistics::blocking_errors(across, p_.blocks);
      io::Json& j = pairs[std::string(1, "xyz"[d])];
      j["heat_flux"] = e.mean;
      double stderr_ = e.stderr_; // the largest over the blockings, as for one wall
      for (const double x : levels) stderr_ = std::max(stderr_, x);
      j["heat_flux_stderr"] = stderr_;
      j["heat_flux_stderr_blocking"] = levels;
      // the upper wall's inflow taken as an outflow: +1, the two walls' flows rise and fall
      // together
      j["wall_block_correlation"] = -statistics::block_correlation(lo, up, p_.blocks);
    }
    out.summary["wall_pairs"] = pairs;
    out.summary["wall_reflections"] = crossings_;
  }
  template <class A> void archive(A& a) {
    a("last_momentum", last_momentum_), a("last_energy", last_energy_);
    a("last_step", last_step_), a("crossings", crossings_), a("heat_moves", heat_moves_);
    a("pressure", pressure_), a("heat_flux", heat_flux_);
  }

private:
  ParticleParameters p_;
  std::array<double, 6> last_momentum_{}, last_energy_{}; // at the last sample
  long last_step_ = 0, crossings_ = 0;
  std::array<double, 12> heat_moves_{}; // as the simulation counted them at the last sample
  std::vector<std::vector<double>> pressure_ = std::vector<std::vector<double>>(6),
                                   heat_flux_ = std::vector<std::vector<double>>(6);
};

// Density and velocity in thin slices along each wall (wall_layers.csv) and, into the summary's
// "walls", each wall's effective position and, for no-slip walls, its friction.
template <int D> class WallLayers : public Archived<D, WallLayers<D>> {
public:
  WallLayers(const ParticleParameters& p, const RunFacts& m)
      : Archived<D, WallLayers<D>>("wall_layers"), p_(p), friction_(m.wall_friction),
        sampler_(box3(p), {{p.walls[0].present, p.walls[1].present, D == 3 && p.walls[2].present}},
                 p.wall_range, 20, p.blocks, sampled_count(p), p.mass, p.cv) {}
  void sample(const Sample<D>& s) override {
    if (s.sampled) sampler_.sample(s.state);
  }
  void finish(RunOutput& out) override {
    const auto layers = sampler_.result(friction_);
    for (const auto& l : layers) {
      io::Json& w = out.summary["walls"][wall_name(l.wall)];
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
    out.wall_layers_csv = WallLayerSampler<D>::csv(layers, D);
  }
  template <class A> void archive(A& a) { sampler_.archive(a); }

private:
  ParticleParameters p_;
  std::function<double(int, double, double)> friction_;
  WallLayerSampler<D> sampler_;
};

} // namespace

int wall_profile_direction(const ParticleParameters& p) {
  for (int d = 0; d < p.dim; ++d) {
    const WallPair& w = p.walls[d];
    if (!w.present || !w.thermal[0] || !w.thermal[1] || p.bins[d] < 5) continue;
    bool one_d = true;
    for (int e = 0; e < p.dim; ++e) one_d &= e == d || p.bins[e] == 1;
    if (one_d) return d;
  }
  return -1;
}

io::Json wall_profile_fit(const ParticleParameters& p, int direction, const BinnedFields& f) {
  const int d = direction;
  const WallPair& w = p.walls[d];
  const double length = p.box[d], centre = 0.5 * length;
  // Parabolas, not lines: the flux q = -kappa(T) T' is the same everywhere, so T'' =
  // -(kappa'/kappa) T'^2 (Fourier's law with kappa(T)), and a line through a bent profile, carried
  // to the walls, puts the bend into the jumps (seed 002's fluid between 1.2 and 0.8: 2-3% of dT).
  // Two fits: the slope at the centre (kappa at the middle temperature) from the central 60%;
  // the wall values from the whole bulk, beyond the wall layer (one cutoff, the reach of the
  // wall's pair terms), carried across that layer only.
  const double lo = 0.2 * length, hi = 0.8 * length;
  const double layer = std::min(p.largest_cutoff(), 0.25 * length);
  const auto parabola = [&](const std::vector<double>& temperature, double from, double to) {
    statistics::QuadraticFit fit(centre);
    for (int bin = 0; bin < f.bin_count(); ++bin) {
      const double x = f.centre(bin, d);
      if (x >= from && x <= to) fit.add(x, temperature[bin], f.temperature_internal.stderr_[bin]);
    }
    return fit;
  };
  const statistics::QuadraticFit middle = parabola(f.temperature_internal.mean, lo, hi);
  const statistics::QuadraticFit bulk =
      parabola(f.temperature_internal.mean, layer, length - layer);
  // The errors from the blocks' own fits (the same weights, so their mean is the fit): the bins
  // share the profile's slow fluctuations, which the fit's error, over independent bins, leaves
  // out. With 2 and 4 blocks merged too; the largest is stated.
  std::vector<double> block_slopes, block_lower, block_upper; // the slope and the wall values
  for (const auto& block : f.temperature_internal_blocks) {
    block_slopes.push_back(parabola(block, lo, hi).slope(centre));
    const statistics::QuadraticFit b = parabola(block, layer, length - layer);
    block_lower.push_back(b.value(0)), block_upper.push_back(b.value(length));
  }
  const auto largest = [](double fit_se, const std::vector<double>& levels) {
    for (const double se : levels) fit_se = std::max(fit_se, se);
    return fit_se;
  };
  const std::vector<double> slope_levels = statistics::merged_blocking_errors(block_slopes);
  io::Json j = io::Json::object();
  j["direction"] = d;
  j["fit_from"] = lo, j["fit_to"] = hi;
  j["slope"] = middle.slope(centre);
  j["slope_stderr"] = largest(middle.slope_stderr(centre), slope_levels);
  j["slope_stderr_fit"] = middle.slope_stderr(centre);
  j["slope_stderr_blocking"] = slope_levels;
  j["temperature_at_centre"] = middle.value(centre);
  j["curvature"] = middle.curvature(), j["curvature_stderr_fit"] = middle.curvature_stderr();
  j["jump_fit_from"] = layer, j["jump_fit_to"] = length - layer;
  j["jump_lower"] = w.temperature[0] - bulk.value(0);
  j["jump_upper"] = w.temperature[1] - bulk.value(length);
  j["jump_lower_stderr"] =
      largest(bulk.value_stderr(0), statistics::merged_blocking_errors(block_lower));
  j["jump_upper_stderr"] =
      largest(bulk.value_stderr(length), statistics::merged_blocking_errors(block_upper));
  j["jump_lower_stderr_fit"] = bulk.value_stderr(0);
  j["jump_upper_stderr_fit"] = bulk.value_stderr(length);
  return j;
}

template <int D> DiagnosticPtr<D> make_wall_fluxes(const ParticleParameters& p) {
  return std::make_unique<WallFluxes<D>>(p);
}

template <int D> DiagnosticPtr<D> make_wall_layers(const ParticleParameters& p, const RunFacts& m) {
  return std::make_unique<WallLayers<D>>(p, m);
}

template DiagnosticPtr<2> make_wall_fluxes<2>(const ParticleParameters&);
template DiagnosticPtr<3> make_wall_fluxes<3>(const ParticleParameters&);
template DiagnosticPtr<2> make_wall_layers<2>(const ParticleParameters&, const RunFacts&);
template DiagnosticPtr<3> make_wall_layers<3>(const ParticleParameters&, const RunFacts&);

} // namespace twinflow::particle
