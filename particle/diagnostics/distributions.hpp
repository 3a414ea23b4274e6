#pragma once
// Distributions over the sampled steps: velocity components and internal energies
// (histograms.csv), and the pair distribution function g(r) (rdf.csv) from the pair pass.

#include "particle/diagnostics/diagnostic.hpp"

namespace twinflow::particle {

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
  Histograms(const ParticleParameters& p, const RunFacts& m);
  std::string name() const override { return "histograms"; }
  void sample(const Sample<D>& s) override;
  void finish(RunOutput& out) override;
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
  PairDistribution(const ParticleParameters& p, const RunFacts& m);
  std::string name() const override { return "pair_distribution"; }
  PairNeeds pair_needs() const override { return {true, false}; }
  void sample(const Sample<D>& s) override;
  void finish(RunOutput& out) override;
  template <class A> void archive(A& a) { a("counts", counts_), a("samples", samples_); }

private:
  std::size_t n_;
  double rc_, volume_ = 1;
  std::vector<double> counts_; // pairs per bin of [0, rc), summed over the samples
  long samples_ = 0;
};

} // namespace twinflow::particle
