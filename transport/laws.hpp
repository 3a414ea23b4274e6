#pragma once
// A transport coefficient as a function of the local state, in the form kinetic theory gives it
// (docs/theory.md, "Coefficients against n and T"): a part carried by moving particles, whose
// mean free path goes as 1/n so that it does not depend on n, and a part carried by the pair
// terms (friction for eta, heat conduction for kappa), which goes as n^2 (Marsh, Backx & Ernst
// 1997; 000:(3.25)-(3.26)):
//   c(n, T) = K (T / T0)^a + P (n / n0)^2 (T / T0)^b.
// b comes from the pair integrals (transport/estimates.hpp), and so does P for kappa; K and a from
// measurements without walls: kappa along a periodic heat-slab profile (kappa_law), eta from
// relaxation runs at the state point and at the isobar's ends (the walls' n and T), which also
// fix its P (viscosity_law; theory's pair part overstates eta by 40% at the default cavity's cold
// wall, docs/notebook/2026-11-27-prediction-suite-and-eta-along-the-isobar.md), else through the
// state point alone with a the exponent of D(T).

#include <vector>

#include "io/json.hpp"
#include "statistics/blocking.hpp"

namespace twinflow::transport {

struct CoefficientLaw {
  double T0 = 1, n0 = 1;      // the reference state (the transport stage's state point)
  double K = 0, K_stderr = 0; // the particles' part at (n0, T0)
  double a = 0, a_stderr = 0; // its power of T
  double P = 0, P_stderr = 0; // the pair part at (n0, T0) (theory, or fitted: fit_law_and_pair)
  double b = 0;               // its power of T (theory)
  // fit_law_and_pair's covariances of K, P and a (else K's error alone enters stderr_at)
  bool has_covariance = false;
  double K_P_covariance = 0, K_a_covariance = 0, P_a_covariance = 0;
  double chi2_per_dof = 0; // of the fit that gave K and a (0: not fitted, or dof 0)
  int points = 0;
  double at(double n, double T) const;
  // The error of at(n0, T): with the covariances, of K (T/T0)^a + P (T/T0)^b through its
  // gradient (t^a, t^b, K t^a ln t), else K's error times t^a.
  double stderr_at(double T) const;
  // The law as json() wrote it (laws of older measurements: no covariances).
  static CoefficientLaw from_json(const io::Json& j);
  double pair_fraction(double T) const; // P (T/T0)^b / c(n0, T)
  io::Json json() const;
};

// One local measurement of a coefficient: its value and error at (n, T).
struct StatePoint {
  double n = 0, T = 0;
  statistics::Estimate value;
};

// K and a by weighted least squares through `points` (P, b given): for each a the best K is
// linear; a by golden-section search on [-3, 5]; errors from chi^2's curvature, scaled by
// sqrt(chi^2 / dof) when that exceeds 1. With a temperature span under 10% a is not fitted:
// `a_fallback` is taken and K's error is the points' mean error.
CoefficientLaw fit_law(const std::vector<StatePoint>& points, double n0, double T0, double P,
                       double b, double a_fallback);

// K, a and P by weighted least squares through `points` (b given; at least three points at two
// or more densities): for each a, K and P are linear; a by golden-section search on [-3, 5]; the
// errors and K and P's covariance from the linearised model at the minimum, scaled by
// sqrt(chi^2 / dof) when that exceeds 1 (three points: an exact fit, dof 0, no scaling).
CoefficientLaw fit_law_and_pair(const std::vector<StatePoint>& points, double n0, double T0,
                                double b);

// K from one measured value at (n0, T) with a given (the pair part's P, b theory's).
CoefficientLaw law_through(const statistics::Estimate& value, double T, double n0, double T0,
                           double P, double b, double a, double a_stderr);

} // namespace twinflow::transport
