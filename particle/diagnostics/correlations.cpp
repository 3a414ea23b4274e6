// The velocity autocorrelation <v(0).v(t)> and the mean-square displacement of up to 1000
// tracked particles (ids 0..), averaged over time origins within a window of samples
// (correlations.csv; the transport stage takes the diffusion coefficient from the MSD). The MSD
// also per group of tracked particles (id mod groups): each group sees every time origin, so the
// groups' scatter holds the time correlations too, and the transport stage's D takes its error
// from it.
#include "particle/diagnostics/plugins.hpp"

#include <algorithm>
#include <sstream>

namespace twinflow::particle {

namespace {
template <int D> class Correlations : public Archived<D, Correlations<D>> {
public:
  Correlations(const ParticleParameters& p, const RunFacts& m)
      : Archived<D, Correlations<D>>("correlations"), window_(p.correlation_samples),
        interval_(p.sample_interval), dt_(p.dt), tracked_(std::min<std::size_t>(m.particles, 1000)),
        groups_(std::min<std::size_t>(tracked_, kGroups)), vacf_(window_, 0.0), msd_(window_, 0.0),
        count_(window_, 0.0), msd_group_(window_ * groups_, 0.0), unwrapped_(tracked_ * D),
        last_wrapped_(tracked_ * D), index_of_(m.particles) {}
  void sample(const Sample<D>& smp) override {
    if (!smp.sampled) return;
    const auto& s = smp.state;
    for (std::size_t i = 0; i < s.size(); ++i) index_of_[s.id[i]] = i;
    std::vector<double> vs(tracked_ * D), xs(tracked_ * D);
    for (std::size_t t = 0; t < tracked_; ++t) {
      const std::size_t i = index_of_[t];
      for (int d = 0; d < D; ++d) {
        vs[t * D + d] = s.v[d][i];
        double dx = s.x[d][i] - last_wrapped_[t * D + d];
        if (samples_ > 0)
          dx = smp.grid.minimum_image(dx, d);
        else
          dx = 0, unwrapped_[t * D + d] = s.x[d][i];
        unwrapped_[t * D + d] += dx;
        last_wrapped_[t * D + d] = s.x[d][i];
        xs[t * D + d] = unwrapped_[t * D + d];
      }
    }
    vbuf_.push_back(std::move(vs)), xbuf_.push_back(std::move(xs));
    if (static_cast<int>(vbuf_.size()) > window_)
      vbuf_.erase(vbuf_.begin()), xbuf_.erase(xbuf_.begin());
    const std::size_t last = vbuf_.size() - 1;
    for (std::size_t lag = 0; lag <= last; ++lag) {
      const auto &v0 = vbuf_[last - lag], &v1 = vbuf_[last], &x0 = xbuf_[last - lag],
                 &x1 = xbuf_[last];
      double cv = 0, dr = 0;
      std::fill(group_dr_.begin(), group_dr_.end(), 0.0);
      for (std::size_t t = 0; t < tracked_; ++t) {
        double dr_t = 0;
        for (int d = 0; d < D; ++d) {
          const std::size_t k = t * D + d;
          cv += v0[k] * v1[k];
          dr_t += (x1[k] - x0[k]) * (x1[k] - x0[k]);
        }
        dr += dr_t, group_dr_[t % groups_] += dr_t;
      }
      vacf_[lag] += cv / tracked_, msd_[lag] += dr / tracked_, count_[lag] += 1;
      for (std::size_t g = 0; g < groups_; ++g)
        msd_group_[lag * groups_ + g] += group_dr_[g] / group_size(g);
    }
    ++samples_;
  }
  void finish(RunOutput& out) override {
    std::ostringstream c;
    c << "# velocity autocorrelation <v(0).v(t)> (k T0/m) and mean-square displacement (rc^2), "
         "averaged over time origins and "
      << tracked_ << " particles; msd_group_g: of the tracked ids with id mod " << groups_
      << " = g\ntime,vacf,msd";
    for (std::size_t g = 0; g < groups_; ++g) c << ",msd_group_" << g;
    c << "\n";
    for (int lag = 0; lag < window_; ++lag)
      if (count_[lag] > 0) {
        c << lag * interval_ * dt_ << "," << vacf_[lag] / count_[lag] << ","
          << msd_[lag] / count_[lag];
        for (std::size_t g = 0; g < groups_; ++g)
          c << "," << msd_group_[lag * groups_ + g] / count_[lag];
        c << "\n";
      }
    out.correlations_csv = c.str();
  }
  template <class A> void archive(A& a) {
    a("vbuf", vbuf_), a("xbuf", xbuf_), a("vacf", vacf_), a("msd", msd_);
    a("count", count_), a("msd_group", msd_group_), a("unwrapped", unwrapped_);
    a("last_wrapped", last_wrapped_);
    a("samples", samples_);
  }

private:
  // Twenty groups: the error from their scatter has 19 degrees of freedom (a chi^2 over seeds
  // weighted by it is then biased by only 19/17).
  static constexpr std::size_t kGroups = 20;
  double group_size(std::size_t g) const { // ids g, g + groups, ... below tracked
    return static_cast<double>((tracked_ - g + groups_ - 1) / groups_);
  }
  int window_;
  long interval_; // steps between samples
  double dt_;
  std::size_t tracked_, groups_;
  std::vector<std::vector<double>> vbuf_, xbuf_; // ring buffers [sample][tracked * D]
  std::vector<double> vacf_, msd_, count_;       // per lag: sums and their number
  std::vector<double> msd_group_;                // per lag and group: sums of group means
  std::vector<double> group_dr_ = std::vector<double>(kGroups); // scratch
  std::vector<double> unwrapped_, last_wrapped_; // tracked positions across periodic images
  std::vector<std::size_t> index_of_;            // scratch: id -> index
  long samples_ = 0;
};

} // namespace

template <int D>
DiagnosticPtr<D> make_correlations(const ParticleParameters& p, const RunFacts& m) {
  return std::make_unique<Correlations<D>>(p, m);
}

template DiagnosticPtr<2> make_correlations<2>(const ParticleParameters&, const RunFacts&);
template DiagnosticPtr<3> make_correlations<3>(const ParticleParameters&, const RunFacts&);

} // namespace twinflow::particle
