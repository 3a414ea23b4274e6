// Heat-slab scenes (seed 002 section III.B): the profile along the slab direction in 0.5 rc bins
// (slab_profile.csv), and kappa from its slopes between the slabs with the energy flux split
// into its parts at two planes (SlabKappaFit).
#include "particle/diagnostics/plugins.hpp"
#include "particle/fields.hpp"

#include <algorithm>
#include <cmath>

#include "statistics/blocking.hpp"
#include "statistics/line_fit.hpp"

namespace twinflow::particle {

namespace {

std::array<int, 3> slab_bins(const ParticleParameters& p) { // 0.5 rc along the slab direction
  std::array<int, 3> bins{{1, 1, 1}};
  const int dir = p.heat_slabs[0].direction;
  bins[dir] = std::max(4, static_cast<int>(std::lround(p.box[dir] / 0.5)));
  return bins;
}

// One half between the slabs, from `a` to `b` along the slab direction.
struct HalfFit {
  double slope = 0, kappa = 0, kappa_fit_se = 0;
  std::vector<double> block_slopes;
  io::Json json;
};

// Seed 002 section III.B: a linear fit of T_internal(x) in the central 60% of the half;
// kappa = J0 / |dT/dx|.
HalfFit half_fit(const BinnedFields& f, int dir, double length, double a, double b, double j0) {
  if (b <= a) b += length; // the half wraps around the periodic box
  const double lo = a + 0.2 * (b - a), hi = b - 0.2 * (b - a);
  // The same weights for the mean profile and each block's, so that the blocks' slopes
  // average to the mean profile's (the fit is linear in the temperatures).
  const auto line = [&](const std::vector<double>& temperature) {
    statistics::LineFit fit;
    for (int bin = 0; bin < f.bin_count(); ++bin) {
      double x = f.centre(bin, dir);
      if (x < a) x += length;
      if (x >= lo && x <= hi) fit.add(x, temperature[bin], f.temperature_internal.stderr_[bin]);
    }
    return fit;
  };
  HalfFit h;
  const statistics::LineFit fit = line(f.temperature_internal.mean);
  for (const auto& block : f.temperature_internal_blocks)
    h.block_slopes.push_back(line(block).slope());
  h.slope = fit.slope();
  const double slope_fit_se = fit.slope_stderr();
  h.kappa = j0 / std::fabs(h.slope);
  h.kappa_fit_se = h.kappa * slope_fit_se / std::fabs(h.slope);
  // The half's own error, from its blocks' slopes (1, 2, 4 blocks merged, the largest): the
  // bins share the profile's slow modes, which the fit over independent bins leaves out.
  double slope_se = slope_fit_se;
  const auto levels = statistics::merged_blocking_errors(h.block_slopes);
  for (const double se : levels) slope_se = std::max(slope_se, se);
  h.json = io::Json::object();
  h.json["fit_from"] = lo, h.json["fit_to"] = hi;
  h.json["slope"] = h.slope, h.json["slope_stderr"] = slope_se;
  h.json["intercept"] = fit.intercept();
  h.json["slope_stderr_fit"] = slope_fit_se, h.json["slope_stderr_blocking"] = levels;
  h.json["kappa"] = h.kappa;
  h.json["kappa_stderr"] = h.kappa * slope_se / std::fabs(h.slope);
  return h;
}

// kappa from both halves, weighted by their fit errors (fixed weights: the combination is then
// a fixed function of the two slopes). Its error from the same combination block by block,
// linearised about the means (kappa_b = kappa (2 - |s_b| / |s|) per half, the delta method):
// the slowest profile mode steepens one half and flattens the other, so the halves'
// fluctuations partly cancel, which their errors taken as independent would miss.
void combine_halves(const HalfFit (&halves)[2], io::Json& out) {
  double wsum = 0, ksum = 0;
  double weight[2];
  for (int half = 0; half < 2; ++half) {
    weight[half] = 1 / (halves[half].kappa_fit_se * halves[half].kappa_fit_se);
    wsum += weight[half], ksum += weight[half] * halves[half].kappa;
  }
  std::vector<double> block_kappa(halves[0].block_slopes.size(), 0.0);
  for (std::size_t b = 0; b < block_kappa.size(); ++b)
    for (int half = 0; half < 2; ++half) {
      const HalfFit& h = halves[half];
      block_kappa[b] +=
          weight[half] / wsum * h.kappa * (2 - std::fabs(h.block_slopes[b]) / std::fabs(h.slope));
    }
  const auto levels = statistics::merged_blocking_errors(block_kappa);
  double kappa_se = 1 / std::sqrt(wsum);
  out["kappa_stderr_fit"] = kappa_se;
  for (const double se : levels) kappa_se = std::max(kappa_se, se);
  out["kappa"] = ksum / wsum;
  out["kappa_stderr"] = kappa_se;
  out["kappa_stderr_blocking"] = levels;
}

// Seed 002 section III.B: kappa from both halves between the slabs, J0 = power / (2 A).
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
  const HalfFit halves[2] = {half_fit(f, dir, length, hot.upper, cold.lower, j0),
                             half_fit(f, dir, length, cold.upper, hot.lower, j0)};
  out["hot_to_cold"] = halves[0].json;
  out["cold_to_hot"] = halves[1].json;
  combine_halves(halves, out);
  // Blocks must outlast the slowest profile mode that moves kappa: the fundamental of the
  // periodic profile, k = 2 pi / L, decays in 1 / (chi k^2), chi = kappa / (rho c), c = c_v + 1
  // + d/2 per particle (000:(3.21), kinetic part d/2). The stated error holds when the longest
  // merged block (4 blocks) is a few decay times (docs/validation.md, "Error bars over seeds").
  const double k = 2 * M_PI / length;
  const double chi = out["kappa"].get<double>() / (p.density * (p.cv + 1 + 0.5 * p.dim));
  const double block_time = p.steps * p.dt / p.blocks;
  out["slowest_mode_decay_time"] = 1 / (chi * k * k);
  out["block_time"] = block_time;
  out["longest_merged_block_over_decay_time"] = 4 * block_time * chi * k * k;
  return out;
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

template <int D> class SlabProfile : public Archived<D, SlabProfile<D>> {
public:
  SlabProfile(const ParticleParameters& p, const RunFacts&)
      : Archived<D, SlabProfile<D>>("slab_profile", {false, true}),
        sampler_(box3(p), slab_bins(p), p.blocks, sampled_count(p), p.mass, p.cv) {}
  void sample(const Sample<D>& s) override {
    if (s.sampled) sampler_.sample(s.state, s.potential, s.conduction);
  }
  void finish(RunOutput& out) override {
    result_ = sampler_.result();
    out.slab_profile_csv = result_.csv();
  }
  const BinnedFields& result() const { return result_; } // after finish
  template <class A> void archive(A& a) { sampler_.archive(a); }

private:
  FieldSampler<D> sampler_;
  BinnedFields result_;
};

} // namespace

io::Json slab_kappa_fit(const ParticleParameters& p, const BinnedFields& profile) {
  io::Json j = slab_fit(p, profile);
  j["flux_decomposition"] = flux_at_planes(p, profile, j["J0"].get<double>());
  return j;
}

template <int D>
BinnedDiagnostic<D> make_slab_profile(const ParticleParameters& p, const RunFacts& m) {
  return BinnedDiagnostic<D>(std::make_unique<SlabProfile<D>>(p, m));
}

template BinnedDiagnostic<2> make_slab_profile<2>(const ParticleParameters&, const RunFacts&);
template BinnedDiagnostic<3> make_slab_profile<3>(const ParticleParameters&, const RunFacts&);

} // namespace twinflow::particle
