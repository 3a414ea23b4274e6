#include "transport/laws.hpp"

#include <algorithm>
#include <cmath>

namespace twinflow::transport {

double CoefficientLaw::at(double n, double T) const {
  const double t = T / T0, r = n / n0;
  return K * std::pow(t, a) + P * r * r * std::pow(t, b);
}

double CoefficientLaw::pair_fraction(double T) const {
  const double pair = P * std::pow(T / T0, b);
  return pair / at(n0, T);
}

io::Json CoefficientLaw::json() const {
  io::Json j = io::Json::object();
  j["form"] = "K (T/T0)^a + P (n/n0)^2 (T/T0)^b";
  j["T0"] = T0, j["n0"] = n0;
  j["K"] = K, j["K_stderr"] = K_stderr;
  j["a"] = a, j["a_stderr"] = a_stderr;
  j["P"] = P, j["b"] = b;
  j["at_reference"] = at(n0, T0);
  j["chi2_per_dof"] = chi2_per_dof, j["points"] = points;
  return j;
}

namespace {
// chi^2 of the law through the points at exponent a, with K at its best value for that a.
struct AtExponent {
  double chi2, K, K_stderr;
};
AtExponent best_K(const std::vector<StatePoint>& points, double n0, double T0, double P, double b,
                  double a) {
  double sxx = 0, sxy = 0;
  for (const StatePoint& p : points) {
    const double w = 1 / (p.value.stderr_ * p.value.stderr_);
    const double x = std::pow(p.T / T0, a);
    const double y = p.value.mean - P * std::pow(p.n / n0, 2) * std::pow(p.T / T0, b);
    sxx += w * x * x, sxy += w * x * y;
  }
  AtExponent r{0, sxy / sxx, 1 / std::sqrt(sxx)};
  for (const StatePoint& p : points) {
    const double model =
        r.K * std::pow(p.T / T0, a) + P * std::pow(p.n / n0, 2) * std::pow(p.T / T0, b);
    const double z = (p.value.mean - model) / p.value.stderr_;
    r.chi2 += z * z;
  }
  return r;
}
} // namespace

CoefficientLaw fit_law(const std::vector<StatePoint>& points, double n0, double T0, double P,
                       double b, double a_fallback) {
  CoefficientLaw law;
  law.T0 = T0, law.n0 = n0, law.P = P, law.b = b;
  law.points = static_cast<int>(points.size());
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const StatePoint& p : points) lo = std::min(lo, p.T), hi = std::max(hi, p.T);
  if (points.size() < 3 || hi < 1.1 * lo) { // too little span to see a power of T
    const AtExponent fixed = best_K(points, n0, T0, P, b, a_fallback);
    law.a = a_fallback, law.K = fixed.K, law.K_stderr = fixed.K_stderr;
    return law;
  }
  // Golden-section search for the a that minimises chi^2 (one minimum for a power law).
  const double phi = 0.5 * (std::sqrt(5.0) - 1);
  double x0 = -3, x3 = 5;
  double x1 = x3 - phi * (x3 - x0), x2 = x0 + phi * (x3 - x0);
  double f1 = best_K(points, n0, T0, P, b, x1).chi2, f2 = best_K(points, n0, T0, P, b, x2).chi2;
  while (x3 - x0 > 1e-6) {
    if (f1 < f2)
      x3 = x2, x2 = x1, f2 = f1, x1 = x3 - phi * (x3 - x0),
      f1 = best_K(points, n0, T0, P, b, x1).chi2;
    else
      x0 = x1, x1 = x2, f1 = f2, x2 = x0 + phi * (x3 - x0),
      f2 = best_K(points, n0, T0, P, b, x2).chi2;
  }
  law.a = 0.5 * (x0 + x3);
  const AtExponent best = best_K(points, n0, T0, P, b, law.a);
  const int dof = static_cast<int>(points.size()) - 2;
  law.chi2_per_dof = best.chi2 / dof;
  const double scale = std::sqrt(std::max(1.0, law.chi2_per_dof));
  // a's error from chi^2's curvature along the profile of the best K: sigma_a^2 = 2 / chi2''.
  const double h = 1e-3;
  const double curvature = (best_K(points, n0, T0, P, b, law.a + h).chi2 - 2 * best.chi2 +
                            best_K(points, n0, T0, P, b, law.a - h).chi2) /
                           (h * h);
  law.a_stderr = scale * std::sqrt(2 / std::max(curvature, 1e-300));
  law.K = best.K;
  law.K_stderr = scale * best.K_stderr;
  return law;
}

CoefficientLaw law_through(const statistics::Estimate& value, double T, double n0, double T0,
                           double P, double b, double a, double a_stderr) {
  CoefficientLaw law;
  law.T0 = T0, law.n0 = n0, law.P = P, law.b = b, law.a = a, law.a_stderr = a_stderr;
  law.points = 1;
  const double t = std::pow(T / T0, a);
  law.K = (value.mean - P * std::pow(T / T0, b)) / t;
  law.K_stderr = value.stderr_ / t;
  return law;
}

} // namespace twinflow::transport
