// Binned fields on the scene's bins (fields.csv, blocks.csv, and cumulative snapshots for
// fields.h5), and the fit a reverse Poiseuille scene takes from them.
#include "io/field_file.hpp"
#include "particle/diagnostics/plugins.hpp"
#include "particle/field_list.hpp"
#include "particle/fields.hpp"
#include "statistics/line_fit.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace twinflow::particle {

namespace {

io::Snapshot snapshot(const BinnedFields& f, double time, double wall, long particle_steps) {
  io::Snapshot s;
  s.time = time;
  s.wall_seconds = wall;
  s.particle_steps = particle_steps;
  for (const NamedField& n : named_fields()) {
    const FieldEstimate& e = f.*n.estimate;
    s.fields.push_back(io::Field{n.name, n.vector ? f.dim : 1, e.mean, e.stderr_});
  }
  return s;
}

template <int D> class Fields : public Archived<D, Fields<D>> {
public:
  Fields(const ParticleParameters& p, const RunFacts& m)
      : Archived<D, Fields<D>>("fields", {false, true}), p_(p), n_(m.particles),
        sampler_(box3(p), p.bins, p.blocks, sampled_count(p), p.mass, p.cv) {}
  void sample(const Sample<D>& s) override {
    if (!s.sampled) return;
    sampler_.sample(s.state, s.potential, s.conduction);
    ++taken_;
    const long rows = sampler_.total_samples();
    if (taken_ == rows || taken_ % std::max(1L, rows / 10) == 0)
      snapshots_.push_back(
          snapshot(sampler_.result(), s.time, s.elapsed_seconds, static_cast<long>(n_) * s.step));
  }
  void finish(RunOutput& out) override {
    result_ = sampler_.result();
    out.fields_csv = result_.csv();
    out.blocks_csv = result_.blocks_csv();
    out.field_grid.dim = D;
    for (int d = 0; d < D; ++d) {
      out.field_grid.counts[d] = p_.bins[d];
      out.field_grid.spacing[d] = p_.box[d] / p_.bins[d];
    }
    out.field_snapshots = std::move(snapshots_);
    io::Json factors = io::Json::object();
    for (const NamedField& n : named_fields())
      factors[n.name] = (result_.*n.estimate).blocking_factor;
    out.summary["field_blocking_factors"] = factors;
  }
  // The final fields, reduced over the blocks once (by finish) for the fits that use them.
  const BinnedFields& result() const { return result_; }
  template <class A> void archive(A& a) {
    auto f = a.nested("sampler");
    sampler_.archive(f);
    a("taken", taken_);
    auto s = a.nested("snapshots");
    archive_snapshots(s);
  }

private:
  // Cumulative averages at a sequence of times, saved with the run (they cannot be recomputed).
  template <class A> void archive_snapshots(A& a) {
    long count = static_cast<long>(snapshots_.size());
    a("count", count);
    if constexpr (A::loading) snapshots_.assign(static_cast<std::size_t>(count), io::Snapshot{});
    for (long k = 0; k < count; ++k) {
      auto s = a.nested(std::to_string(k));
      io::Snapshot& snap = snapshots_[k];
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
  ParticleParameters p_;
  std::size_t n_;
  FieldSampler<D> sampler_;
  long taken_ = 0;
  std::vector<io::Snapshot> snapshots_;
  BinnedFields result_;
};

} // namespace

namespace {
// v = c0 + c1 y + c2 y^2 through the bins with lo <= y <= hi, weighted by their errors.
statistics::QuadraticFit fit_parabola(const BinnedFields& f, double lo, double hi) {
  statistics::QuadraticFit fit(0.5 * (lo + hi));
  for (int bin = 0; bin < f.bin_count(); ++bin) {
    const double y = f.centre(bin, 1);
    if (y >= lo && y <= hi)
      fit.add(y, f.velocity.mean[bin * f.dim], f.velocity.stderr_[bin * f.dim]);
  }
  return fit;
}

// The wall's apparent slip: where the bulk's parabola reaches v = 0 beyond the wall plane at
// y = wall (Navier's b, positive beyond the plane), and its error from the fit's covariance
// (d root / d c_k = -root^k / v'(root): the value's error at the root over the slope there).
std::pair<double, double> slip_at_wall(const statistics::QuadraticFit& fit, double wall,
                                       double into_fluid) {
  // v(wall + s) = v0 + v1 s + v2 s^2
  const double v0 = fit.value(wall), v1 = fit.slope(wall), v2 = 0.5 * fit.curvature();
  const double root_term = std::sqrt(std::max(v1 * v1 - 4 * v2 * v0, 0.0));
  const double s1 = (-v1 + root_term) / (2 * v2), s2 = (-v1 - root_term) / (2 * v2);
  const double root = wall + (std::fabs(s1) < std::fabs(s2) ? s1 : s2);
  return {(wall - root) * into_fluid, fit.value_stderr(root) / std::fabs(fit.slope(root))};
}
} // namespace

// Each half's parabola away from the kink at Ly/2 (and from a wall's layer): eta from its
// curvature, v'' = -n F / eta; between walls along y also each wall's slip length.
io::Json poiseuille_fit(const ParticleParameters& p, const BinnedFields& f) {
  io::Json j = io::Json::object();
  if (f.bins[1] < 8) {
    j["note"] = "needs at least 8 bins along y";
    return j;
  }
  const double ly = p.box[1];
  const bool walls = p.walls[1].present;
  const double margin = walls ? std::max(0.05 * ly, p.largest_cutoff()) : 0.05 * ly;
  double wsum = 0, esum = 0;
  const char* names[2] = {"lower_half", "upper_half"};
  for (int half = 0; half < 2; ++half) {
    const double lo = half == 0 ? margin : 0.5 * ly + 0.05 * ly;
    const double hi = half == 0 ? 0.5 * ly - 0.05 * ly : ly - margin;
    const statistics::QuadraticFit fit = fit_parabola(f, lo, hi);
    const double curvature = fit.curvature();
    const double force = half == 0 ? p.poiseuille_force : -p.poiseuille_force;
    const double eta = -p.density * force / curvature; // v'' = -n F / eta
    const double eta_se = std::fabs(eta) * fit.curvature_stderr() / std::fabs(curvature);
    io::Json h = io::Json::object();
    h["curvature"] = curvature, h["viscosity"] = eta, h["viscosity_stderr"] = eta_se;
    if (walls) {
      const auto [slip, slip_se] = slip_at_wall(fit, half == 0 ? 0 : ly, half == 0 ? 1 : -1);
      h["wall_slip"] = slip, h["wall_slip_stderr"] = slip_se;
    }
    j[names[half]] = h;
    wsum += 1 / (eta_se * eta_se), esum += eta / (eta_se * eta_se);
  }
  j["viscosity"] = esum / wsum;
  j["viscosity_stderr"] = 1 / std::sqrt(wsum);
  return j;
}

template <int D> BinnedDiagnostic<D> make_fields(const ParticleParameters& p, const RunFacts& m) {
  return BinnedDiagnostic<D>(std::make_unique<Fields<D>>(p, m));
}

template BinnedDiagnostic<2> make_fields<2>(const ParticleParameters&, const RunFacts&);
template BinnedDiagnostic<3> make_fields<3>(const ParticleParameters&, const RunFacts&);

} // namespace twinflow::particle
