#include "transport/laws.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace twinflow::transport {

double CoefficientLaw::at(double n, double T) const {
  const double t = T / T0, r = n / n0;
  return K * std::pow(t, a) + P * r * r * std::pow(t, b);
}

double CoefficientLaw::pair_fraction(double T) const {
  const double pair = P * std::pow(T / T0, b);
  return pair / at(n0, T);
}

double CoefficientLaw::stderr_at(double T) const {
  const double t = T / T0, x_K = std::pow(t, a), x_P = std::pow(t, b);
  if (!has_covariance) return K_stderr * x_K;
  const double x_a = K * x_K * std::log(t); // d c / d a
  const double var = x_K * x_K * K_stderr * K_stderr + x_P * x_P * P_stderr * P_stderr +
                     x_a * x_a * a_stderr * a_stderr + 2 * x_K * x_P * K_P_covariance +
                     2 * x_K * x_a * K_a_covariance + 2 * x_P * x_a * P_a_covariance;
  return std::sqrt(std::max(var, 0.0));
}

CoefficientLaw CoefficientLaw::from_json(const io::Json& j) {
  const auto at = [&](const char* key) { return io::number(j, {key}); };
  CoefficientLaw law;
  law.T0 = at("T0"), law.n0 = at("n0");
  law.K = at("K"), law.K_stderr = at("K_stderr"), law.a = at("a"), law.a_stderr = at("a_stderr");
  law.P = at("P"), law.b = at("b");
  if (const io::Json* c = io::find(j, {"covariance"})) {
    law.has_covariance = true;
    law.P_stderr = at("P_stderr");
    law.K_P_covariance = io::number(*c, {"K_P"});
    law.K_a_covariance = io::number(*c, {"K_a"});
    law.P_a_covariance = io::number(*c, {"P_a"});
  }
  return law;
}

io::Json CoefficientLaw::json() const {
  io::Json j = io::Json::object();
  j["form"] = "K (T/T0)^a + P (n/n0)^2 (T/T0)^b";
  j["T0"] = T0, j["n0"] = n0;
  j["K"] = K, j["K_stderr"] = K_stderr;
  j["a"] = a, j["a_stderr"] = a_stderr;
  j["P"] = P, j["P_stderr"] = P_stderr, j["b"] = b;
  if (has_covariance)
    j["covariance"] = {{"K_P", K_P_covariance}, {"K_a", K_a_covariance}, {"P_a", P_a_covariance}};
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

namespace {
// K and P by weighted linear least squares at exponent a (the 2 x 2 normal equations), and chi^2.
struct KAndP {
  double chi2 = 0, K = 0, P = 0;
};
KAndP best_K_and_P(const std::vector<StatePoint>& points, double n0, double T0, double b,
                   double a) {
  double s11 = 0, s12 = 0, s22 = 0, s1y = 0, s2y = 0;
  for (const StatePoint& p : points) {
    const double w = 1 / (p.value.stderr_ * p.value.stderr_);
    const double x1 = std::pow(p.T / T0, a), x2 = std::pow(p.n / n0, 2) * std::pow(p.T / T0, b);
    s11 += w * x1 * x1, s12 += w * x1 * x2, s22 += w * x2 * x2;
    s1y += w * x1 * p.value.mean, s2y += w * x2 * p.value.mean;
  }
  const double det = s11 * s22 - s12 * s12;
  KAndP r;
  r.K = (s22 * s1y - s12 * s2y) / det, r.P = (s11 * s2y - s12 * s1y) / det;
  for (const StatePoint& p : points) {
    const double model =
        r.K * std::pow(p.T / T0, a) + r.P * std::pow(p.n / n0, 2) * std::pow(p.T / T0, b);
    const double z = (p.value.mean - model) / p.value.stderr_;
    r.chi2 += z * z;
  }
  return r;
}

// The a in [lo, hi] that minimises f(a) (golden-section search; one minimum assumed).
template <class F> double golden_minimum(F f, double lo, double hi) {
  const double phi = 0.5 * (std::sqrt(5.0) - 1);
  double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  while (hi - lo > 1e-6) {
    if (f1 < f2)
      hi = x2, x2 = x1, f2 = f1, x1 = hi - phi * (hi - lo), f1 = f(x1);
    else
      lo = x1, x1 = x2, f1 = f2, x2 = lo + phi * (hi - lo), f2 = f(x2);
  }
  return 0.5 * (lo + hi);
}
} // namespace

CoefficientLaw fit_law_and_pair(const std::vector<StatePoint>& points, double n0, double T0,
                                double b) {
  CoefficientLaw law;
  law.T0 = T0, law.n0 = n0, law.b = b;
  law.points = static_cast<int>(points.size());
  const auto chi2 = [&](double a) { return best_K_and_P(points, n0, T0, b, a).chi2; };
  law.a = golden_minimum(chi2, -3, 5);
  const KAndP best = best_K_and_P(points, n0, T0, b, law.a);
  law.K = best.K, law.P = best.P;
  const int dof = law.points - 3;
  law.chi2_per_dof = dof > 0 ? best.chi2 / dof : 0;
  // The covariance of (K, P, a): (J^T W J)^-1 with the model's derivatives J at the minimum
  // (K and P's errors at a fixed a would leave out a's), scaled by chi^2 / dof when above 1.
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  for (const StatePoint& p : points) {
    const double x1 = std::pow(p.T / T0, law.a);
    const Eigen::Vector3d j(x1, std::pow(p.n / n0, 2) * std::pow(p.T / T0, b),
                            law.K * x1 * std::log(p.T / T0));
    normal += j * j.transpose() / (p.value.stderr_ * p.value.stderr_);
  }
  const Eigen::Matrix3d cov = std::max(1.0, law.chi2_per_dof) * normal.inverse();
  law.K_stderr = std::sqrt(cov(0, 0)), law.P_stderr = std::sqrt(cov(1, 1));
  law.a_stderr = std::sqrt(cov(2, 2));
  law.has_covariance = true;
  law.K_P_covariance = cov(0, 1), law.K_a_covariance = cov(0, 2), law.P_a_covariance = cov(1, 2);
  return law;
}

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
  law.a = golden_minimum([&](double a) { return best_K(points, n0, T0, P, b, a).chi2; }, -3, 5);
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
