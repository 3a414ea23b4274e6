#include "particle/diagnostics/correlations.hpp"

#include <algorithm>
#include <sstream>

namespace twinflow::particle {

template <int D>
Correlations<D>::Correlations(const ParticleParameters& p, const RunFacts& m)
    : window_(p.correlation_samples), interval_(p.sample_interval), dt_(p.dt),
      tracked_(std::min<std::size_t>(m.particles, 1000)), vacf_(window_, 0.0), msd_(window_, 0.0),
      count_(window_, 0.0), unwrapped_(tracked_ * D), last_wrapped_(tracked_ * D),
      index_of_(m.particles) {}

template <int D> void Correlations<D>::sample(const Sample<D>& smp) {
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
    for (std::size_t k = 0; k < tracked_ * D; ++k) {
      cv += v0[k] * v1[k];
      dr += (x1[k] - x0[k]) * (x1[k] - x0[k]);
    }
    vacf_[lag] += cv / tracked_, msd_[lag] += dr / tracked_, count_[lag] += 1;
  }
  ++samples_;
}

template <int D> void Correlations<D>::finish(RunOutput& out) {
  std::ostringstream c;
  c << "# velocity autocorrelation <v(0).v(t)> (k T0/m) and mean-square displacement (rc^2), "
       "averaged over time origins and "
    << tracked_ << " particles\ntime,vacf,msd\n";
  for (int lag = 0; lag < window_; ++lag)
    if (count_[lag] > 0)
      c << lag * interval_ * dt_ << "," << vacf_[lag] / count_[lag] << ","
        << msd_[lag] / count_[lag] << "\n";
  out.correlations_csv = c.str();
}

template class Correlations<2>;
template class Correlations<3>;

} // namespace twinflow::particle
