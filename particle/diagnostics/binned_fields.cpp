#include "particle/diagnostics/binned_fields.hpp"

#include <algorithm>
#include <cmath>

namespace twinflow::particle {

namespace {

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

} // namespace

template <int D>
Fields<D>::Fields(const ParticleParameters& p, const RunFacts& m)
    : p_(p), n_(m.particles), sampler_(box3(p), p.bins, p.blocks, sampled_count(p), p.mass, p.cv) {}

template <int D> void Fields<D>::sample(const Sample<D>& s) {
  if (!s.sampled) return;
  sampler_.sample(s.state, s.potential, s.conduction);
  ++taken_;
  const long rows = sampler_.total_samples();
  if (taken_ == rows || taken_ % std::max(1L, rows / 10) == 0)
    snapshots_.push_back(
        snapshot(sampler_.result(), s.time, s.elapsed_seconds, static_cast<long>(n_) * s.step));
}

template <int D> void Fields<D>::finish(RunOutput& out) {
  result_ = sampler_.result();
  out.fields_csv = result_.csv();
  out.blocks_csv = result_.blocks_csv();
  out.field_grid.dim = D;
  for (int d = 0; d < D; ++d) {
    out.field_grid.counts[d] = p_.bins[d];
    out.field_grid.spacing[d] = p_.box[d] / p_.bins[d];
  }
  out.field_snapshots = std::move(snapshots_);
}

template <int D> void PoiseuilleFit<D>::finish(RunOutput& out) {
  const BinnedFields& f = fields_.result();
  io::Json j = io::Json::object();
  if (f.bins[1] < 8) {
    j["note"] = "needs at least 8 bins along y";
    out.summary["poiseuille"] = j;
    return;
  }
  const double ly = p_.box[1];
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
    const double force = half == 0 ? p_.poiseuille_force : -p_.poiseuille_force;
    const double eta = -p_.density * force / (2 * c2); // v'' = 2 c2 = -n F / eta
    const double eta_se = std::fabs(eta) * std::sqrt(c2_var) / std::fabs(c2);
    io::Json h = io::Json::object();
    h["curvature"] = 2 * c2, h["viscosity"] = eta, h["viscosity_stderr"] = eta_se;
    j[names[half]] = h;
    wsum += 1 / (eta_se * eta_se), esum += eta / (eta_se * eta_se);
  }
  j["viscosity"] = esum / wsum;
  j["viscosity_stderr"] = 1 / std::sqrt(wsum);
  out.summary["poiseuille"] = j;
}

template class Fields<2>;
template class Fields<3>;
template class PoiseuilleFit<2>;
template class PoiseuilleFit<3>;

} // namespace twinflow::particle
