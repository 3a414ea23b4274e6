#pragma once
// The velocity autocorrelation <v(0).v(t)> and the mean-square displacement of up to 1000
// tracked particles (ids 0..), averaged over time origins within a window of samples
// (correlations.csv; the transport stage takes the diffusion coefficient from the MSD).

#include "particle/diagnostics/diagnostic.hpp"

namespace twinflow::particle {

template <int D> class Correlations : public Archived<D, Correlations<D>> {
public:
  Correlations(const ParticleParameters& p, const RunFacts& m);
  std::string name() const override { return "correlations"; }
  void sample(const Sample<D>& s) override;
  void finish(RunOutput& out) override;
  template <class A> void archive(A& a) {
    a("vbuf", vbuf_), a("xbuf", xbuf_), a("vacf", vacf_), a("msd", msd_);
    a("count", count_), a("unwrapped", unwrapped_), a("last_wrapped", last_wrapped_);
    a("samples", samples_);
  }

private:
  int window_;
  long interval_; // steps between samples
  double dt_;
  std::size_t tracked_;
  std::vector<std::vector<double>> vbuf_, xbuf_; // ring buffers [sample][tracked * D]
  std::vector<double> vacf_, msd_, count_;       // per lag: sums and their number
  std::vector<double> unwrapped_, last_wrapped_; // tracked positions across periodic images
  std::vector<std::size_t> index_of_;            // scratch: id -> index
  long samples_ = 0;
};

} // namespace twinflow::particle
