#include "particle/diagnostics/diagnostics.hpp"

#include "particle/diagnostics/binned_fields.hpp"
#include "particle/diagnostics/correlations.hpp"
#include "particle/diagnostics/distributions.hpp"
#include "particle/diagnostics/relaxation.hpp"
#include "particle/diagnostics/slabs.hpp"
#include "particle/diagnostics/thermo.hpp"
#include "particle/diagnostics/walls.hpp"

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
  auto add = [&](auto diagnostic) -> auto& {
    auto& d = *diagnostic;
    list.push_back(std::move(diagnostic));
    return d;
  };
  add(std::make_unique<Thermo<D>>(p, m));
  if (p.has_walls()) {
    add(std::make_unique<WallFluxes<D>>(p));
    add(std::make_unique<WallLayers<D>>(p, m));
  }
  add(std::make_unique<Histograms<D>>(p, m));
  add(std::make_unique<PairDistribution<D>>(p, m));
  add(std::make_unique<Correlations<D>>(p, m));
  const bool heat_mode = m.has_energy && p.temperature_perturbation != 0;
  const bool shear_mode = p.shear_perturbation != 0;
  if (heat_mode || shear_mode)
    add(std::make_unique<RelaxationModes<D>>(p, m, heat_mode, shear_mode));
  const auto& fields = add(std::make_unique<Fields<D>>(p, m));
  if (p.poiseuille_force != 0) add(std::make_unique<PoiseuilleFit<D>>(p, fields));
  if (const int d = wall_profile_direction(p); d >= 0)
    add(std::make_unique<WallProfileFit<D>>(p, d, fields));
  if (!p.heat_slabs.empty()) {
    const auto& profile = add(std::make_unique<SlabProfile<D>>(p, m));
    if (m.has_energy && p.heat_slabs.size() == 2)
      add(std::make_unique<SlabKappaFit<D>>(p, profile));
  }
  return list;
}

template DiagnosticList<2> make_diagnostics<2>(const ParticleParameters&, const RunFacts&);
template DiagnosticList<3> make_diagnostics<3>(const ParticleParameters&, const RunFacts&);

} // namespace twinflow::particle
