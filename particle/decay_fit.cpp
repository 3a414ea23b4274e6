#include "particle/decay_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "statistics/line_fit.hpp"

namespace twinflow::particle {

namespace {
// The fit of ln a = intercept + slope t over the samples `used`, a's noise sigma about it.
struct LogFit {
  double slope = 0, intercept = 0, sigma = 0;
  statistics::LineFit line;
  std::vector<std::size_t> used;
};

class DecayFitter {
public:
  DecayFitter(const std::vector<double>& t, const std::vector<double>& a) : t_(t), a_(a) {}

  // The decay's first window, from 80% to 30% of the initial amplitude: [start, end).
  void window(std::size_t& start, std::size_t& end) const {
    const double a0 = a_.front();
    start = 0;
    while (start < a_.size() && a_[start] > 0.8 * a0) ++start;
    end = start;
    while (end < a_.size() && a_[end] >= 0.3 * a0) ++end;
  }

  // An unweighted line through the window, then three passes of a weighted fit over every sample
  // from `start` whose fitted amplitude stays above 3 sigma.
  LogFit fit(std::size_t start, std::size_t end) const {
    LogFit f;
    statistics::LineFit first;
    for (std::size_t k = start; k < end; ++k) first.add(t_[k], std::log(a_[k]));
    f.slope = first.slope(), f.intercept = first.intercept();
    const std::size_t n = t_.size();
    // (a floor for noise-free data)
    f.sigma = std::max(noise(f, n - end >= 5 ? end : start), 1e-12 * a_.front());
    for (int pass = 0; pass < 3; ++pass) {
      f.line = statistics::LineFit{};
      f.used.clear();
      for (std::size_t k = start; k < n; ++k) {
        const double fk = fitted(f, k);
        if (fk < 3 * f.sigma) break;
        if (a_[k] <= 0) continue;
        // E ln(f + e) = ln f - sigma^2 / (2 f^2) + O(sigma^4) (Taylor); var ln a = sigma^2 / f^2
        f.line.add(t_[k], std::log(a_[k]) + f.sigma * f.sigma / (2 * fk * fk), f.sigma / fk);
        f.used.push_back(k);
      }
      if (f.used.size() < 5) break;
      f.slope = f.line.slope(), f.intercept = f.line.intercept();
      f.sigma = std::max(noise(f, start), 1e-12 * a_.front());
    }
    return f;
  }

  // The slope's standard error: the fit's, scaled by its chi^2 and by the AR(1) factor
  // (1 + r) / (1 - r) of samples correlated as the decay itself.
  double slope_stderr(const LogFit& f) const {
    double chi2 = 0;
    for (const std::size_t k : f.used) {
      const double fk = fitted(f, k);
      const double r =
          (std::log(a_[k]) + f.sigma * f.sigma / (2 * fk * fk) - f.intercept - f.slope * t_[k]) *
          fk;
      chi2 += r * r / (f.sigma * f.sigma);
    }
    const double m = static_cast<double>(f.used.size());
    const double sample_dt = (t_.back() - t_.front()) / static_cast<double>(t_.size() - 1);
    const double r = std::exp(f.slope * sample_dt);
    return f.line.slope_stderr() * std::sqrt(chi2 / (m - 2) * (1 + r) / (1 - r));
  }

private:
  double fitted(const LogFit& f, std::size_t k) const {
    return std::exp(f.intercept + f.slope * t_[k]);
  }
  // The rms of a about the fit from sample `from` on.
  double noise(const LogFit& f, std::size_t from) const {
    double ss = 0;
    for (std::size_t k = from; k < t_.size(); ++k)
      ss += (a_[k] - fitted(f, k)) * (a_[k] - fitted(f, k));
    return std::sqrt(ss / static_cast<double>(t_.size() - from));
  }

  const std::vector<double>& t_;
  const std::vector<double>& a_;
};
} // namespace

io::Json decay_fit(double wave, const std::vector<double>& t, const std::vector<double>& a,
                   const char* diffusivity) {
  io::Json j = io::Json::object();
  j["wavenumber"] = wave;
  const DecayFitter fitter(t, a);
  std::size_t start = 0, end = 0;
  if (!t.empty()) fitter.window(start, end);
  if (t.empty() || a.front() <= 0 || end >= t.size() || end - start < 5) {
    j["points"] = static_cast<long>(end - start);
    j["note"] = "too few samples between 80% and 30% of the initial amplitude: run longer";
    return j;
  }
  const LogFit f = fitter.fit(start, end);
  j["points"] = static_cast<long>(f.used.size());
  if (f.used.size() < 5) {
    j["note"] = "the mode sinks into its noise too early: a larger box or amplitude";
    return j;
  }
  const double slope_se = fitter.slope_stderr(f);
  j["noise_over_amplitude"] = f.sigma / a.front();
  j["fit_from_time"] = t[f.used.front()], j["fit_to_time"] = t[f.used.back()];
  j["decay_rate"] = -f.slope, j["decay_rate_stderr"] = slope_se;
  j[diffusivity] = -f.slope / (wave * wave); // a ~ exp(-D k^2 t), 004
  j[std::string(diffusivity) + "_stderr"] = slope_se / (wave * wave);
  return j;
}

} // namespace twinflow::particle
