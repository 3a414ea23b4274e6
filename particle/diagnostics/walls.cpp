#include "particle/diagnostics/walls.hpp"

#include <algorithm>

#include "statistics/blocking.hpp"
#include "statistics/line_fit.hpp"

namespace twinflow::particle {

const char* wall_name(int wall) {
  static const char* names[6] = {"x_lower", "x_upper", "y_lower", "y_upper", "z_lower", "z_upper"};
  return names[wall];
}

template <int D> WallFluxes<D>::WallFluxes(const ParticleParameters& p) : p_(p) {}

template <int D> void WallFluxes<D>::sample(const Sample<D>& s) {
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
}

template <int D> void WallFluxes<D>::finish(RunOutput& out) {
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
  }
  out.summary["walls"] = walls;
  out.summary["wall_reflections"] = crossings_;
}

template <int D>
WallLayers<D>::WallLayers(const ParticleParameters& p, const RunFacts& m)
    : p_(p), friction_(m.wall_friction),
      sampler_(box3(p), {{p.walls[0].present, p.walls[1].present, D == 3 && p.walls[2].present}},
               p.wall_range, 20, p.blocks, sampled_count(p), p.mass) {}

template <int D> void WallLayers<D>::sample(const Sample<D>& s) {
  if (s.sampled) sampler_.sample(s.state);
}

template <int D> void WallLayers<D>::finish(RunOutput& out) {
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

template <int D> void WallProfileFit<D>::finish(RunOutput& out) {
  const BinnedFields& f = fields_.result();
  const int d = direction_;
  const WallPair& w = p_.walls[d];
  const double length = p_.box[d], lo = 0.2 * length, hi = 0.8 * length;
  const auto line = [&](const std::vector<double>& temperature) {
    statistics::LineFit fit;
    for (int bin = 0; bin < f.bin_count(); ++bin) {
      const double x = f.centre(bin, d);
      if (x >= lo && x <= hi) fit.add(x, temperature[bin], f.temperature_internal.stderr_[bin]);
    }
    return fit;
  };
  const statistics::LineFit fit = line(f.temperature_internal.mean);
  // The slope's error from the blocks' own slopes (the same weights, so their mean is the
  // slope): the bins share the profile's slow fluctuations, which the fit's error, over
  // independent bins, leaves out. With 2 and 4 blocks merged too; the largest is stated.
  std::vector<double> block_slopes;
  for (const auto& block : f.temperature_internal_blocks)
    block_slopes.push_back(line(block).slope());
  const std::vector<double> blocking =
      statistics::blocking_errors(block_slopes, static_cast<int>(block_slopes.size()));
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
  out.summary["wall_profile"] = j;
}

template class WallFluxes<2>;
template class WallFluxes<3>;
template class WallLayers<2>;
template class WallLayers<3>;
template class WallProfileFit<2>;
template class WallProfileFit<3>;

} // namespace twinflow::particle
