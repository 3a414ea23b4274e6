#pragma once
// A straight line y = a + b x by weighted least squares (Numerical Recipes, 3rd ed., sec. 15.2):
// weights 1/se^2, or 1 where no error is given; slope and intercept with their standard errors.

#include <cmath>

namespace twinflow::statistics {

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

} // namespace twinflow::statistics
