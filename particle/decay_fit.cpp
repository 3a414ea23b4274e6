#include "particle/decay_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "statistics/line_fit.hpp"

namespace twinflow::particle {

io::Json decay_fit(double wave, const std::vector<double>& t, const std::vector<double>& a,
                   const char* diffusivity) {
  io::Json j = io::Json::object();
  j["wavenumber"] = wave;
  const std::size_t n = t.size();
  const double a0 = n ? a.front() : 0;
  std::size_t start = 0;
  while (start < n && a[start] > 0.8 * a0) ++start;
  std::size_t end = start;
  while (end < n && a[end] >= 0.3 * a0) ++end;
  if (a0 <= 0 || end >= n || end - start < 5) {
    j["points"] = static_cast<long>(end - start);
    j["note"] = "too few samples between 80% and 30% of the initial amplitude: run longer";
    return j;
  }
  statistics::LineFit first;
  for (std::size_t k = start; k < end; ++k) first.add(t[k], std::log(a[k]));
  double slope = first.slope(), intercept = first.intercept();
  auto fitted = [&](std::size_t k) { return std::exp(intercept + slope * t[k]); };
  auto noise = [&](std::size_t from) {
    double ss = 0;
    for (std::size_t k = from; k < n; ++k) ss += (a[k] - fitted(k)) * (a[k] - fitted(k));
    return std::sqrt(ss / static_cast<double>(n - from));
  };
  // (a floor for noise-free data)
  double sigma = std::max(noise(n - end >= 5 ? end : start), 1e-12 * a0);
  statistics::LineFit line;
  std::vector<std::size_t> used;
  for (int pass = 0; pass < 3; ++pass) {
    line = statistics::LineFit{};
    used.clear();
    for (std::size_t k = start; k < n; ++k) {
      const double f = fitted(k);
      if (f < 3 * sigma) break;
      if (a[k] <= 0) continue;
      // E ln(f + e) = ln f - sigma^2 / (2 f^2) + O(sigma^4) (Taylor); var ln a = sigma^2 / f^2
      line.add(t[k], std::log(a[k]) + sigma * sigma / (2 * f * f), sigma / f);
      used.push_back(k);
    }
    if (used.size() < 5) break;
    slope = line.slope(), intercept = line.intercept();
    sigma = std::max(noise(start), 1e-12 * a0);
  }
  j["points"] = static_cast<long>(used.size());
  if (used.size() < 5) {
    j["note"] = "the mode sinks into its noise too early: a larger box or amplitude";
    return j;
  }
  double chi2 = 0;
  for (const std::size_t k : used) {
    const double f = fitted(k);
    const double r = (std::log(a[k]) + sigma * sigma / (2 * f * f) - intercept - slope * t[k]) * f;
    chi2 += r * r / (sigma * sigma);
  }
  const double m = static_cast<double>(used.size());
  const double sample_dt = (t.back() - t.front()) / static_cast<double>(n - 1);
  const double r = std::exp(slope * sample_dt);
  const double slope_se = line.slope_stderr() * std::sqrt(chi2 / (m - 2) * (1 + r) / (1 - r));
  j["noise_over_amplitude"] = sigma / a0;
  j["fit_from_time"] = t[used.front()], j["fit_to_time"] = t[used.back()];
  j["decay_rate"] = -slope, j["decay_rate_stderr"] = slope_se;
  j[diffusivity] = -slope / (wave * wave); // a ~ exp(-D k^2 t), 004
  j[std::string(diffusivity) + "_stderr"] = slope_se / (wave * wave);
  return j;
}

} // namespace twinflow::particle
