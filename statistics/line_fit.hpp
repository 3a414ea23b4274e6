#pragma once
// Weighted least squares (weights 1/se^2, or 1 where no error is given): a straight line and a
// parabola, with their standard errors.

#include <array>
#include <cmath>

namespace twinflow::statistics {

// y = a + b x (Numerical Recipes, 3rd ed., sec. 15.2): slope and intercept.
struct LineFit {
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  void add(double x, double y, double se = 0) {
    const double w = se > 0 ? 1 / (se * se) : 1;
    sw += w, sx += w * x, sy += w * y, sxx += w * x * x, sxy += w * x * y;
  }
  double det() const { return sw * sxx - sx * sx; }
  double slope() const { return (sw * sxy - sx * sy) / det(); }
  double intercept() const { return (sxx * sy - sx * sxy) / det(); }
  double slope_stderr() const { return std::sqrt(sw / det()); }
  // Standard error of the line's value at x.
  double value_stderr(double x) const { return std::sqrt((sxx - 2 * x * sx + x * x * sw) / det()); }
};

// A parabola y = a + b u + c u^2, u = x - centre, by weighted least squares (the normal
// equations, Numerical Recipes, 3rd ed., sec. 15.4): its value and slope at any x with their
// standard errors from the parameters' covariance, the inverse of the normal matrix.
class QuadraticFit {
public:
  explicit QuadraticFit(double centre = 0) : centre_(centre) {}
  void add(double x, double y, double se = 0) {
    const double w = se > 0 ? 1 / (se * se) : 1, u = x - centre_;
    double p = w;
    for (int k = 0; k < 5; ++k, p *= u) s_[k] += p;
    t_[0] += w * y, t_[1] += w * u * y, t_[2] += w * u * u * y;
  }
  double value(double x) const { return dot(basis(x), parameters()); }
  double slope(double x) const { return dot(slope_basis(x), parameters()); }
  double curvature() const { return 2 * parameters()[2]; } // y''
  double value_stderr(double x) const { return spread(basis(x)); }
  double slope_stderr(double x) const { return spread(slope_basis(x)); }
  double curvature_stderr() const { return spread({0, 0, 2}); }

private:
  using Vec = std::array<double, 3>;
  using Mat = std::array<Vec, 3>;
  static double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  Vec basis(double x) const {
    const double u = x - centre_;
    return {1, u, u * u};
  }
  Vec slope_basis(double x) const { return {0, 1, 2 * (x - centre_)}; }
  // The covariance: the inverse of the normal matrix M_ij = sum w u^(i+j), by cofactors.
  Mat covariance() const {
    const Mat m{{{s_[0], s_[1], s_[2]}, {s_[1], s_[2], s_[3]}, {s_[2], s_[3], s_[4]}}};
    Mat c{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        c[i][j] = m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1];
      }
    const double det = m[0][0] * c[0][0] + m[0][1] * c[1][0] + m[0][2] * c[2][0];
    for (auto& row : c)
      for (double& v : row) v /= det;
    return c;
  }
  Vec parameters() const {
    const Mat c = covariance();
    return {dot(c[0], t_), dot(c[1], t_), dot(c[2], t_)};
  }
  double spread(const Vec& v) const { // sqrt(v^T C v)
    const Mat c = covariance();
    return std::sqrt(dot(v, {dot(c[0], v), dot(c[1], v), dot(c[2], v)}));
  }
  double centre_;
  std::array<double, 5> s_{}; // sum w u^k
  Vec t_{};                   // sum w u^k y
};

} // namespace twinflow::statistics
