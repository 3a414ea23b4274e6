// Distributions over the sampled steps: velocity components and internal energies
// (histograms.csv), and the pair distribution function g(r) (rdf.csv) from the pair pass.
#include "particle/diagnostics/plugins.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace twinflow::particle {

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

template <int D> class Histograms : public Archived<D, Histograms<D>> {
public:
  Histograms(const ParticleParameters& p, const RunFacts& m)
      : Archived<D, Histograms<D>>("histograms"), has_energy_(m.has_energy),
        velocity_(-5 * std::sqrt(p.temperature / p.mass), 5 * std::sqrt(p.temperature / p.mass),
                  p.histogram_bins),
        energy_(0, 3 * p.cv * p.temperature, p.histogram_bins) {}
  void sample(const Sample<D>& s) override {
    if (!s.sampled) return;
    for (int d = 0; d < D; ++d)
      for (const double v : s.state.v[d]) velocity_.add(v);
    for (const double ui : s.state.u) energy_.add(ui);
  }
  void finish(RunOutput& out) override {
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
  template <class A> void archive(A& a) {
    a("velocity", velocity_.counts), a("velocity_total", velocity_.total);
    a("energy", energy_.counts), a("energy_total", energy_.total);
  }

private:
  bool has_energy_;
  Histogram velocity_, energy_;
};

template <int D> class PairDistribution : public Archived<D, PairDistribution<D>> {
public:
  PairDistribution(const ParticleParameters& p, const RunFacts& m)
      : Archived<D, PairDistribution<D>>("pair_distribution", {true, false}), n_(m.particles),
        rc_(m.rc), counts_(p.rdf_bins, 0.0) {
    for (int d = 0; d < D; ++d) volume_ *= p.box[d];
  }
  void sample(const Sample<D>& s) override {
    if (!s.sampled) return;
    for (std::size_t b = 0; b < counts_.size(); ++b) counts_[b] += s.pair_counts[b];
    ++samples_;
  }
  void finish(RunOutput& out) override {
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
  template <class A> void archive(A& a) { a("counts", counts_), a("samples", samples_); }

private:
  std::size_t n_;
  double rc_, volume_ = 1;
  std::vector<double> counts_; // pairs per bin of [0, rc), summed over the samples
  long samples_ = 0;
};

} // namespace

template <int D> DiagnosticPtr<D> make_histograms(const ParticleParameters& p, const RunFacts& m) {
  return std::make_unique<Histograms<D>>(p, m);
}

template <int D>
DiagnosticPtr<D> make_pair_distribution(const ParticleParameters& p, const RunFacts& m) {
  return std::make_unique<PairDistribution<D>>(p, m);
}

template DiagnosticPtr<2> make_histograms<2>(const ParticleParameters&, const RunFacts&);
template DiagnosticPtr<3> make_histograms<3>(const ParticleParameters&, const RunFacts&);
template DiagnosticPtr<2> make_pair_distribution<2>(const ParticleParameters&, const RunFacts&);
template DiagnosticPtr<3> make_pair_distribution<3>(const ParticleParameters&, const RunFacts&);

} // namespace twinflow::particle
