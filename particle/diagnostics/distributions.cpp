#include "particle/diagnostics/distributions.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace twinflow::particle {

template <int D>
Histograms<D>::Histograms(const ParticleParameters& p, const RunFacts& m)
    : has_energy_(m.has_energy), velocity_(-5 * std::sqrt(p.temperature / p.mass),
                                           5 * std::sqrt(p.temperature / p.mass), p.histogram_bins),
      energy_(0, 3 * p.cv * p.temperature, p.histogram_bins) {}

template <int D> void Histograms<D>::sample(const Sample<D>& s) {
  if (!s.sampled) return;
  for (int d = 0; d < D; ++d)
    for (const double v : s.state.v[d]) velocity_.add(v);
  for (const double ui : s.state.u) energy_.add(ui);
}

template <int D> void Histograms<D>::finish(RunOutput& out) {
  std::ostringstream h;
  h << "# histograms over sampled steps; velocity in sqrt(k T0/m), internal energy in k T0\n"
       "quantity,bin_centre,probability_density\n";
  const int bins = static_cast<int>(velocity_.counts.size());
  for (int b = 0; b < bins; ++b)
    h << "velocity_component," << velocity_.lo + (b + 0.5) * velocity_.width() << ","
      << velocity_.density(b) << "\n";
  if (has_energy_)
    for (int b = 0; b < bins; ++b)
      h << "internal_energy," << energy_.lo + (b + 0.5) * energy_.width() << ","
        << energy_.density(b) << "\n";
  out.histograms_csv = h.str();
}

template <int D>
PairDistribution<D>::PairDistribution(const ParticleParameters& p, const RunFacts& m)
    : n_(m.particles), rc_(m.rc), counts_(p.rdf_bins, 0.0) {
  for (int d = 0; d < D; ++d) volume_ *= p.box[d];
}

template <int D> void PairDistribution<D>::sample(const Sample<D>& s) {
  if (!s.sampled) return;
  for (std::size_t b = 0; b < counts_.size(); ++b) counts_[b] += s.pair_counts[b];
  ++samples_;
}

template <int D> void PairDistribution<D>::finish(RunOutput& out) {
  std::ostringstream g;
  g << "# pair distribution function g(r) for r < the largest cutoff; r in rc\nr,g\n";
  const double dr = rc_ / counts_.size();
  for (std::size_t b = 0; b < counts_.size(); ++b) {
    const double r0 = b * dr, r1 = r0 + dr;
    const double shell =
        D == 3 ? 4.0 / 3.0 * M_PI * (r1 * r1 * r1 - r0 * r0 * r0) : M_PI * (r1 * r1 - r0 * r0);
    const double ideal = 0.5 * n_ * (n_ / volume_) * shell * std::max<long>(samples_, 1);
    g << r0 + 0.5 * dr << "," << counts_[b] / ideal << "\n";
  }
  out.rdf_csv = g.str();
}

template class Histograms<2>;
template class Histograms<3>;
template class PairDistribution<2>;
template class PairDistribution<3>;

} // namespace twinflow::particle
