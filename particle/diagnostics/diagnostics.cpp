#include "particle/diagnostics/diagnostics.hpp"

#include "particle/diagnostics/plugins.hpp"

namespace twinflow::particle {

long sampled_count(const ParticleParameters& p) {
  const long total = p.equilibration_steps + p.steps;
  long rows = 0;
  for (long step = p.equilibration_steps + 1; step <= total; ++step)
    rows += step % p.sample_interval == 0 || step == total;
  return rows;
}

std::array<double, 3> box3(const ParticleParameters& p) {
  return {{p.box[0], p.box[1], p.dim == 3 ? p.box[2] : 1.0}};
}

template <int D>
DiagnosticList<D> make_diagnostics(const ParticleParameters& p, const RunFacts& m) {
  DiagnosticList<D> list;
  auto add = [&](DiagnosticPtr<D> diagnostic) { list.push_back(std::move(diagnostic)); };
  // A fit of binned fields: `fit` gives its results, stored under `key` of the summary.
  auto add_fit = [&](const char* name, const char* key, std::function<io::Json()> fit) {
    add(std::make_unique<Fit<D>>(name, [key, fit](RunOutput& out) { out.summary[key] = fit(); }));
  };
  add(make_thermo<D>(p, m));
  if (p.has_walls()) {
    add(make_wall_fluxes<D>(p));
    add(make_wall_layers<D>(p, m));
  }
  add(make_histograms<D>(p, m));
  add(make_pair_distribution<D>(p, m));
  add(make_correlations<D>(p, m));
  const bool heat_mode = m.has_energy && p.temperature_perturbation != 0;
  const bool shear_mode = p.shear_perturbation != 0;
  if (heat_mode || shear_mode) add(make_relaxation_modes<D>(p, m, heat_mode, shear_mode));
  auto fields = make_fields<D>(p, m);
  const BinnedFields& f = fields.fields;
  add(std::move(fields.diagnostic));
  if (p.poiseuille_force != 0)
    add_fit("poiseuille_fit", "poiseuille", [p, &f] { return poiseuille_fit(p, f); });
  if (const int d = wall_profile_direction(p); d >= 0)
    add_fit("wall_profile_fit", "wall_profile", [p, d, &f] { return wall_profile_fit(p, d, f); });
  if (!p.heat_slabs.empty()) {
    auto profile = make_slab_profile<D>(p, m);
    const BinnedFields& slabs = profile.fields;
    add(std::move(profile.diagnostic));
    if (m.has_energy && p.heat_slabs.size() == 2)
      add_fit("slab_kappa_fit", "heat_slabs", [p, &slabs] { return slab_kappa_fit(p, slabs); });
  }
  return list;
}

template DiagnosticList<2> make_diagnostics<2>(const ParticleParameters&, const RunFacts&);
template DiagnosticList<3> make_diagnostics<3>(const ParticleParameters&, const RunFacts&);

} // namespace twinflow::particle
